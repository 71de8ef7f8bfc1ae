//! `rollbeam._native`: the Rust core seen from Python, nothing computed here. Every function
//! takes a scene as its text with the values set on it (what `rollbeam.Scene` holds, so a
//! scene pickles as text) and calls the same library functions as the command line; the
//! Python layer (`rollbeam/__init__.py`) turns the answers into dicts and numpy arrays.
//! Runs release the GIL.

use std::path::{Path, PathBuf};

use pyo3::exceptions::{PyException, PyOSError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes};

use rollbeam::commands::check::Described;
use rollbeam::error::{short_numbers, Error};
use rollbeam::output;
use rollbeam::plan::Planner;
use rollbeam::run::{self as core_run, Overrides, Run};
use rollbeam::scene::{BeamScene, Scene, SceneSpec};
use rollbeam::workflows::analyses::{default_mode_count, natural_modes, static_solution};
use rollbeam::workflows::settings::solver_overrides;
use rollbeam::workflows::sweep::cluster::{self, Record};
use rollbeam::workflows::sweep::{self, Value};
use rollbeam::workflows::tradeoff::{run_tradeoff, TradeoffOptions};

pyo3::create_exception!(_native, SceneError, PyException);
pyo3::create_exception!(_native, SolverError, PyException);

/// The command line's sentence, as the matching Python exception.
fn py_err(e: Error) -> PyErr {
    let sentence = short_numbers(&e.to_string()).replace('\n', " ");
    match e {
        Error::Input(_) => SceneError::new_err(sentence),
        Error::Solver(_) => SolverError::new_err(sentence),
        Error::Output(_) => PyOSError::new_err(sentence),
    }
}

/// A scene as the Python `Scene` holds it.
#[derive(Clone, FromPyObject)]
struct SceneText {
    #[pyo3(attribute("_text"))]
    text: String,
    #[pyo3(attribute("_source"))]
    source: String,
    #[pyo3(attribute("_stem"))]
    stem: String,
    /// False for a scene dict: its text is JSON the package wrote, whose lines no one saw.
    #[pyo3(attribute("_lined"))]
    lined: bool,
    #[pyo3(attribute("_values"))]
    values: Vec<(String, ValueArg)>,
}

/// A value set at a key: a number, or a name (`True`/`False` as the scene format's names).
#[derive(Clone)]
struct ValueArg(Value);

impl<'a, 'py> FromPyObject<'a, 'py> for ValueArg {
    type Error = PyErr;

    fn extract(ob: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if let Ok(b) = ob.cast::<PyBool>() {
            return Ok(ValueArg(Value::Name(b.is_true().to_string())));
        }
        if let Ok(x) = ob.extract::<f64>() {
            return Ok(ValueArg(Value::Number(x)));
        }
        if let Ok(s) = ob.extract::<String>() {
            return Ok(ValueArg(Value::Name(s)));
        }
        Err(SceneError::new_err(format!(
            "a value must be a number or a name (got {})",
            ob.repr()
                .map_or_else(|_| "?".to_string(), |r| r.to_string())
        )))
    }
}

impl SceneText {
    fn spec(&self) -> Result<SceneSpec, Error> {
        let read = if self.lined {
            SceneSpec::parse
        } else {
            SceneSpec::parse_unlined
        };
        let mut spec = read(&self.text, &self.source, &self.stem)?;
        for (key, v) in &self.values {
            sweep::apply(&mut spec, key, &v.0)
                .map_err(|e| Error::Input(format!("{}: {e}", self.source)))?;
        }
        Ok(spec)
    }

    fn scene(&self) -> Result<Scene, Error> {
        Planner::default().plan(&self.spec()?)
    }
}

fn beam_of<'a>(scene: &'a Scene, what: &str) -> Result<&'a BeamScene, Error> {
    scene.beam().ok_or_else(|| {
        Error::Input(format!(
            "scene {}: `{what}` needs a beam track; this scene has a rigid curve",
            scene.name
        ))
    })
}

fn bytes<'py>(py: Python<'py>, v: impl IntoIterator<Item = f64>) -> Bound<'py, PyBytes> {
    let raw: Vec<u8> = v.into_iter().flat_map(f64::to_ne_bytes).collect();
    PyBytes::new(py, &raw)
}

/// Check and plan the scene; its name, or the scene file's error.
#[pyfunction]
fn plan(scene: SceneText) -> PyResult<String> {
    scene.scene().map(|s| s.name).map_err(py_err)
}

/// The scene as a scene file, its values written in.
#[pyfunction]
fn to_yaml(scene: SceneText) -> PyResult<String> {
    scene.spec().and_then(|s| s.to_yaml()).map_err(py_err)
}

/// What `rollbeam check` prints.
#[pyfunction]
fn check(scene: SceneText) -> PyResult<String> {
    let s = scene.scene().map_err(py_err)?;
    Ok(short_numbers(Described(&s).to_string().trim_end()))
}

/// One run's results, kept in Rust until asked for.
#[pyclass(unsendable)]
struct NativeRun {
    run: Run,
    /// `summary.yaml`'s and `history.csv`'s texts, formed once where the run was checked.
    summary: String,
    history: String,
}

#[pymethods]
impl NativeRun {
    fn summary_yaml(&self) -> String {
        self.summary.clone()
    }

    /// The columns of history.csv: (name, float64 bytes), an empty cell as NaN.
    fn history<'py>(&self, py: Python<'py>) -> Vec<(String, Bound<'py, PyBytes>)> {
        let mut lines = self.history.lines();
        let names: Vec<String> = lines
            .next()
            .unwrap_or("")
            .split(',')
            .map(String::from)
            .collect();
        let mut columns = vec![Vec::new(); names.len()];
        for line in lines {
            for (c, cell) in columns.iter_mut().zip(line.split(',')) {
                c.push(cell.parse::<f64>().unwrap_or(f64::NAN));
            }
        }
        names
            .into_iter()
            .zip(columns)
            .map(|(n, c)| (n, bytes(py, c)))
            .collect()
    }

    /// Beam runs: (x, times, u, w, φ), the last three row-major over (time, x).
    #[allow(clippy::type_complexity)]
    fn shapes<'py>(&self, py: Python<'py>) -> Option<Vec<Bound<'py, PyBytes>>> {
        let Run::Beam(b) = &self.run else { return None };
        let all = || b.shapes.iter().flat_map(|(_, d)| d.iter());
        Some(vec![
            bytes(py, b.envelope.x.iter().copied()),
            bytes(py, b.shapes.iter().map(|(t, _)| *t)),
            bytes(py, all().map(|d| d.u)),
            bytes(py, all().map(|d| d.w)),
            bytes(py, all().map(|d| d.phi)),
        ])
    }

    /// Beam runs: x and the extremes of u, w and φ over the run at each x.
    fn envelope<'py>(&self, py: Python<'py>) -> Option<Vec<(String, Bound<'py, PyBytes>)>> {
        let Run::Beam(b) = &self.run else { return None };
        let e = &b.envelope;
        Some(vec![
            ("x".into(), bytes(py, e.x.iter().copied())),
            ("u_min".into(), bytes(py, e.min.iter().map(|d| d.u))),
            ("u_max".into(), bytes(py, e.max.iter().map(|d| d.u))),
            ("w_min".into(), bytes(py, e.min.iter().map(|d| d.w))),
            ("w_max".into(), bytes(py, e.max.iter().map(|d| d.w))),
            ("phi_min".into(), bytes(py, e.min.iter().map(|d| d.phi))),
            ("phi_max".into(), bytes(py, e.max.iter().map(|d| d.phi))),
        ])
    }

    /// Write exactly what `rollbeam run` writes into `dir` (the figures where asked).
    #[pyo3(signature = (dir, figures=true))]
    fn write(&self, py: Python<'_>, dir: PathBuf, figures: bool) -> PyResult<()> {
        let run = &self.run;
        py.detach(|| output::write_all(run, &dir, figures))
            .map_err(py_err)
    }
}

/// Run the scene; the integrator settings override the scene's.
#[pyfunction]
#[pyo3(signature = (scene, method=None, rtol=None, atol=None))]
fn run(
    py: Python<'_>,
    scene: SceneText,
    method: Option<String>,
    rtol: Option<f64>,
    atol: Option<f64>,
) -> PyResult<NativeRun> {
    let s = scene.scene().map_err(py_err)?;
    let over = solver_overrides(&s, method.as_deref(), rtol, atol).map_err(py_err)?;
    let (run, (summary, history)) = py
        .detach(|| {
            let run = core_run::run(&s, &over, false)?;
            output::finite_tables(&run).map(|texts| (run, texts))
        })
        .map_err(py_err)?;
    Ok(NativeRun {
        run,
        summary,
        history,
    })
}

/// `static.yaml`'s text.
#[pyfunction]
fn static_yaml(py: Python<'_>, scene: SceneText) -> PyResult<String> {
    let s = scene.scene().map_err(py_err)?;
    py.detach(|| {
        let setup = beam_of(&s, "static")?;
        output::yaml(&static_solution(&s, setup)?)
    })
    .map_err(py_err)
}

/// (frequencies in Hz, x, u, w, φ), the shapes row-major over (mode, x), mass-normalised.
#[pyfunction]
#[pyo3(signature = (scene, count=None, samples=200))]
fn modes<'py>(
    py: Python<'py>,
    scene: SceneText,
    count: Option<usize>,
    samples: usize,
) -> PyResult<Vec<Bound<'py, PyBytes>>> {
    let s = scene.scene().map_err(py_err)?;
    if samples == 0 || samples > 100_000 {
        return Err(SceneError::new_err(format!(
            "samples must be from 1 to 100000 (got {samples})"
        )));
    }
    let m = py
        .detach(|| {
            let setup = beam_of(&s, "modes")?;
            let count = count.unwrap_or_else(|| default_mode_count(setup));
            natural_modes(&s, setup, count, samples)
        })
        .map_err(py_err)?;
    let all = || m.shapes.iter().flat_map(|mode| mode.iter());
    Ok(vec![
        bytes(py, m.hz.iter().copied()),
        bytes(py, m.xs.iter().copied()),
        bytes(py, all().map(|d| d.u)),
        bytes(py, all().map(|d| d.w)),
        bytes(py, all().map(|d| d.phi)),
    ])
}

/// Work–precision into `dir` (tradeoff.csv, .svg, .txt); the lines `rollbeam tradeoff`
/// prints. `file` is the scene file a stored reference sits beside, if any.
#[pyfunction]
#[pyo3(signature = (scene, dir, file=None, methods=vec![], rtols=vec![], elements=vec![], orders=vec![], models=vec![], max_steps=None))]
#[allow(clippy::too_many_arguments)]
fn tradeoff(
    py: Python<'_>,
    scene: SceneText,
    dir: PathBuf,
    file: Option<PathBuf>,
    methods: Vec<String>,
    rtols: Vec<f64>,
    elements: Vec<usize>,
    orders: Vec<usize>,
    models: Vec<String>,
    max_steps: Option<usize>,
) -> PyResult<Vec<String>> {
    let s = scene.scene().map_err(py_err)?;
    let options = TradeoffOptions {
        methods,
        rtols,
        elements,
        orders,
        models,
        max_steps,
        points: Vec::new(),
        recompute: false,
        recompute_means: false,
    };
    // The command that stores a reference for `file`; the package never stores one.
    let made_by = match &file {
        Some(f) => format!("rollbeam tradeoff {} --reference", f.display()),
        None => format!("rollbeam.tradeoff({})", scene.source),
    };
    py.detach(|| run_tradeoff(&s, file.as_deref(), &options, &dir, &made_by, false).map(|(_, l)| l))
        .map_err(py_err)
}

fn cases_of(cases: Vec<Vec<ValueArg>>) -> Vec<Vec<Value>> {
    cases
        .into_iter()
        .map(|c| c.into_iter().map(|v| v.0).collect())
        .collect()
}

/// The scene as written, and the integrator settings checked against its plan.
fn with_overrides(
    scene: &SceneText,
    method: Option<&str>,
    rtol: Option<f64>,
    atol: Option<f64>,
) -> PyResult<(SceneSpec, Overrides)> {
    let spec = scene.spec().map_err(py_err)?;
    let over = Planner::default()
        .plan(&spec)
        .and_then(|planned| solver_overrides(&planned, method, rtol, atol))
        .map_err(py_err)?;
    Ok((spec, over))
}

/// Whether every value can be set at its key (the scene is not planned): a key the scene
/// cannot hold, or a value it cannot take, is the sweep's error rather than every case's.
#[pyfunction]
fn settable(scene: SceneText, keys: Vec<String>, values: Vec<Vec<ValueArg>>) -> PyResult<()> {
    let spec = scene.spec().map_err(py_err)?;
    for (key, vs) in keys.iter().zip(values) {
        for v in vs {
            sweep::apply(&mut spec.clone(), key, &v.0)
                .map_err(|e| py_err(Error::Input(format!("sweep over {key}: {e}"))))?;
        }
    }
    Ok(())
}

/// Every case on this machine's cores; the text of sweep.csv.
#[pyfunction]
#[pyo3(signature = (scene, keys, cases, method=None, rtol=None, atol=None))]
fn sweep_cases(
    py: Python<'_>,
    scene: SceneText,
    keys: Vec<String>,
    cases: Vec<Vec<ValueArg>>,
    method: Option<String>,
    rtol: Option<f64>,
    atol: Option<f64>,
) -> PyResult<String> {
    let (spec, over) = with_overrides(&scene, method.as_deref(), rtol, atol)?;
    let cases = cases_of(cases);
    let rows = py.detach(|| sweep::run_cases(&spec, &keys, &cases, &over, false));
    Ok(sweep::sweep_csv(&rows, &keys))
}

/// One case; its record (the text `done/<id>.yaml` of a planned sweep holds).
#[pyfunction]
#[pyo3(signature = (scene, keys, values, method=None, rtol=None, atol=None))]
fn run_case(
    py: Python<'_>,
    scene: SceneText,
    keys: Vec<String>,
    values: Vec<ValueArg>,
    method: Option<String>,
    rtol: Option<f64>,
    atol: Option<f64>,
) -> PyResult<String> {
    let (spec, over) = with_overrides(&scene, method.as_deref(), rtol, atol)?;
    let values: Vec<Value> = values.into_iter().map(|v| v.0).collect();
    let outcome = py.detach(|| sweep::run_case(&spec, &keys, &values, &over));
    Record::of(&sweep::row((values, outcome)))
        .to_yaml()
        .map_err(py_err)
}

/// The text of sweep.csv from the cases' records, in their order.
#[pyfunction]
fn merge(keys: Vec<String>, records: Vec<String>) -> PyResult<String> {
    let records = records
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let source = format!("case {i}");
            Record::from_yaml(r, &source).map(|r| (source, r))
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(py_err)?;
    let rows = cluster::rows(&records, keys.len()).map_err(py_err)?;
    Ok(sweep::sweep_csv(&rows, &keys))
}

/// Whether `path` names a file (a scene given as a path rather than as text).
#[pyfunction]
fn is_file(path: &str) -> bool {
    path.len() < 4096 && !path.contains('\n') && Path::new(path).is_file()
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add("SolverError", m.py().get_type::<SolverError>())?;
    m.add_class::<NativeRun>()?;
    for f in [
        wrap_pyfunction!(plan, m)?,
        wrap_pyfunction!(to_yaml, m)?,
        wrap_pyfunction!(check, m)?,
        wrap_pyfunction!(run, m)?,
        wrap_pyfunction!(static_yaml, m)?,
        wrap_pyfunction!(modes, m)?,
        wrap_pyfunction!(tradeoff, m)?,
        wrap_pyfunction!(settable, m)?,
        wrap_pyfunction!(sweep_cases, m)?,
        wrap_pyfunction!(run_case, m)?,
        wrap_pyfunction!(merge, m)?,
        wrap_pyfunction!(is_file, m)?,
    ] {
        m.add_function(f)?;
    }
    Ok(())
}

//! The scene file (see SCENE-FORMAT in the README): read with locations into a [`SceneSpec`]
//! (what the user wrote, which a typed [`SceneSpec::set`] may change key by key), and checked
//! into the model it names, and only that; nothing is chosen or computed here beyond what the
//! check needs. What the scene leaves out is chosen by the planning step (`plan.rs`). Every
//! problem is reported as one sentence with the file, the line and the key.

use std::path::Path;

use serde::{Deserialize, Serialize};
use serde_saphyr::{Location, Spanned};

use crate::analysis::discretisation::{
    jumps, weight_drops, Discretisation, DEFAULT_ACCURACY, DEFAULT_ORDER,
};
use crate::beam::damping::DampingSpec;
use crate::beam::element::Section;
use crate::beam::load::{BeamStart, PointLoad, Probe};
use crate::beam::supports::{mesh_multiple, statically_supported, Support};
use crate::beam::train::{hslm, Train, TrainModel, HSLM_NAMES};
use crate::beam::{BeamModel, BeamSpec, Quadrature, MAX_ORDER};
use crate::coupling::{patch, Coupling, DiskOnBeamSpec};
use crate::curve::expr::Formula;
use crate::curve::spline::Spline;
use crate::curve::Curve;
use crate::disk::Disk;
use crate::error::{quote, Error};
use crate::ode::Method;
use crate::rolling::{ContactLoss, Rolling};

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    name: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    gravity: Option<Spanned<f64>>,
    duration: Spanned<f64>,
    track: Spanned<TrackFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    disk: Option<Spanned<DiskFile>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    train: Option<Spanned<TrainFile>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    loads: Option<Spanned<Vec<Spanned<LoadFile>>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    solver: Option<SolverFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    output: Option<OutputFile>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct TrackFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    curve: Option<Spanned<CurveFile>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    beam: Option<Spanned<BeamFile>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
struct BeamFile {
    from: Spanned<[f64; 2]>,
    to: Spanned<[f64; 2]>,
    E: Spanned<f64>,
    G: Spanned<f64>,
    rho: Spanned<f64>,
    A: Spanned<f64>,
    Av: Spanned<f64>,
    I: Spanned<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    depth: Option<Spanned<f64>>,
    supports: Spanned<SupportsFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    elements: Option<Spanned<i64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    order: Option<Spanned<i64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    quadrature: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    initial: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    model: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    modes: Option<Spanned<i64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    damping: Option<Spanned<DampingFile>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    self_weight: Option<Spanned<bool>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct TrainFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    hslm: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    axles: Option<Spanned<Vec<f64>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    load: Option<Spanned<AxleLoads>>,
    speed: Spanned<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    model: Option<Spanned<String>>,
}

/// One force for every axle, or one each.
#[derive(Clone, Deserialize, Serialize)]
#[serde(untagged)]
enum AxleLoads {
    Each(Vec<f64>),
    All(f64),
}

#[derive(Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct DampingFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    ratio: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    modes: Option<Spanned<Vec<i64>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    alpha: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    beta: Option<Spanned<f64>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct SupportsFile {
    from: Spanned<String>,
    to: Spanned<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    intermediate: Option<Spanned<Vec<Spanned<f64>>>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct LoadFile {
    x: Spanned<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    fx: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    fy: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mz: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    from: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    until: Option<Spanned<f64>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct ProbeFile {
    name: Spanned<String>,
    x: Spanned<f64>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct CurveFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    parabola: Option<ParabolaFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    line: Option<LineFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    expr: Option<ExprFile>,
    #[serde(skip_serializing_if = "Option::is_none")]
    points: Option<Spanned<Vec<Spanned<[f64; 2]>>>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct ParabolaFile {
    k: Spanned<f64>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct LineFile {
    from: Spanned<[f64; 2]>,
    to: Spanned<[f64; 2]>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct ExprFile {
    x: Spanned<String>,
    y: Spanned<String>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct DiskFile {
    mass: Spanned<f64>,
    radius: Spanned<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    s0: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    omega0: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    coupling: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    formulation: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mu: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    patch: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    contact_loss: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    restitution: Option<Spanned<f64>>,
}

#[derive(Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct SolverFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    method: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rtol: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    atol: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rho_inf: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    accuracy: Option<Spanned<f64>>,
}

#[derive(Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct OutputFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    interval: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    probes: Option<Spanned<Vec<Spanned<ProbeFile>>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    shapes: Option<Spanned<Vec<Spanned<f64>>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    magnify: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    acceleration_cutoff_hz: Option<Spanned<f64>>,
}

/// How the disk on a rigid curve is formulated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formulation {
    Minimal,
    Thesis,
}

impl Formulation {
    pub fn name(self) -> &'static str {
        match self {
            Formulation::Minimal => "minimal",
            Formulation::Thesis => "thesis",
        }
    }
}

#[derive(Clone, Debug)]
pub struct SolverSettings {
    pub method: Method,
    pub rtol: f64,
    pub atol: f64,
    /// Why rtol is what it is, where it was left out and the planner chose it from the beam
    /// scene's accuracy.
    pub rtol_chosen: Option<String>,
    /// atol was left out with rtol: it is rtol times this size of the response (m).
    pub atol_scale: Option<f64>,
    /// Why, where it was.
    pub atol_chosen: Option<String>,
}

/// A disk on a rigid curve.
#[derive(Clone, Debug)]
pub struct RollingScene {
    pub rolling: Rolling,
    pub formulation: Formulation,
}

/// A flexible beam under point loads.
#[derive(Clone, Debug)]
pub struct BeamScene {
    pub beam: BeamSpec,
    pub start: BeamStart,
    /// A disk riding on the beam, if the scene has one.
    pub disk: Option<DiskOnBeamSpec>,
    /// A train of axle loads crossing the beam, if the scene has one (never with a disk).
    pub train: Option<Train>,
    pub loads: Vec<PointLoad>,
    pub probes: Vec<Probe>,
    pub shapes: Vec<f64>,
    pub magnify: f64,
    /// Spectral radius at infinity of generalized-α.
    pub rho_inf: f64,
    /// Why ρ∞ is what it is, when the plan chose it (`plan::rho_inf_for`).
    pub rho_inf_chosen: Option<String>,
    /// Relative accuracy asked of the peak deflection: what the mesh and tolerances are
    /// chosen from when the scene leaves them out.
    pub accuracy: f64,
    /// The mesh the plan chose for the scene, when it left elements or order out.
    pub discretisation: Option<Discretisation>,
    /// Why the beam has the model it has, when the plan chose it (or its modes).
    pub model_choice: Option<String>,
    /// The frequency (Hz) above which the modes are left out of the recorded accelerations;
    /// `None`: EN 1991-2's max(30 Hz, 1.5 f1, f3).
    pub acceleration_cutoff_hz: Option<f64>,
    /// The size of the displacements its loads cause (m), when the supports allow a static
    /// estimate: see `analysis::discretisation::response_size`. Set by the plan.
    pub response: Option<f64>,
}

impl BeamScene {
    /// Whether a load is switched on or off during the run, the beam's own weight included
    /// where it drops on a beam that starts undeformed: it then excites every mode the mesh
    /// holds.
    pub fn load_switched(&self) -> bool {
        jumps(&self.loads, self.start) || weight_drops(&self.beam, self.start)
    }
}

/// The shortest contact patch, and section depth, against the beam's length: below it the
/// patch's kernel (of height 1/b) and the kink's curvature (θ/b) leave floating point.
const MIN_PATCH_PER_LENGTH: f64 = 1e-6;

impl BeamScene {
    /// How much the disk's results depend on its contact patch (see `coupling::patch`): its
    /// weight's kink in the axis, at the fastest it can roll (its start speed, plus what the
    /// drop of the axis from its start can add), against the response size.
    pub fn patch_sensitivity(&self) -> Option<patch::Sensitivity> {
        let d = self.disk.as_ref()?;
        let weight = d.disk.mass * d.gravity;
        let (from, to) = (self.beam.from, self.beam.to);
        let length = (to[0] - from[0]).hypot(to[1] - from[1]);
        let start_y = from[1] + (to[1] - from[1]) * d.s0 / length;
        let drop = (start_y - from[1].min(to[1])).max(0.0);
        let speed = (d.v0() * d.v0() + 2.0 * d.gravity * drop).sqrt();
        Some(patch::Sensitivity::of(
            &self.beam.section,
            weight,
            d.gravity,
            speed,
            d.patch,
            self.response.unwrap_or(f64::INFINITY),
        ))
    }

    /// What the results depend on beyond the accuracy asked, one sentence each.
    pub fn warnings(&self) -> Vec<String> {
        self.patch_sensitivity()
            .map_or_else(Vec::new, |s| s.warnings(self.accuracy))
    }
}

/// What the scene models, and only that.
#[derive(Clone, Debug)]
pub enum Model {
    Rolling(RollingScene),
    Beam(BeamScene),
}

/// A checked scene: everything the run needs, nothing it does not.
#[derive(Clone, Debug)]
pub struct Scene {
    pub name: String,
    pub duration: f64,
    pub model: Model,
    pub solver: SolverSettings,
    /// Time between rows of history.csv.
    pub interval: f64,
}

impl Scene {
    pub fn rolling(&self) -> Option<&RollingScene> {
        match &self.model {
            Model::Rolling(r) => Some(r),
            Model::Beam(_) => None,
        }
    }

    pub fn beam(&self) -> Option<&BeamScene> {
        match &self.model {
            Model::Beam(b) => Some(b),
            Model::Rolling(_) => None,
        }
    }
}

pub const DEFAULT_GRAVITY: f64 = 9.81;
/// Finest `solver.accuracy`: with a switched load its rtol is a thousandth of it, 1e-11.
const MIN_ACCURACY: f64 = 1e-8;
/// Rows of history.csv a run may write.
const MAX_ROWS: f64 = 1e6;
/// Mesh nodes a beam may have (three unknowns each): its sparse factor then takes some
/// hundred megabytes, and one solve about a second.
const MAX_NODES: f64 = 100_001.0;
/// Intermediate bearings must sit at nodes of a uniform mesh of at most this many elements.
const MAX_SPANS: usize = 1000;
/// Most axles a train may have: every one is a load the beam reads at every evaluation.
const MAX_AXLES: usize = 10_000;
/// Most moving-mass axles on the deck at one time.
const MAX_MASSES_ON_DECK: usize = 100;

/// The most of the increasing positions `x` that fit in one window of length `span`.
fn most_within(x: &[f64], span: f64) -> usize {
    let mut first = 0;
    let mut most = 0;
    for (last, &xl) in x.iter().enumerate() {
        while xl - x[first] > span {
            first += 1;
        }
        most = most.max(last + 1 - first);
    }
    most
}
use crate::beam::modal::MAX_MODES;

/// Reports problems as "FILE line N: KEY ...".
struct Checker<'a> {
    file: &'a str,
}

impl Checker<'_> {
    /// Line 0 is a value that was set rather than read from the file.
    fn err<T>(&self, line: u64, key: &str, msg: impl std::fmt::Display) -> Result<T, Error> {
        Err(Error::Input(if line == 0 {
            format!("{}: `{key}` {msg}", self.file)
        } else {
            format!("{} line {line}: `{key}` {msg}", self.file)
        }))
    }

    fn finite(&self, v: &Spanned<f64>, key: &str) -> Result<f64, Error> {
        if !v.value.is_finite() {
            return self.err(
                v.referenced.line(),
                key,
                format!("must be a finite number, not {}", v.value),
            );
        }
        Ok(v.value)
    }

    fn positive(&self, v: &Spanned<f64>, key: &str) -> Result<f64, Error> {
        let x = self.finite(v, key)?;
        if x <= 0.0 {
            return self.err(
                v.referenced.line(),
                key,
                format!("must be positive (got {x})"),
            );
        }
        Ok(x)
    }

    /// A length of the section or the contact (m): positive, at least a millionth of the beam's
    /// length `length` and at most all of it; `short` says what a shorter one would be, and
    /// `long` how a longer one exceeds the beam and why that cannot be.
    fn part_of_length(
        &self,
        v: &Spanned<f64>,
        key: &str,
        length: f64,
        short: &str,
        long: (&str, &str),
    ) -> Result<f64, Error> {
        let x = self.positive(v, key)?;
        let line = v.referenced.line();
        if x < MIN_PATCH_PER_LENGTH * length {
            return self.err(line, key, format!("= {x:e} m is below a millionth of the beam's length (L = {length:e} m): {short}"));
        }
        if x > length {
            return self.err(
                line,
                key,
                format!("= {x:e} m {} (L = {length:e} m): {}", long.0, long.1),
            );
        }
        Ok(x)
    }

    /// A quantity derived from the scene's values (a length, a stiffness, an inertia) that the
    /// model divides by or squares: it must be a normal positive double, neither overflowed
    /// to infinity nor underflowed towards zero by extreme inputs.
    fn derived(&self, line: u64, key: &str, what: &str, v: f64) -> Result<f64, Error> {
        if v.is_normal() && v > 0.0 {
            return Ok(v);
        }
        self.err(
            line,
            key,
            format!(
                "makes {what} {}, which is not a finite positive number a double holds; the values are too extreme",
                if v.is_finite() { format!("= {v:e}") } else { "infinite".into() }
            ),
        )
    }

    /// The disk of a scene, its mass, radius and what the model derives from them.
    fn disk(&self, d: &DiskFile, gravity: f64) -> Result<Disk, Error> {
        let disk = Disk {
            mass: self.positive(&d.mass, "disk.mass")?,
            radius: self.positive(&d.radius, "disk.radius")?,
        };
        let line = d.radius.referenced.line();
        self.derived(
            line,
            "disk.radius",
            "the disk's moment of inertia C = m a²/2",
            disk.inertia(),
        )?;
        self.derived(
            line,
            "disk.radius",
            "the disk's rolling mass m + C/a²",
            disk.rolling_mass(),
        )?;
        if gravity != 0.0 {
            self.derived(
                d.mass.referenced.line(),
                "disk.mass",
                "the disk's weight m |g|",
                disk.mass * gravity.abs(),
            )?;
        }
        Ok(disk)
    }

    fn pair(&self, v: &Spanned<[f64; 2]>, key: &str) -> Result<[f64; 2], Error> {
        if v.value.iter().any(|x| !x.is_finite()) {
            return self.err(
                v.referenced.line(),
                key,
                format!("must hold finite numbers, not {:?}", v.value),
            );
        }
        Ok(v.value)
    }
}

/// A scene as written: the file's values with their lines, nothing chosen. [`SceneSpec::set`]
/// changes one of them by its dotted key, as `sweep --set` and the tests do; checking and
/// planning it again gives the changed scene.
#[derive(Clone)]
pub struct SceneSpec {
    file: SceneFile,
    /// Names the source in messages.
    source: String,
    /// The default scene name.
    stem: String,
}

/// A checked scene, not yet planned: what only the planning step (`plan.rs`) turns into a
/// [`Scene`], choosing what the scene left out.
pub struct Checked {
    /// The scene with the mesh and tolerances as given, or provisional where left out.
    pub scene: Scene,
    /// Element count and degree as the scene gives them.
    pub elements: Option<usize>,
    pub order: Option<usize>,
    /// Element counts are kept to multiples of this, which puts a node at each bearing.
    pub multiple: usize,
    /// The scene names its beam model (the plan chooses it otherwise).
    pub model_given: bool,
    pub rtol_given: bool,
    pub atol_given: bool,
    /// The scene gives generalized-α's ρ∞ (the plan chooses it otherwise).
    pub rho_inf_given: bool,
}

/// Largest scene file read: a curve or profile of a million points, with room to spare.
pub const MAX_SCENE_BYTES: u64 = 64 << 20;

impl SceneSpec {
    pub fn load(path: &Path) -> Result<SceneSpec, Error> {
        let text = crate::files::read_text(path, MAX_SCENE_BYTES, "scene file")?;
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        SceneSpec::parse(&text, &path.display().to_string(), &stem)
    }

    /// Read and check; `source` names the source in messages, `stem` is the default scene name.
    pub fn parse(text: &str, source: &str, stem: &str) -> Result<SceneSpec, Error> {
        let file: SceneFile = serde_saphyr::from_str(text).map_err(|e| {
            let at = e.location().map(|l| (l.line(), l.column()));
            let sentence = crate::scene_error::describe(text, &e.to_string(), at);
            Error::Input(format!("{source} {sentence}"))
        })?;
        let spec = SceneSpec {
            file,
            source: source.into(),
            stem: stem.into(),
        };
        spec.check()?;
        Ok(spec)
    }

    /// The scene as a scene file: what it was read from with every [`SceneSpec::set`]
    /// applied. Reading the text back gives the same scene (a planned sweep's case files,
    /// the Python package's pickled scenes).
    pub fn to_yaml(&self) -> Result<String, Error> {
        serde_saphyr::to_string(&self.file)
            .map_err(|e| Error::Output(format!("cannot write the scene as YAML: {e}")))
    }

    /// The model the scene names, checked; mesh and tolerances as given.
    pub fn check(&self) -> Result<Checked, Error> {
        check(&self.file, &self.source, &self.stem)
    }

    /// Set the number at a dotted key of the scene format (`disk.omega0`, `track.beam.E`,
    /// `track.beam.elements`, …), whether or not the file gives it. The changed scene is not
    /// checked here: [`SceneSpec::check`] does that.
    pub fn set(&mut self, key: &str, value: f64) -> Result<(), Error> {
        let f = &mut self.file;
        let unset = |what: &str| {
            Err(Error::Input(format!(
                "`{key}` cannot be set: the scene has no {what}"
            )))
        };
        let number = |slot: &mut Spanned<f64>| slot.value = value;
        let option = |slot: &mut Option<Spanned<f64>>| match slot {
            Some(s) => s.value = value,
            None => *slot = Some(given(value)),
        };
        let whole = |slot: &mut Option<Spanned<i64>>| -> Result<(), Error> {
            if value.fract() != 0.0 || value.abs() > 1e15 {
                return Err(Error::Input(format!(
                    "`{key}` takes a whole number (got {value})"
                )));
            }
            let v = value as i64;
            match slot {
                Some(s) => s.value = v,
                None => *slot = Some(given(v)),
            }
            Ok(())
        };
        match key.split_once('.') {
            None => match key {
                "gravity" => option(&mut f.gravity),
                "duration" => number(&mut f.duration),
                _ => return Err(not_a_number(key)),
            },
            Some(("track", rest)) => match rest.split_once('.') {
                Some(("beam", field)) => {
                    let Some(b) = f.track.value.beam.as_mut() else {
                        return unset("beam track");
                    };
                    let b = &mut b.value;
                    match field {
                        "E" => number(&mut b.E),
                        "G" => number(&mut b.G),
                        "rho" => number(&mut b.rho),
                        "A" => number(&mut b.A),
                        "Av" => number(&mut b.Av),
                        "I" => number(&mut b.I),
                        "depth" => option(&mut b.depth),
                        "elements" => whole(&mut b.elements)?,
                        "order" => whole(&mut b.order)?,
                        "modes" => whole(&mut b.modes)?,
                        "damping.ratio" | "damping.alpha" | "damping.beta" => {
                            let d = &mut b
                                .damping
                                .get_or_insert_with(|| given(DampingFile::default()))
                                .value;
                            match field {
                                "damping.ratio" => option(&mut d.ratio),
                                "damping.alpha" => option(&mut d.alpha),
                                _ => option(&mut d.beta),
                            }
                        }
                        _ => return Err(not_a_number(key)),
                    }
                }
                Some(("curve", "parabola.k")) => {
                    match f
                        .track
                        .value
                        .curve
                        .as_mut()
                        .and_then(|c| c.value.parabola.as_mut())
                    {
                        Some(p) => number(&mut p.k),
                        None => return unset("parabola"),
                    }
                }
                _ => return Err(not_a_number(key)),
            },
            Some(("disk", field)) => {
                let Some(d) = f.disk.as_mut() else {
                    return unset("disk");
                };
                let d = &mut d.value;
                match field {
                    "mass" => number(&mut d.mass),
                    "radius" => number(&mut d.radius),
                    "s0" => option(&mut d.s0),
                    "omega0" => option(&mut d.omega0),
                    "mu" => option(&mut d.mu),
                    "patch" => option(&mut d.patch),
                    "restitution" => option(&mut d.restitution),
                    _ => return Err(not_a_number(key)),
                }
            }
            Some(("train", field)) => {
                let Some(t) = f.train.as_mut() else {
                    return unset("train");
                };
                match field {
                    "speed" => number(&mut t.value.speed),
                    _ => return Err(not_a_number(key)),
                }
            }
            Some(("solver", field)) => {
                let s = f.solver.get_or_insert_with(SolverFile::default);
                match field {
                    "rtol" => option(&mut s.rtol),
                    "atol" => option(&mut s.atol),
                    "rho_inf" => option(&mut s.rho_inf),
                    "accuracy" => option(&mut s.accuracy),
                    _ => return Err(not_a_number(key)),
                }
            }
            Some(("output", field)) => {
                let o = f.output.get_or_insert_with(OutputFile::default);
                match field {
                    "interval" => option(&mut o.interval),
                    "magnify" => option(&mut o.magnify),
                    "acceleration_cutoff_hz" => option(&mut o.acceleration_cutoff_hz),
                    _ => return Err(not_a_number(key)),
                }
            }
            _ => return Err(not_a_number(key)),
        }
        Ok(())
    }

    /// Leave out an optional key, so that its default applies (`output.shapes`, `solver.rtol`,
    /// `track.beam.elements`, …).
    pub fn unset(&mut self, key: &str) -> Result<(), Error> {
        let f = &mut self.file;
        let no = |what: &str| {
            Err(Error::Input(format!(
                "`{key}` cannot be left out: the scene has no {what}"
            )))
        };
        match key {
            "gravity" => f.gravity = None,
            "loads" => f.loads = None,
            "track.beam.elements"
            | "track.beam.order"
            | "track.beam.quadrature"
            | "track.beam.initial"
            | "track.beam.depth"
            | "track.beam.model"
            | "track.beam.modes"
            | "track.beam.damping"
            | "track.beam.self_weight" => {
                let Some(b) = f.track.value.beam.as_mut() else {
                    return no("beam track");
                };
                let b = &mut b.value;
                match key {
                    "track.beam.elements" => b.elements = None,
                    "track.beam.order" => b.order = None,
                    "track.beam.quadrature" => b.quadrature = None,
                    "track.beam.depth" => b.depth = None,
                    "track.beam.model" => b.model = None,
                    "track.beam.modes" => b.modes = None,
                    "track.beam.damping" => b.damping = None,
                    "track.beam.self_weight" => b.self_weight = None,
                    _ => b.initial = None,
                }
            }
            "disk.s0" | "disk.omega0" | "disk.mu" | "disk.patch" | "disk.coupling"
            | "disk.formulation" | "disk.contact_loss" | "disk.restitution" => {
                let Some(d) = f.disk.as_mut() else {
                    return no("disk");
                };
                let d = &mut d.value;
                match key {
                    "disk.s0" => d.s0 = None,
                    "disk.omega0" => d.omega0 = None,
                    "disk.mu" => d.mu = None,
                    "disk.patch" => d.patch = None,
                    "disk.coupling" => d.coupling = None,
                    "disk.contact_loss" => d.contact_loss = None,
                    "disk.restitution" => d.restitution = None,
                    _ => d.formulation = None,
                }
            }
            "solver.method" | "solver.rtol" | "solver.atol" | "solver.rho_inf"
            | "solver.accuracy" => {
                if let Some(s) = f.solver.as_mut() {
                    match key {
                        "solver.method" => s.method = None,
                        "solver.rtol" => s.rtol = None,
                        "solver.atol" => s.atol = None,
                        "solver.rho_inf" => s.rho_inf = None,
                        _ => s.accuracy = None,
                    }
                }
            }
            "output.interval"
            | "output.probes"
            | "output.shapes"
            | "output.magnify"
            | "output.acceleration_cutoff_hz" => {
                if let Some(o) = f.output.as_mut() {
                    match key {
                        "output.interval" => o.interval = None,
                        "output.probes" => o.probes = None,
                        "output.shapes" => o.shapes = None,
                        "output.magnify" => o.magnify = None,
                        _ => o.acceleration_cutoff_hz = None,
                    }
                }
            }
            _ => {
                return Err(Error::Input(format!(
                    "`{key}` is not an optional key of the scene format"
                )))
            }
        }
        Ok(())
    }

    /// Set the name at a dotted key of the scene format (`disk.coupling`, `solver.method`,
    /// `track.beam.quadrature`, …), whether or not the file gives it.
    pub fn set_name(&mut self, key: &str, value: &str) -> Result<(), Error> {
        let f = &mut self.file;
        let text = |slot: &mut Option<Spanned<String>>| match slot {
            Some(s) => s.value = value.into(),
            None => *slot = Some(given(value.to_string())),
        };
        match key {
            "name" => text(&mut f.name),
            "disk.coupling" | "disk.formulation" | "disk.contact_loss" => {
                let Some(d) = f.disk.as_mut() else {
                    return Err(Error::Input(format!(
                        "`{key}` cannot be set: the scene has no disk"
                    )));
                };
                match key {
                    "disk.coupling" => text(&mut d.value.coupling),
                    "disk.formulation" => text(&mut d.value.formulation),
                    _ => text(&mut d.value.contact_loss),
                }
            }
            "solver.method" => text(&mut f.solver.get_or_insert_with(SolverFile::default).method),
            "train.hslm" | "train.model" => {
                let Some(t) = f.train.as_mut() else {
                    return Err(Error::Input(format!(
                        "`{key}` cannot be set: the scene has no train"
                    )));
                };
                if key == "train.hslm" {
                    text(&mut t.value.hslm);
                    t.value.axles = None;
                    t.value.load = None;
                } else {
                    text(&mut t.value.model);
                }
            }
            "track.beam.self_weight" => {
                let Some(b) = f.track.value.beam.as_mut() else {
                    return Err(Error::Input(format!(
                        "`{key}` cannot be set: the scene has no beam track"
                    )));
                };
                let on = match value {
                    "true" => true,
                    "false" => false,
                    _ => {
                        return Err(Error::Input(format!(
                            "`{key}` is true or false (got {})",
                            quote(value)
                        )))
                    }
                };
                b.value.self_weight = Some(given(on));
            }
            "track.beam.quadrature" | "track.beam.initial" | "track.beam.model" => {
                let Some(b) = f.track.value.beam.as_mut() else {
                    return Err(Error::Input(format!(
                        "`{key}` cannot be set: the scene has no beam track"
                    )));
                };
                match key {
                    "track.beam.quadrature" => text(&mut b.value.quadrature),
                    "track.beam.model" => text(&mut b.value.model),
                    _ => text(&mut b.value.initial),
                }
            }
            _ => {
                return Err(Error::Input(format!(
                    "`{key}` does not take a name (a number key is swept as `{key}=FROM:TO:COUNT`); the keys that take names are name, disk.coupling, disk.formulation, disk.contact_loss, solver.method, train.hslm, train.model, track.beam.model, track.beam.quadrature, track.beam.initial and track.beam.self_weight"
                )))
            }
        }
        Ok(())
    }
}

/// A value set rather than read: it has no line in the file.
fn given<T>(value: T) -> Spanned<T> {
    Spanned::new(value, Location::UNKNOWN, Location::UNKNOWN)
}

fn not_a_number(key: &str) -> Error {
    Error::Input(format!(
        "`{key}` is not a number the scene format holds (keys are dotted paths such as disk.omega0, track.beam.E or solver.rtol)"
    ))
}

fn check(raw: &SceneFile, file: &str, stem: &str) -> Result<Checked, Error> {
    let c = Checker { file };
    let name = scene_name(&c, raw.name.as_ref(), stem)?;
    let gravity = match &raw.gravity {
        Some(g) => c.finite(g, "gravity")?,
        None => DEFAULT_GRAVITY,
    };
    let duration = c.positive(&raw.duration, "duration")?;
    let track = &raw.track;
    let (model, mesh) = match (&track.value.curve, &track.value.beam) {
        (Some(_), Some(_)) | (None, None) => {
            return c.err(
                track.referenced.line(),
                "track",
                "must name exactly one of `curve` or `beam`",
            )
        }
        (Some(curve), None) => (
            Model::Rolling(rolling_scene(&c, raw, curve, gravity)?),
            Given {
                elements: None,
                order: None,
                multiple: 1,
                model: true,
                duration,
            },
        ),
        (None, Some(beam)) => {
            let (scene, mesh) = beam_scene(&c, raw, beam, duration, gravity)?;
            (Model::Beam(scene), mesh)
        }
    };
    let duration = mesh.duration;
    let beam_default = matches!(model, Model::Beam(_));
    let mut solver = SolverSettings {
        method: if beam_default {
            Method::GenAlpha
        } else {
            Method::Dopri5
        },
        rtol: 1e-6,
        atol: 1e-9,
        rtol_chosen: None,
        atol_scale: None,
        atol_chosen: None,
    };
    let (mut rtol_given, mut atol_given) = (false, false);
    if let Some(s) = &raw.solver {
        if let Some(m) = &s.method {
            solver.method = Method::from_name(&m.value).map_or_else(
                || {
                    c.err(
                        m.referenced.line(),
                        "solver.method",
                        format!("is {}; use one of {}", quote(&m.value), method_names()),
                    )
                },
                Ok,
            )?;
            if solver.method == Method::GenAlpha && !beam_default {
                return c.err(m.referenced.line(), "solver.method", "genalpha integrates structural (beam) scenes; use dopri5, trbdf2 or esdirk4 for a rigid curve");
            }
        }
        if let Some(r) = &s.rtol {
            solver.rtol = c.positive(r, "solver.rtol")?;
            if let Some(why) = crate::ode::rtol_problem(solver.rtol) {
                return c.err(r.referenced.line(), "solver.rtol", why);
            }
            rtol_given = true;
        }
        if let Some(a) = &s.atol {
            solver.atol = c.positive(a, "solver.atol")?;
            atol_given = true;
        }
    }
    let mut interval = duration / 500.0;
    if let Some(i) = raw.output.as_ref().and_then(|o| o.interval.as_ref()) {
        interval = c.positive(i, "output.interval")?;
        if interval > duration {
            return c.err(
                i.referenced.line(),
                "output.interval",
                format!("= {interval} s is longer than `duration` = {duration} s; history.csv would hold t = 0 alone"),
            );
        }
        if duration / interval > MAX_ROWS {
            return c.err(i.referenced.line(), "output.interval", format!("= {interval:e} would write {:.3e} rows of history; at most {MAX_ROWS:.0} are allowed", duration / interval));
        }
    }
    if let (Model::Beam(b), Some(s)) = (&model, &raw.solver) {
        if let (Some(d), Some(m)) = (&b.disk, &s.method) {
            if d.coupling == Coupling::Thesis
                && solver.method != Method::GenAlpha
                && b.beam.model != BeamModel::Exact
                && mesh.model
            {
                return c.err(m.referenced.line(), "solver.method", format!("{} integrates the thesis coupling as the published 3n + 6 system, which transcribes the exact beam; use `model: exact`, or genalpha for the thesis coupling on a {} beam", solver.method.name(), b.beam.model.name()));
            }
        }
    }
    Ok(Checked {
        scene: Scene {
            name,
            duration,
            model,
            solver,
            interval,
        },
        elements: mesh.elements,
        order: mesh.order,
        multiple: mesh.multiple,
        model_given: mesh.model,
        rtol_given,
        atol_given,
        rho_inf_given: raw.solver.as_ref().is_some_and(|s| s.rho_inf.is_some()),
    })
}

/// Why a user's name cannot name a folder or a column, if it cannot: what every such name
/// must be (not empty, no control character, at most `max` characters).
fn name_flaw(name: &str, max: usize) -> Option<String> {
    if name.trim().is_empty() {
        Some("is empty".into())
    } else if name.chars().any(char::is_control) {
        Some("holds a control character".into())
    } else if name.chars().count() > max {
        Some(format!("is longer than {max} characters"))
    } else {
        None
    }
}

/// Longest scene name: it names the output folder.
const MAX_NAME_CHARS: usize = 100;

/// The scene's name, which names its default output folder `out/<name>`: so it must be a
/// plain folder name, never a path that leads elsewhere. Refused rather than rewritten, so
/// that the folder a run writes is always the name the user gave.
fn scene_name(c: &Checker, given: Option<&Spanned<String>>, stem: &str) -> Result<String, Error> {
    let (name, line, key) = match given {
        Some(n) => (n.value.as_str(), n.referenced.line(), "name"),
        None => (stem, 0, "name (the file's stem, as the scene gives none)"),
    };
    let why = name_flaw(name, MAX_NAME_CHARS).or_else(|| {
        if name == "." || name == ".." {
            Some("would name a folder outside out/".into())
        } else if name.contains(['/', '\\']) {
            Some("holds a path separator; a name names one folder in out/".into())
        } else {
            None
        }
    });
    match why {
        Some(why) => c.err(line, key, format!("= {} {why}", quote(name))),
        None => Ok(name.to_string()),
    }
}

/// `disk.contact_loss` and `disk.restitution`, checked; `None` where the scene gives neither.
fn contact_loss(c: &Checker, d: &DiskFile) -> Result<Option<ContactLoss>, Error> {
    let restitution = match &d.restitution {
        Some(e) => {
            let v = c.finite(e, "disk.restitution")?;
            if !(0.0..=1.0).contains(&v) {
                return c.err(
                    e.referenced.line(),
                    "disk.restitution",
                    format!("= {v} is outside [0, 1]: the share of the normal speed a landing gives back (0 plastic, 1 elastic)"),
                );
            }
            Some((v, e.referenced.line()))
        }
        None => None,
    };
    match (&d.contact_loss, restitution) {
        (None, None) => Ok(None),
        (None, Some((e, _))) => Ok(Some(ContactLoss::Fly { restitution: e })),
        (Some(k), e) => match k.value.as_str() {
            "fly" => Ok(Some(ContactLoss::Fly {
                restitution: e.map_or(0.0, |e| e.0),
            })),
            "stop" => match e {
                Some((_, line)) => c.err(
                    line,
                    "disk.restitution",
                    "acts at a landing, and with `contact_loss: stop` the disk never lands; leave it out or fly",
                ),
                None => Ok(Some(ContactLoss::Stop)),
            },
            other => c.err(
                k.referenced.line(),
                "disk.contact_loss",
                format!("is {}; use fly or stop", quote(other)),
            ),
        },
    }
}

fn rolling_scene(
    c: &Checker,
    raw: &SceneFile,
    curve_file: &Spanned<CurveFile>,
    gravity: f64,
) -> Result<RollingScene, Error> {
    let track = &raw.track;
    refuse_beam_keys(c, raw)?;
    let curve = build_curve(c, curve_file)?;
    let Some(disk_file) = &raw.disk else {
        return c.err(
            track.referenced.line(),
            "disk",
            "is missing: a rigid curve needs a disk to roll on it",
        );
    };
    let d = &disk_file.value;
    let disk = c.disk(d, gravity)?;
    let s0 = match &d.s0 {
        Some(s) => c.finite(s, "disk.s0")?,
        None => 0.0,
    };
    let omega0 = match &d.omega0 {
        Some(w) => c.finite(w, "disk.omega0")?,
        None => 0.0,
    };
    let mu = match &d.mu {
        Some(m) => Some(c.positive(m, "disk.mu")?),
        None => None,
    };
    if let Some(cp) = &d.coupling {
        return c.err(
            cp.referenced.line(),
            "disk.coupling",
            "applies to beam tracks only; on a rigid curve choose `formulation`",
        );
    }
    if let Some(p) = &d.patch {
        return c.err(
            p.referenced.line(),
            "disk.patch",
            "applies to beam tracks only; on a rigid curve the contact is a point",
        );
    }
    let formulation = match &d.formulation {
        None => Formulation::Minimal,
        Some(f) => match f.value.as_str() {
            "minimal" => Formulation::Minimal,
            "thesis" => Formulation::Thesis,
            other => {
                return c.err(
                    f.referenced.line(),
                    "disk.formulation",
                    format!("is {}; use minimal or thesis", quote(other)),
                )
            }
        },
    };
    if let Some((lo, hi)) = curve.domain() {
        if !(lo..=hi).contains(&s0) {
            let line =
                d.s0.as_ref()
                    .map_or(disk_file.referenced.line(), |s| s.referenced.line());
            return c.err(
                line,
                "disk.s0",
                format!(
                    "= {s0} is off the track: the {} runs over s in [{lo}, {hi}]",
                    curve.kind()
                ),
            );
        }
    }
    let mut rolling = Rolling::new(curve, disk, gravity, s0, omega0, mu);
    rolling.contact_loss = contact_loss(c, d)?.unwrap_or(ContactLoss::Fly { restitution: 0.0 });
    if let Some(s) = rolling.first_unfit_point() {
        let kappa = rolling.curve.at(s).curvature();
        if !kappa.is_finite() {
            return c.err(
                curve_file.referenced.line(),
                "track.curve",
                format!("has no finite tangent or curvature at s = {s:.4}, where the disk can reach (r' = 0 or a derivative is infinite there)"),
            );
        }
        return c.err(
            d.radius.referenced.line(),
            "disk.radius",
            format!(
                "= {} does not fit the curve at s = {s:.4}, which the disk can reach: the radius of curvature there is {:.4} m (the disk needs radius × curvature < 1)",
                disk.radius,
                1.0 / kappa
            ),
        );
    }
    // The start in numbers: a finite point can still lie where the curve's coordinates, or the
    // energy measured from them, overflow.
    let start = rolling.curve.at(s0);
    let centre = rolling.centre(&start);
    let (kinetic, potential) = rolling.energies(rolling.v0(), omega0, centre[1]);
    let s0_line =
        d.s0.as_ref()
            .map_or(disk_file.referenced.line(), |s| s.referenced.line());
    for (v, what) in [
        (centre[0], "the centre's X at the start"),
        (centre[1], "the centre's Y at the start"),
        (start.speed(), "the curve's speed |r'| at the start"),
        (kinetic + potential, "the initial energy"),
    ] {
        if !v.is_finite() {
            return c.err(
                s0_line,
                "disk.s0",
                format!(
                    "= {s0} makes {what} infinite or undefined; start the disk where the curve's numbers are finite"
                ),
            );
        }
    }
    Ok(RollingScene {
        rolling,
        formulation,
    })
}

/// Keys that belong to beam tracks, refused on a rigid curve with the reason.
fn refuse_beam_keys(c: &Checker, raw: &SceneFile) -> Result<(), Error> {
    if let Some(t) = &raw.train {
        return c.err(
            t.referenced.line(),
            "train",
            "crosses beam tracks only; on a rigid curve give a disk",
        );
    }
    if let Some(loads) = &raw.loads {
        return c.err(
            loads.referenced.line(),
            "loads",
            "apply to beam tracks only; a rigid curve carries no loads",
        );
    }
    if let Some(rho) = raw.solver.as_ref().and_then(|s| s.rho_inf.as_ref()) {
        return c.err(
            rho.referenced.line(),
            "solver.rho_inf",
            "applies to genalpha on beam tracks only",
        );
    }
    if let Some(a) = raw.solver.as_ref().and_then(|s| s.accuracy.as_ref()) {
        return c.err(
            a.referenced.line(),
            "solver.accuracy",
            "chooses a beam's mesh and tolerances; on a rigid curve set solver.rtol",
        );
    }
    if let Some(o) = &raw.output {
        let beam_only = [
            o.probes.as_ref().map(|v| v.referenced.line()),
            o.shapes.as_ref().map(|v| v.referenced.line()),
            o.magnify.as_ref().map(|v| v.referenced.line()),
            o.acceleration_cutoff_hz
                .as_ref()
                .map(|v| v.referenced.line()),
        ];
        for (line, key) in beam_only.iter().zip([
            "output.probes",
            "output.shapes",
            "output.magnify",
            "output.acceleration_cutoff_hz",
        ]) {
            if let Some(line) = line {
                return c.err(*line, key, "applies to beam tracks only");
            }
        }
    }
    Ok(())
}

fn beam_scene(
    c: &Checker,
    raw: &SceneFile,
    file: &Spanned<BeamFile>,
    duration: f64,
    gravity: f64,
) -> Result<(BeamScene, Given), Error> {
    let b = &file.value;
    let (mut beam, length, multiple, model_given) = beam_spec(c, b)?;
    beam.damping = damping(c, b)?;
    if b.self_weight.as_ref().is_some_and(|w| w.value) {
        beam.self_weight = Some(gravity);
    }
    let start = beam_start(c, b, &beam)?;
    let loads = point_loads(c, raw, length)?;
    let train = match &raw.train {
        None => None,
        Some(t) => Some(train(c, raw, t, &beam, gravity)?),
    };
    // With a train `duration` is the free vibration after its last axle has left.
    let duration = match (&train, &raw.train) {
        (Some(t), Some(file)) => c.derived(
            file.value.speed.referenced.line(),
            "train.speed",
            "the run's length, the crossing plus `duration`,",
            t.gone(length) + duration,
        )?,
        _ => duration,
    };
    let (probes, shapes, magnify) = outputs(c, raw, length, duration)?;
    let rho_inf = match raw.solver.as_ref().and_then(|s| s.rho_inf.as_ref()) {
        None => 1.0,
        Some(r) => {
            let v = c.finite(r, "solver.rho_inf")?;
            if !(0.0..=1.0).contains(&v) {
                return c.err(
                    r.referenced.line(),
                    "solver.rho_inf",
                    format!("= {v} must lie in [0, 1]"),
                );
            }
            v
        }
    };
    let disk = match &raw.disk {
        None => None,
        Some(d) => Some(disk_on_beam(c, d, &beam, length, gravity)?),
    };
    let accuracy = match raw.solver.as_ref().and_then(|s| s.accuracy.as_ref()) {
        None => DEFAULT_ACCURACY,
        Some(a) => {
            let v = c.positive(a, "solver.accuracy")?;
            if v >= 0.5 {
                return c.err(
                    a.referenced.line(),
                    "solver.accuracy",
                    format!("= {v} is a relative error and must be below 0.5"),
                );
            }
            if v < MIN_ACCURACY {
                return c.err(
                    a.referenced.line(),
                    "solver.accuracy",
                    format!("= {v:e} asks for more than the beam's equations hold: the tolerances it implies (down to accuracy/1000) would pass the round-off of a step; use at least {MIN_ACCURACY:e}"),
                );
            }
            v
        }
    };
    let given = Given {
        elements: b.elements.as_ref().map(|_| beam.elements),
        order: b.order.as_ref().map(|_| beam.order),
        multiple,
        model: model_given,
        duration,
    };
    let scene = BeamScene {
        beam,
        start,
        disk,
        train,
        loads,
        probes,
        shapes,
        magnify,
        rho_inf,
        rho_inf_chosen: None,
        accuracy,
        discretisation: None,
        model_choice: None,
        acceleration_cutoff_hz: match raw
            .output
            .as_ref()
            .and_then(|o| o.acceleration_cutoff_hz.as_ref())
        {
            None => None,
            Some(f) => Some(c.positive(f, "output.acceleration_cutoff_hz")?),
        },
        response: None,
    };
    Ok((scene, given))
}

/// What of the mesh and model a beam scene gives itself (the plan chooses the rest).
pub struct Given {
    pub elements: Option<usize>,
    pub order: Option<usize>,
    /// Element counts are kept to multiples of this, which puts a node at each bearing.
    pub multiple: usize,
    /// The scene names its beam model.
    pub model: bool,
    /// The run's duration: the scene's, or with a train the crossing plus the scene's.
    pub duration: f64,
}

/// The beam as the file gives it: its axis, section, supports and mesh (the element count 0
/// where the file leaves it to the plan); its length; and the multiple element counts are kept
/// to, which puts a node at each bearing.
fn beam_spec(c: &Checker, b: &BeamFile) -> Result<(BeamSpec, f64, usize, bool), Error> {
    let from = c.pair(&b.from, "track.beam.from")?;
    let to = c.pair(&b.to, "track.beam.to")?;
    let length = (to[0] - from[0]).hypot(to[1] - from[1]);
    if length == 0.0 {
        return c.err(
            b.to.referenced.line(),
            "track.beam.to",
            "equals `from`: the beam has zero length",
        );
    }
    c.derived(
        b.to.referenced.line(),
        "track.beam.to",
        "the beam's length",
        length,
    )?;
    let e = c.positive(&b.E, "track.beam.E")?;
    let g = c.positive(&b.G, "track.beam.G")?;
    let rho = c.positive(&b.rho, "track.beam.rho")?;
    let a = c.positive(&b.A, "track.beam.A")?;
    let av = c.positive(&b.Av, "track.beam.Av")?;
    let i = c.positive(&b.I, "track.beam.I")?;
    let (supports, bearings, multiple) = supports(c, b, length)?;
    let (elements, order, quadrature) = mesh(c, b, multiple)?;
    let section = Section {
        ea: e * a,
        gav: g * av,
        ei: e * i,
        rho_a: rho * a,
        rho_i: rho * i,
    };
    for (v, given, key, what) in [
        (section.ea, &b.E, "track.beam.E", "the axial stiffness E A"),
        (
            section.gav,
            &b.G,
            "track.beam.G",
            "the shear stiffness G Av",
        ),
        (
            section.ei,
            &b.I,
            "track.beam.I",
            "the bending stiffness E I",
        ),
        (
            section.rho_a,
            &b.rho,
            "track.beam.rho",
            "the mass per length ρ A",
        ),
        (
            section.rho_i,
            &b.rho,
            "track.beam.rho",
            "the rotary inertia per length ρ I",
        ),
        (
            section.ea / section.rho_a,
            &b.rho,
            "track.beam.rho",
            "the squared axial wave speed E/ρ",
        ),
    ] {
        c.derived(given.referenced.line(), key, what, v)?;
    }
    let depth = match &b.depth {
        Some(d) => c.part_of_length(
            d,
            "track.beam.depth",
            length,
            "the depth sets the contact patch, which would be a point",
            ("is deeper than the beam is long", "that is not a beam"),
        )?,
        None => {
            let depth = patch::rectangular_depth(&section);
            if !(depth <= length) {
                return c.err(
                    b.I.referenced.line(),
                    "track.beam.I",
                    format!(
                        "with A makes the rectangle √(12 I/A) = {} m deep, deeper than the beam is long: that is not a beam (give `track.beam.depth` if the section is not a rectangle)",
                        crate::error::short_numbers(&format!("{depth:e}"))
                    ),
                );
            }
            depth
        }
    };
    let unknowns = (elements > 0).then(|| {
        let held: usize = supports.iter().map(|s| s.held_components().len()).sum();
        3 * (elements * order + 1) - held - bearings.len()
    });
    let model = beam_model(c, b, unknowns)?;
    let beam = BeamSpec {
        from,
        to,
        section,
        depth,
        supports,
        bearings,
        elements,
        order,
        quadrature,
        model: model.unwrap_or(BeamModel::Exact),
        damping: None,
        self_weight: None,
    };
    Ok((beam, length, multiple, model.is_some()))
}

/// The train as the file gives it: an HSLM name, or axles and their load; its speed and model.
fn train(
    c: &Checker,
    raw: &SceneFile,
    file: &Spanned<TrainFile>,
    beam: &BeamSpec,
    gravity: f64,
) -> Result<Train, Error> {
    let t = &file.value;
    if let Some(d) = &raw.disk {
        return c.err(
            d.referenced.line(),
            "disk",
            "and `train` are both given: a scene has one rider, a disk or a train",
        );
    }
    let speed = c.positive(&t.speed, "train.speed")?;
    let model = match &t.model {
        None => TrainModel::MovingForce,
        Some(m) if m.value == "moving-force" => TrainModel::MovingForce,
        Some(m) if m.value == "moving-mass" => {
            if !(gravity > 0.0) {
                return c.err(
                    m.referenced.line(),
                    "train.model",
                    format!("is moving-mass, whose axle masses are their loads over gravity, and gravity is {gravity}: give a positive `gravity`, or use moving-force"),
                );
            }
            TrainModel::MovingMass
        }
        Some(m) => {
            return c.err(
                m.referenced.line(),
                "train.model",
                format!(
                    "is {}; a train's axles are moving-force or moving-mass",
                    quote(&m.value)
                ),
            )
        }
    };
    let (name, axles, loads) = match (&t.hslm, &t.axles, &t.load) {
        (Some(h), None, None) => {
            let (axles, force) = hslm(&h.value).map_or_else(
                || {
                    c.err(
                        h.referenced.line(),
                        "train.hslm",
                        format!(
                            "is {}; EN 1991-2's HSLM-A trains are {HSLM_NAMES}",
                            quote(&h.value)
                        ),
                    )
                },
                Ok,
            )?;
            let loads = vec![force; axles.len()];
            (h.value.clone(), axles, loads)
        }
        (Some(h), _, _) => {
            return c.err(
                h.referenced.line(),
                "train.hslm",
                "names a train whose axles and loads are EN 1991-2's: leave `axles` and `load` out",
            )
        }
        (None, Some(a), Some(l)) => {
            let line = a.referenced.line();
            let axles = a.value.clone();
            if axles.is_empty() || axles.len() > MAX_AXLES {
                return c.err(
                    line,
                    "train.axles",
                    format!("must hold 1 to {MAX_AXLES} axles"),
                );
            }
            if axles.iter().any(|x| !x.is_finite() || *x < 0.0)
                || axles.windows(2).any(|w| w[1] <= w[0])
            {
                return c.err(
                    line,
                    "train.axles",
                    "must be distances behind the first axle (m), from 0 and increasing",
                );
            }
            let loads = match &l.value {
                AxleLoads::All(p) => vec![*p; axles.len()],
                AxleLoads::Each(each) if each.len() == axles.len() => each.clone(),
                AxleLoads::Each(each) => {
                    return c.err(
                        l.referenced.line(),
                        "train.load",
                        format!(
                            "lists {} loads for {} axles: give one per axle, or one number for all",
                            each.len(),
                            axles.len()
                        ),
                    )
                }
            };
            if loads.iter().any(|p| !p.is_finite()) {
                return c.err(
                    l.referenced.line(),
                    "train.load",
                    "must hold finite forces (N)",
                );
            }
            if model == TrainModel::MovingMass && loads.iter().any(|p| !(*p > 0.0)) {
                return c.err(
                        l.referenced.line(),
                        "train.load",
                        "must hold positive forces (N) with moving-mass, whose axle masses are the loads over gravity",
                    );
            }
            ("axles".to_string(), axles, loads)
        }
        (None, Some(_), None) => {
            return c.err(
                file.referenced.line(),
                "train.load",
                "is missing: give the force per axle (N), or one per axle",
            )
        }
        (None, None, _) => {
            return c.err(
                file.referenced.line(),
                "train",
                "needs `hslm` (A1 to A10), or `axles` and `load`",
            )
        }
    };
    if model == TrainModel::MovingMass {
        let span = (beam.to[0] - beam.from[0]).hypot(beam.to[1] - beam.from[1]);
        let most = most_within(&axles, span);
        if most > MAX_MASSES_ON_DECK {
            return c.err(
                file.referenced.line(),
                "train",
                format!("puts up to {most} moving-mass axles on the {span} m deck at once; at most {MAX_MASSES_ON_DECK} can be (each one's inertia couples to every other's through the beam, so the work grows with their square): use moving-force, or fewer axles"),
            );
        }
    }
    let masses = match model {
        TrainModel::MovingForce => Vec::new(),
        TrainModel::MovingMass => loads.iter().map(|p| p / gravity).collect(),
    };
    Ok(Train {
        name,
        axles,
        loads,
        speed,
        model,
        masses,
        patch: patch::dispersed_half_width(beam.depth),
    })
}

/// Rayleigh damping as the file gives it: a ratio at two modes, or α and β.
fn damping(c: &Checker, b: &BeamFile) -> Result<Option<DampingSpec>, Error> {
    let Some(d) = &b.damping else {
        return Ok(None);
    };
    let line = d.referenced.line();
    let d = &d.value;
    let non_negative = |v: &Spanned<f64>, key: &str| -> Result<f64, Error> {
        let x = c.finite(v, key)?;
        if x < 0.0 {
            return c.err(
                v.referenced.line(),
                key,
                format!("= {x} must not be negative"),
            );
        }
        Ok(x)
    };
    match (&d.ratio, d.alpha.is_some() || d.beta.is_some()) {
        (Some(r), true) => c.err(
            r.referenced.line(),
            "track.beam.damping",
            "gives a ratio and alpha or beta: give {ratio, modes} or {alpha, beta}, not both",
        ),
        (None, false) => c.err(
            line,
            "track.beam.damping",
            "is empty: give {ratio: ζ, modes: [i, j]} or {alpha: α, beta: β}",
        ),
        (Some(r), false) => {
            let zeta = c.finite(r, "track.beam.damping.ratio")?;
            if !(0.0..1.0).contains(&zeta) {
                return c.err(
                    r.referenced.line(),
                    "track.beam.damping.ratio",
                    format!("= {zeta} must lie in [0, 1): a ratio of 1 or more is no longer a vibration"),
                );
            }
            let modes = match &d.modes {
                None => [1, 2],
                Some(m) => match m.value.as_slice() {
                    &[i, j] if i >= 1 && j >= 1 && i != j && i.max(j) <= MAX_MODES as i64 => {
                        [i as usize, j as usize]
                    }
                    _ => {
                        return c.err(
                            m.referenced.line(),
                            "track.beam.damping.modes",
                            format!(
                            "must be two distinct mode numbers from 1 to {MAX_MODES}, e.g. [1, 2]"
                        ),
                        )
                    }
                },
            };
            Ok(Some(DampingSpec::Ratio { zeta, modes }))
        }
        (None, true) => {
            if let Some(m) = &d.modes {
                return c.err(
                    m.referenced.line(),
                    "track.beam.damping.modes",
                    "anchors a ratio; alpha and beta need no modes",
                );
            }
            let alpha = d
                .alpha
                .as_ref()
                .map_or(Ok(0.0), |v| non_negative(v, "track.beam.damping.alpha"))?;
            let beta = d
                .beta
                .as_ref()
                .map_or(Ok(0.0), |v| non_negative(v, "track.beam.damping.beta"))?;
            Ok(Some(DampingSpec::Rayleigh { alpha, beta }))
        }
    }
}

/// The beam model as the file gives it, `None` where it leaves the choice to the plan; a
/// modal beam whose `modes` are left out has 0 until the plan chooses them. `unknowns`: the
/// mesh's, where the file gives the element count.
fn beam_model(
    c: &Checker,
    b: &BeamFile,
    unknowns: Option<usize>,
) -> Result<Option<BeamModel>, Error> {
    let model = match &b.model {
        None => None,
        Some(m) => Some(match m.value.as_str() {
            "exact" => BeamModel::Exact,
            "linear" => BeamModel::Linear,
            "modal" => BeamModel::Modal { modes: 0 },
            other => {
                return c.err(
                    m.referenced.line(),
                    "track.beam.model",
                    format!("is {}; use exact, linear or modal", quote(other)),
                )
            }
        }),
    };
    let Some(modes) = &b.modes else {
        return Ok(model);
    };
    let line = modes.referenced.line();
    if let Some(m @ (BeamModel::Exact | BeamModel::Linear)) = model {
        return c.err(
            line,
            "track.beam.modes",
            format!(
                "counts the modes of a modal beam; `model: {}` keeps every unknown of the mesh (use `model: modal`, or leave `modes` out)",
                m.name()
            ),
        );
    }
    if modes.value < 1 {
        return c.err(
            line,
            "track.beam.modes",
            format!("must be at least 1 (got {})", modes.value),
        );
    }
    if let Some(n) = unknowns {
        if modes.value as u64 > n as u64 {
            return c.err(
                line,
                "track.beam.modes",
                format!(
                    "= {} is more than the mesh has: its {n} unknowns have {n} modes",
                    modes.value
                ),
            );
        }
    }
    if modes.value > MAX_MODES as i64 {
        return c.err(
            line,
            "track.beam.modes",
            format!(
                "= {} is more than a modal beam keeps ({MAX_MODES}); use `model: linear` for the whole mesh",
                modes.value
            ),
        );
    }
    Ok(Some(BeamModel::Modal {
        modes: modes.value as usize,
    }))
}

/// The end supports, the intermediate bearings (sorted), and the multiple of elements that
/// puts a node at each.
fn supports(
    c: &Checker,
    b: &BeamFile,
    length: f64,
) -> Result<([Support; 2], Vec<f64>, usize), Error> {
    let support = |v: &Spanned<String>, key: &str| {
        Support::from_name(&v.value).map_or_else(
            || {
                c.err(
                    v.referenced.line(),
                    key,
                    format!(
                        "is {}; use clamped, pinned, roller or free",
                        quote(&v.value)
                    ),
                )
            },
            Ok,
        )
    };
    let supports = [
        support(&b.supports.value.from, "track.beam.supports.from")?,
        support(&b.supports.value.to, "track.beam.supports.to")?,
    ];
    let mut bearings = Vec::new();
    for x in b
        .supports
        .value
        .intermediate
        .iter()
        .flat_map(|v| v.value.iter())
    {
        let key = "track.beam.supports.intermediate";
        let v = c.finite(x, key)?;
        if !(v > 0.0 && v < length) {
            return c.err(
                x.referenced.line(),
                key,
                format!("has x = {v}, which is not strictly inside the beam (0, {length})"),
            );
        }
        if bearings
            .iter()
            .any(|&b: &f64| (b - v).abs() <= 1e-9 * length)
        {
            return c.err(x.referenced.line(), key, format!("names x = {v} twice"));
        }
        bearings.push(v);
    }
    bearings.sort_by(f64::total_cmp);
    let fractions: Vec<f64> = bearings.iter().map(|x| x / length).collect();
    let Some(multiple) = mesh_multiple(&fractions, MAX_SPANS) else {
        // The first bearing that no mesh fits together with those before it is the one named:
        // a list of hundreds would not be a sentence.
        let k = (1..=fractions.len())
            .find(|&k| mesh_multiple(&fractions[..k], MAX_SPANS).is_none())
            .unwrap_or(fractions.len());
        let before = match k - 1 {
            0 => String::new(),
            1 => format!(" with the bearing at x = {} before it", bearings[0]),
            n => format!(" with the {n} bearings before it"),
        };
        return c.err(
            b.supports.referenced.line(),
            "track.beam.supports.intermediate",
            format!("has a bearing at x = {}{before} that does not divide the beam into spans of commensurable length (a uniform mesh of at most {MAX_SPANS} elements needs a node at each)", bearings[k - 1]),
        );
    };
    Ok((supports, bearings, multiple))
}

/// Element count (0 when left out: the plan chooses it), degree and quadrature.
fn mesh(c: &Checker, b: &BeamFile, multiple: usize) -> Result<(usize, usize, Quadrature), Error> {
    // Left out, the element count is chosen from the accuracy once the loads are read (below).
    let elements = match &b.elements {
        None => 0,
        Some(n) if n.value >= 1 => n.value as usize,
        Some(n) => {
            return c.err(
                n.referenced.line(),
                "track.beam.elements",
                format!("must be at least 1 (got {})", n.value),
            )
        }
    };
    if let Some(n) = &b.elements {
        if n.value as usize % multiple != 0 {
            return c.err(
                n.referenced.line(),
                "track.beam.elements",
                format!(
                    "= {} puts no node at an intermediate bearing: use a multiple of {multiple}",
                    n.value
                ),
            );
        }
    }
    let order = match &b.order {
        None => DEFAULT_ORDER,
        Some(n) if (1..=MAX_ORDER as i64).contains(&n.value) => n.value as usize,
        Some(n) => {
            return c.err(
                n.referenced.line(),
                "track.beam.order",
                format!(
                    "must be a Lagrange degree from 1 to {MAX_ORDER} (got {})",
                    n.value
                ),
            )
        }
    };
    if let Some(n) = &b.elements {
        let nodes = n.value as f64 * order as f64 + 1.0;
        if nodes > MAX_NODES {
            return c.err(
                n.referenced.line(),
                "track.beam.elements",
                format!(
                    "= {} of degree {order} makes {nodes:.0} nodes; a beam may have at most {MAX_NODES:.0} (three unknowns each)",
                    n.value
                ),
            );
        }
    }
    let quadrature = match &b.quadrature {
        None => Quadrature::Reduced,
        Some(q) => Quadrature::from_name(&q.value).map_or_else(
            || {
                c.err(
                    q.referenced.line(),
                    "track.beam.quadrature",
                    format!("is {}; use reduced, full or lobatto", quote(&q.value)),
                )
            },
            Ok,
        )?,
    };
    Ok((elements, order, quadrature))
}

fn beam_start(c: &Checker, b: &BeamFile, beam: &BeamSpec) -> Result<BeamStart, Error> {
    let start = match &b.initial {
        None => BeamStart::Rest,
        Some(v) if v.value == "rest" => BeamStart::Rest,
        Some(v) if v.value == "static" => BeamStart::Static,
        Some(v) => {
            return c.err(
                v.referenced.line(),
                "track.beam.initial",
                format!("is {}; use rest or static", quote(&v.value)),
            )
        }
    };
    if start == BeamStart::Static && !statically_supported(beam.supports, beam.bearings.len()) {
        return c.err(
            b.initial.as_ref().map_or(0, |v| v.referenced.line()),
            "track.beam.initial",
            "is static, but the supports leave the beam free to move as a rigid body, so it has no static equilibrium",
        );
    }

    Ok(start)
}

/// A material point of the beam, x in [0, L].
fn within(c: &Checker, x: &Spanned<f64>, key: &str, length: f64) -> Result<f64, Error> {
    let v = c.finite(x, key)?;
    if !(0.0..=length).contains(&v) {
        return c.err(
            x.referenced.line(),
            key,
            format!("= {v} lies outside the beam, which runs over x in [0, {length}]"),
        );
    }
    Ok(v)
}

fn point_loads(c: &Checker, raw: &SceneFile, length: f64) -> Result<Vec<PointLoad>, Error> {
    let mut loads = Vec::new();
    if let Some(list) = &raw.loads {
        for l in &list.value {
            let lf = &l.value;
            let opt = |v: &Option<Spanned<f64>>, key: &str| {
                v.as_ref().map_or(Ok(0.0), |v| c.finite(v, key))
            };
            let from_t = opt(&lf.from, "loads.from")?;
            let until = match &lf.until {
                None => f64::INFINITY,
                Some(u) => {
                    let u_v = c.finite(u, "loads.until")?;
                    if u_v <= from_t {
                        return c.err(
                            u.referenced.line(),
                            "loads.until",
                            format!(
                                "= {u_v} is not after `from` = {from_t}: the load would never act"
                            ),
                        );
                    }
                    u_v
                }
            };
            loads.push(PointLoad {
                x: within(c, &lf.x, "loads.x", length)?,
                force: [opt(&lf.fx, "loads.fx")?, opt(&lf.fy, "loads.fy")?],
                mz: opt(&lf.mz, "loads.mz")?,
                from: from_t,
                until,
            });
        }
    }
    Ok(loads)
}

/// Probes (default: `mid` at L/2), shape times and their magnification.
fn outputs(
    c: &Checker,
    raw: &SceneFile,
    length: f64,
    duration: f64,
) -> Result<(Vec<Probe>, Vec<f64>, f64), Error> {
    let mut probes = Vec::new();
    let mut shapes = Vec::new();
    let mut magnify = 1.0;
    if let Some(o) = &raw.output {
        for p in o.probes.iter().flat_map(|v| v.value.iter()) {
            let name = &p.value.name;
            let why = name_flaw(&name.value, 40).or_else(|| {
                if name.value.contains([',', '"']) {
                    Some(
                        "holds a comma or a quote, which cannot head a column of history.csv"
                            .into(),
                    )
                } else if probes.iter().any(|q: &Probe| q.name == name.value) {
                    Some("names two probes".into())
                } else {
                    None
                }
            });
            if let Some(why) = why {
                return c.err(
                    name.referenced.line(),
                    "output.probes.name",
                    format!("= {} {why}", quote(&name.value)),
                );
            }
            probes.push(Probe {
                name: name.value.clone(),
                x: within(c, &p.value.x, "output.probes.x", length)?,
            });
        }
        for t in o.shapes.iter().flat_map(|v| v.value.iter()) {
            let tv = c.finite(t, "output.shapes")?;
            if !(0.0..=duration).contains(&tv) {
                return c.err(
                    t.referenced.line(),
                    "output.shapes",
                    format!("time {tv} lies outside the run [0, {duration}]"),
                );
            }
            shapes.push(tv);
        }
        if let Some(m) = &o.magnify {
            magnify = c.positive(m, "output.magnify")?;
        }
    }
    if probes.is_empty() {
        probes.push(Probe {
            name: "mid".into(),
            x: 0.5 * length,
        });
    }
    Ok((probes, shapes, magnify))
}

/// The disk of a beam scene: checked against the beam it rolls on.
fn disk_on_beam(
    c: &Checker,
    file: &Spanned<DiskFile>,
    beam: &BeamSpec,
    length: f64,
    gravity: f64,
) -> Result<DiskOnBeamSpec, Error> {
    let d = &file.value;
    let disk = c.disk(d, gravity)?;
    if let Some(f) = &d.formulation {
        return c.err(
            f.referenced.line(),
            "disk.formulation",
            "applies to rigid curves only; on a beam choose `coupling`",
        );
    }
    let coupling = match &d.coupling {
        None => Coupling::Consistent,
        Some(cp) => Coupling::from_name(&cp.value).map_or_else(
            || {
                c.err(
                    cp.referenced.line(),
                    "disk.coupling",
                    format!(
                        "is {}; use one of {}",
                        quote(&cp.value),
                        Coupling::ALL.map(|k| k.name()).join(", ")
                    ),
                )
            },
            Ok,
        )?,
    };
    let line = d
        .contact_loss
        .as_ref()
        .map(|k| k.referenced.line())
        .or(d.restitution.as_ref().map(|e| e.referenced.line()))
        .unwrap_or(file.referenced.line());
    let key = if d.contact_loss.is_some() {
        "disk.contact_loss"
    } else {
        "disk.restitution"
    };
    let contact_loss = match (contact_loss(c, d)?, coupling) {
        (Some(_), Coupling::MovingForce | Coupling::MovingMass) => {
            return c.err(
                line,
                key,
                format!(
                    "applies to a disk that can leave the beam; the {} coupling's load is held to the beam and never leaves it",
                    coupling.name()
                ),
            );
        }
        (Some(ContactLoss::Fly { .. }), Coupling::Thesis) => {
            return c.err(
                line,
                key,
                "asks the disk to fly off the beam, which only the consistent coupling does: the thesis coupling rolls the disk on the axis as if it were frozen, which gives a landing no meaning; write `contact_loss: stop` or use `coupling: consistent`",
            );
        }
        (Some(loss), _) => loss,
        (None, Coupling::Consistent) => ContactLoss::Fly { restitution: 0.0 },
        (None, _) => ContactLoss::Stop,
    };
    let s0_line =
        d.s0.as_ref()
            .map_or(file.referenced.line(), |s| s.referenced.line());
    let s0 = match &d.s0 {
        Some(s) => c.finite(s, "disk.s0")?,
        None => 0.0,
    };
    if !(0.0..=length).contains(&s0) {
        return c.err(
            s0_line,
            "disk.s0",
            format!("= {s0} is off the beam, which runs over x in [0, {length}]"),
        );
    }
    let omega_line = d
        .omega0
        .as_ref()
        .map_or(file.referenced.line(), |s| s.referenced.line());
    let omega0 = match &d.omega0 {
        Some(w) => c.finite(w, "disk.omega0")?,
        None => 0.0,
    };
    if !coupling.rolls() && omega0 == 0.0 {
        return c.err(
            omega_line,
            "disk.omega0",
            format!(
                "is 0: a {} travels at the constant speed −radius × omega0, so it needs a non-zero omega0",
                coupling.name()
            ),
        );
    }
    // Rolling off the end it starts on leaves nothing to simulate; a disk resting exactly on
    // an end support with no speed has nowhere to go but off or nowhere.
    let v0 = -disk.radius * omega0;
    if (s0 == 0.0 && v0 < 0.0) || (s0 == length && v0 > 0.0) {
        return c.err(
            omega_line,
            "disk.omega0",
            format!("= {omega0} rolls the disk off the end of the beam it starts on (s0 = {s0}); Ω < 0 rolls towards +x"),
        );
    }
    if (s0 == 0.0 || s0 == length) && v0 == 0.0 {
        return c.err(
            s0_line,
            "disk.s0",
            format!("= {s0} puts the disk at rest on the end support, where it would load only the support and never move onto the beam; give it a speed (omega0) or start it inside"),
        );
    }
    let mu = match &d.mu {
        Some(m) => Some(c.positive(m, "disk.mu")?),
        None => None,
    };
    let patch = match &d.patch {
        Some(p) => c.part_of_length(
            p,
            "disk.patch",
            length,
            "a contact that short is a point, on which the disk's contact force is not defined (see REPORT.md, \"What depends on the patch\")",
            (
                "is wider than the beam",
                "the patch is the half-width of the contact, about the section's depth",
            ),
        )?,
        None => {
            patch::physical_half_width(&beam.section, beam.depth, disk.radius, disk.mass * gravity)
                .min(length)
        }
    };
    Ok(DiskOnBeamSpec {
        disk,
        s0,
        omega0,
        coupling,
        mu,
        gravity,
        patch,
        contact_loss,
    })
}

pub fn method_names() -> String {
    Method::ALL.map(|m| m.name()).join(", ")
}

fn build_curve(c: &Checker, file: &Spanned<CurveFile>) -> Result<Curve, Error> {
    let f = &file.value;
    let count = [
        f.parabola.is_some(),
        f.line.is_some(),
        f.expr.is_some(),
        f.points.is_some(),
    ]
    .iter()
    .filter(|&&b| b)
    .count();
    if count != 1 {
        return c.err(
            file.referenced.line(),
            "track.curve",
            "must name exactly one of parabola, line, expr or points",
        );
    }
    if let Some(p) = &f.parabola {
        let k = c.finite(&p.k, "track.curve.parabola.k")?;
        if k == 0.0 {
            return c.err(
                p.k.referenced.line(),
                "track.curve.parabola.k",
                "is 0: that is a straight line; use `line`",
            );
        }
        return Ok(Curve::Parabola { k });
    }
    if let Some(l) = &f.line {
        let from = c.pair(&l.from, "track.curve.line.from")?;
        let to = c.pair(&l.to, "track.curve.line.to")?;
        if from == to {
            return c.err(
                l.to.referenced.line(),
                "track.curve.line.to",
                "equals `from`: the line has zero length",
            );
        }
        return Ok(Curve::Line { from, to });
    }
    if let Some(e) = &f.expr {
        let parse = |v: &Spanned<String>, key: &str| {
            Formula::parse(&v.value)
                .or_else(|m| c.err(v.referenced.line(), key, format!("does not parse: {m}")))
        };
        return Ok(Curve::Expr {
            x: parse(&e.x, "track.curve.expr.x")?,
            y: parse(&e.y, "track.curve.expr.y")?,
        });
    }
    let pts = f.points.as_ref().expect("one kind is present");
    if pts.value.len() < 4 {
        return c.err(
            pts.referenced.line(),
            "track.curve.points",
            format!(
                "has {} points; a C2 spline needs at least 4",
                pts.value.len()
            ),
        );
    }
    let mut xy = Vec::with_capacity(pts.value.len());
    for (i, p) in pts.value.iter().enumerate() {
        let q = c.pair(p, "track.curve.points")?;
        if let Some(prev) = xy.last().map(|p: &[f64; 2]| p[0]) {
            if q[0] <= prev {
                return c.err(
                    p.referenced.line(),
                    "track.curve.points",
                    format!(
                        "must have X increasing, but point {} has X = {} after {prev}",
                        i + 1,
                        q[0]
                    ),
                );
            }
        }
        xy.push(q);
    }
    Ok(Curve::Points(Spline::new(&xy)))
}

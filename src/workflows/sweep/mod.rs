//! `rollbeam sweep SCENE.yaml --set KEY=FROM:TO:COUNT [--set KEY=A,B,…]`: one scene over a
//! grid of its values, the runs spread over every core. A number is swept over an evenly
//! spaced range or the values listed, a name (`train.hslm`, `disk.coupling`, …) over a list;
//! several `--set` make the grid of every combination. Each case's values are set at their
//! keys of the scene ([`SceneSpec::set`], [`SceneSpec::set_name`]) and the scene checked and
//! planned again, so a value the scene cannot take is refused with the same sentence a scene
//! file would get. One summary row per case; a run that fails is a row with its reason.
//!
//! A sweep larger than one machine is planned into case files, run in shards anywhere and
//! merged (`cluster.rs`); the Python package's `sweep` runs the same cases through the same
//! functions, so every route gives the same table.

pub mod cluster;

use crate::error::{quote, Error};
use crate::output::plots::{line_chart, line_chart_with_references};
use crate::output::write;
use crate::plan::Planner;
use crate::run::{self, Overrides, Run};
use crate::scene::{holds_number, is_key, SceneSpec};
use std::fmt::Write as _;
use std::path::Path;

/// Most cases one sweep runs: each is a whole run, and their rows are held in memory.
pub const MAX_CASES: usize = 100_000;
/// EN 1991-2 §6.4.6.2's limit of the deck acceleration on ballasted track (m/s²), drawn on a
/// train sweep's figure.
const BALLASTED_LIMIT: f64 = 3.5;

/// What one key is swept over.
#[derive(Clone, Debug, PartialEq)]
pub enum Sweep {
    /// FROM:TO:COUNT, evenly spaced.
    Range { from: f64, to: f64, count: usize },
    /// A number key's values listed (`train.speed=80,90,100`, or one value).
    Numbers(Vec<f64>),
    /// A list of names.
    Names(Vec<String>),
}

/// KEY=FROM:TO:COUNT or KEY=A,B,… (numbers for a number key, names for a name key).
#[derive(Clone, Debug, PartialEq)]
pub struct Setting {
    pub key: String,
    pub sweep: Sweep,
}

/// One value of a swept key.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Number(f64),
    Name(String),
}

impl std::fmt::Display for Value {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Value::Number(v) => write!(f, "{}", number_text(*v)),
            Value::Name(n) => write!(f, "{n}"),
        }
    }
}

/// A swept value as `sweep.csv` holds it: a name that reads as a number (`nan`, `inf`, `3` at
/// a key of names) quoted, so that it reads back as the name it is and the table's check for
/// non-finite numbers does not take it for one.
fn csv_cell(v: &Value) -> String {
    match v {
        Value::Name(n) if n.parse::<f64>().is_ok() => format!("\"{n}\""),
        _ => v.to_string(),
    }
}

/// A swept number as the table and the case files write it: the shortest text that reads
/// back to it, with an exponent where plain digits would run past a few dozen (1e-300 is
/// three hundred digits written out).
pub fn number_text(v: f64) -> String {
    if v != 0.0 && !(1e-5..1e16).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

impl Setting {
    pub fn parse(arg: &str) -> Result<Setting, Error> {
        let bad = |why: &str| {
            Error::Input(format!(
                "--set {} {why}; write KEY=FROM:TO:COUNT (e.g. disk.omega0=-10:-120:111), KEY=X,X (e.g. train.speed=80,90) or KEY=NAME,NAME (e.g. train.hslm=A1,A2)",
                quote(arg)
            ))
        };
        let (key, range) = arg.split_once('=').ok_or_else(|| bad("has no '='"))?;
        if key.split('.').any(|k| k.trim().is_empty()) {
            return Err(bad("has an empty key"));
        }
        let key = key.trim().to_string();
        let number = |s: &str| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(&format!("has {} where a finite number belongs", quote(s))))
        };
        if !range.contains(':') {
            let names: Vec<String> = range.split(',').map(|n| n.trim().to_string()).collect();
            if names.iter().any(|n| n.is_empty()) {
                return Err(bad("has an empty value"));
            }
            if names.len() > MAX_CASES {
                return Err(bad(&format!("lists more than {MAX_CASES} values")));
            }
            // Numbers listed at a key the format does not know are refused as numbers (what
            // the key is not), not as names.
            let unknown_numbers = !is_key(&key) && names.iter().all(|n| number(n).is_ok());
            let sweep = if holds_number(&key) || unknown_numbers {
                Sweep::Numbers(names.iter().map(|n| number(n)).collect::<Result<_, _>>()?)
            } else {
                Sweep::Names(names)
            };
            return Ok(Setting { key, sweep });
        }
        let parts: Vec<&str> = range.split(':').collect();
        let [from, to, count] = parts[..] else {
            return Err(bad("needs three fields after '='"));
        };
        let count = count
            .trim()
            .parse::<usize>()
            .ok()
            .filter(|&c| (1..=MAX_CASES).contains(&c))
            .ok_or_else(|| {
                bad(&format!(
                    "has {} where a count from 1 to {MAX_CASES} belongs",
                    quote(count)
                ))
            })?;
        Ok(Setting {
            key,
            sweep: Sweep::Range {
                from: number(from)?,
                to: number(to)?,
                count,
            },
        })
    }

    /// The numbers swept, in the order given (none for a list of names).
    pub fn values(&self) -> Vec<f64> {
        match &self.sweep {
            Sweep::Range { from, count: 1, .. } => vec![*from],
            &Sweep::Range { from, to, count } => (0..count)
                .map(|i| from + (to - from) * i as f64 / (count - 1) as f64)
                .collect(),
            Sweep::Numbers(values) => values.clone(),
            Sweep::Names(_) => Vec::new(),
        }
    }

    /// Whether the key is swept over numbers (a range or a list).
    pub fn numeric(&self) -> bool {
        !matches!(self.sweep, Sweep::Names(_))
    }

    /// Every value, in the order swept.
    pub fn all(&self) -> Vec<Value> {
        match &self.sweep {
            Sweep::Names(names) => names.iter().cloned().map(Value::Name).collect(),
            _ => self.values().into_iter().map(Value::Number).collect(),
        }
    }

    /// Set one value at the key of a scene.
    fn apply(&self, spec: &mut SceneSpec, value: &Value) -> Result<(), Error> {
        apply(spec, &self.key, value)
    }

    /// Every value, in the order the rows report them: numbers ascending, names as given.
    fn in_row_order(&self) -> Vec<Value> {
        let mut values = self.all();
        if self.numeric() {
            values.sort_by(|a, b| match (a, b) {
                (Value::Number(x), Value::Number(y)) => x.total_cmp(y),
                _ => std::cmp::Ordering::Equal,
            });
        }
        values
    }

    /// "FROM to TO" or "A, B".
    pub fn describe(&self) -> String {
        match &self.sweep {
            Sweep::Range { from, to, .. } => {
                format!("from {} to {}", number_text(*from), number_text(*to))
            }
            Sweep::Numbers(values) => {
                let values: Vec<String> = values.iter().map(|v| number_text(*v)).collect();
                values.join(", ")
            }
            Sweep::Names(names) => names.join(", "),
        }
    }
}

/// Set one value at a dotted key of a scene: a number or a name.
pub fn apply(spec: &mut SceneSpec, key: &str, value: &Value) -> Result<(), Error> {
    match value {
        Value::Number(v) => spec.set(key, *v),
        Value::Name(n) => spec.set_name(key, n),
    }
}

/// The scene of one case: its values set at the keys, in order.
pub fn case_spec(spec: &SceneSpec, keys: &[String], values: &[Value]) -> Result<SceneSpec, Error> {
    let mut changed = spec.clone();
    for (key, v) in keys.iter().zip(values) {
        apply(&mut changed, key, v)?;
    }
    Ok(changed)
}

/// What one case of the sweep reports.
#[derive(Clone, Debug)]
pub struct SweepRow {
    /// The case's value of each key, in the order the keys were given.
    pub values: Vec<Value>,
    /// The first key's number (NaN for a name): a one-key range's value.
    pub value: f64,
    pub outcome: Result<Summary, String>,
}

#[derive(Clone, Debug)]
pub struct Summary {
    pub stop: String,
    pub t_end: f64,
    pub energy_drift: f64,
    pub steps: usize,
    /// The steps the error estimate or Newton turned back, and the right-hand sides
    /// evaluated: with the steps and the wall time, what the solver did for the case.
    pub rejected: usize,
    pub rhs_evals: usize,
    pub wall_s: f64,
    /// Beam scenes: per probe (name, w_min, w_max, amplitude after the last load left or
    /// NaN, largest |vertical acceleration|).
    pub probes: Vec<(String, f64, f64, f64, f64)>,
    /// Per disk (`disk`, or `disk1`, `disk2`, … for several): its contact force's extremes
    /// and when it left the track (NaN: it did not).
    pub disks: Vec<DiskRow>,
    /// With vehicles: per body (`<vehicle>.<body>`, its largest |vertical acceleration|, or
    /// NaN where the vehicle never came onto the deck).
    pub bodies: Vec<(String, f64)>,
}

/// A disk's columns of `sweep.csv`.
#[derive(Clone, Debug, PartialEq)]
pub struct DiskRow {
    pub name: String,
    pub rn_min: f64,
    pub rn_max: f64,
    /// The normal contact force averaged over a period of the acceleration's cutoff: its
    /// least and largest (NaN where the run has no such mean).
    pub rn_mean_min: f64,
    pub rn_mean_max: f64,
    pub left_track_t: f64,
}

fn summarise(r: &Run) -> Summary {
    let mut probes = Vec::new();
    let mut disks = Vec::new();
    let mut bodies = Vec::new();
    match r {
        Run::Beam(b) => {
            for (k, p) in b.setup.probes.iter().enumerate() {
                let [_, w, _, a] = b.extremes.probes[k];
                let after = b.amplitude_after_exit(k).unwrap_or(f64::NAN);
                probes.push((p.name.clone(), w.min, w.max, after, a.largest_magnitude().0));
            }
            let on = b.extremes.disks.iter().zip(&b.disks_left_t);
            for (k, (name, (extremes, left))) in
                b.setup.disk_names().into_iter().zip(on).enumerate()
            {
                if let Some([rn, ..]) = extremes {
                    let mean = b.extremes.contact_means.get(k).copied().flatten();
                    disks.push(DiskRow {
                        name,
                        rn_min: rn.min,
                        rn_max: rn.max,
                        rn_mean_min: mean.map_or(f64::NAN, |[m, ..]| m.min),
                        rn_mean_max: mean.map_or(f64::NAN, |[m, ..]| m.max),
                        left_track_t: left.unwrap_or(f64::NAN),
                    });
                }
            }
            for v in &b.vehicles {
                for (name, range, _) in &v.bodies {
                    let a = if range.seen() {
                        range.largest_magnitude().0
                    } else {
                        f64::NAN
                    };
                    bodies.push((format!("{}.{name}", v.name), a));
                }
            }
        }
        Run::Rolling(rr) => {
            let [rn, ..] = rr.contact;
            disks.push(DiskRow {
                name: "disk".into(),
                rn_min: rn.min,
                rn_max: rn.max,
                rn_mean_min: f64::NAN,
                rn_mean_max: f64::NAN,
                left_track_t: f64::NAN,
            });
        }
    }
    Summary {
        stop: r.header().stop.name().to_string(),
        t_end: r.header().t_end,
        energy_drift: r.header().energy.max_rel_drift(),
        steps: r.header().stats.steps,
        rejected: r.header().stats.rejected,
        rhs_evals: r.header().stats.rhs_evals,
        wall_s: r.header().stats.wall_s,
        probes,
        disks,
        bodies,
    }
}

/// Run the scene at every value of one setting, on every core.
pub fn run_sweep(
    spec: &SceneSpec,
    setting: &Setting,
    over: &Overrides,
    show_progress: bool,
) -> Result<Vec<SweepRow>, Error> {
    run_grid(spec, std::slice::from_ref(setting), over, show_progress)
}

/// Run the scene at every combination of the settings' values, on every core.
pub fn run_grid(
    spec: &SceneSpec,
    settings: &[Setting],
    over: &Overrides,
    show_progress: bool,
) -> Result<Vec<SweepRow>, Error> {
    let grid = grid(spec, settings)?;
    // A scene that fails at both ends of a one-key range is the command's error.
    if let [s] = settings {
        let all = s.all();
        let planner = Planner::default();
        let at = |v: &Value| {
            case_spec(spec, std::slice::from_ref(&s.key), std::slice::from_ref(v))
                .and_then(|c| planner.plan(&c))
        };
        if let (Err(e), Err(_)) = (at(&all[0]), at(&all[all.len() - 1])) {
            return Err(Error::Input(format!("--set {}: {e}", s.key)));
        }
    }
    let keys: Vec<String> = settings.iter().map(|s| s.key.clone()).collect();
    Ok(run_cases(spec, &keys, &grid, over, show_progress))
}

/// Every combination of the settings' values, in the order the rows are reported: numbers
/// ascending within each key, names in the order given, keys in the order given. A key the
/// scene cannot hold, or a value it cannot take (a fraction for an element count, a name the
/// key does not know), is the command's error, not every run's.
pub fn grid(spec: &SceneSpec, settings: &[Setting]) -> Result<Vec<Vec<Value>>, Error> {
    settings
        .iter()
        .try_fold(1_usize, |n, s| n.checked_mul(s.all().len()))
        .filter(|&n| n <= MAX_CASES)
        .ok_or_else(|| {
            Error::Input(format!(
                "the --set options make more than {MAX_CASES} cases; sweep fewer values"
            ))
        })?;
    for s in settings {
        for value in s.all() {
            s.apply(&mut spec.clone(), &value)
                .map_err(|e| Error::Input(format!("--set {}: {e}", s.key)))?;
        }
    }
    let mut grid: Vec<Vec<Value>> = vec![Vec::new()];
    for s in settings {
        let values = s.in_row_order();
        grid = grid
            .into_iter()
            .flat_map(|case| {
                values.iter().map(move |v| {
                    let mut c = case.clone();
                    c.push(v.clone());
                    c
                })
            })
            .collect();
    }
    Ok(grid)
}

/// The values of row `i` of [`grid`], without building the grid: the last key varies fastest.
pub fn case_at(settings: &[Setting], mut i: usize) -> Option<Vec<Value>> {
    let mut values = Vec::with_capacity(settings.len());
    for s in settings.iter().rev() {
        let all = s.in_row_order();
        values.push(all.get(i % all.len().max(1))?.clone());
        i /= all.len().max(1);
    }
    values.reverse();
    (i == 0).then_some(values)
}

/// One row per case, in the order of the cases, the runs spread over every core.
pub fn run_cases(
    spec: &SceneSpec,
    keys: &[String],
    cases: &[Vec<Value>],
    over: &Overrides,
    show_progress: bool,
) -> Vec<SweepRow> {
    // The cases share one planner: those on one beam under one heaviest load plan its mesh,
    // model and ρ∞ once (the mesh's eigenproblems were a tenth of an HSLM case).
    let planner = Planner::default();
    let outcomes = super::parallel::map(cases, show_progress, |case| {
        planned_case(&planner, spec, keys, case, over)
    });
    cases.iter().cloned().zip(outcomes).map(row).collect()
}

/// One case run: its summary, or why it could not run.
pub fn run_case(
    spec: &SceneSpec,
    keys: &[String],
    values: &[Value],
    over: &Overrides,
) -> Result<Summary, String> {
    planned_case(&Planner::default(), spec, keys, values, over)
}

fn planned_case(
    planner: &Planner,
    spec: &SceneSpec,
    keys: &[String],
    values: &[Value],
    over: &Overrides,
) -> Result<Summary, String> {
    case_spec(spec, keys, values)
        .and_then(|c| planner.plan(&c))
        .and_then(|scene| run_planned(&scene, over))
        .map_err(|e| e.to_string())
}

/// A planned case run as a sweep runs it: the envelope along the beam left unwatched, the
/// history unrecorded (on HSLM's sweep the rows cost a fifth of a case and moved no number
/// `sweep.csv` reports).
pub(crate) fn run_planned(scene: &crate::scene::Scene, over: &Overrides) -> Result<Summary, Error> {
    let over = Overrides {
        no_envelope: true,
        no_history: true,
        ..over.clone()
    };
    run::run(scene, &over, false).map(|r| summarise(&r))
}

/// A case's row from its values and outcome.
pub fn row((values, outcome): (Vec<Value>, Result<Summary, String>)) -> SweepRow {
    SweepRow {
        value: match values.first() {
            Some(Value::Number(v)) => *v,
            _ => f64::NAN,
        },
        values,
        outcome,
    }
}

/// `sweep.csv` (one row per case) and `sweep.svg`: the probes' extreme deflections (or, on a
/// rigid curve, the disk's normal reaction) against the first key; over a train's speed and
/// its HSLM names, the deck acceleration and deflection per train with their envelope.
pub fn write_sweep(rows: &[SweepRow], setting: &Setting, dir: &Path) -> Result<(), Error> {
    write_grid(rows, std::slice::from_ref(setting), dir)
}

pub fn write_grid(rows: &[SweepRow], settings: &[Setting], dir: &Path) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(|e| crate::output::io_error(dir, e))?;
    let probe_names = probe_names(rows);
    let keys: Vec<String> = settings.iter().map(|s| s.key.clone()).collect();
    write(&dir.join("sweep.csv"), &sweep_csv(rows, &keys))?;
    comfort(rows, settings, dir)?;
    match settings {
        [speed, names] | [names, speed]
            if speed.numeric() && !names.numeric() && !probe_names.is_empty() =>
        {
            let x = settings.iter().position(|s| s == speed).unwrap_or(0);
            train_charts(rows, speed, x, &probe_names[0], dir)
        }
        _ => sweep_chart(rows, &settings[0], &probe_names, dir),
    }
}

/// With vehicles, `comfort.svg`: each body's largest vertical acceleration against the first
/// key swept over a range (over a grid, one series per value of the others), with EN 1990's
/// comfort levels.
fn comfort(rows: &[SweepRow], settings: &[Setting], dir: &Path) -> Result<(), Error> {
    let x = settings.iter().position(Setting::numeric);
    let Some(x) = x.filter(|_| !body_names(rows).is_empty()) else {
        return Ok(());
    };
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for r in rows {
        let (Ok(s), Value::Number(value)) = (r.outcome.as_ref(), &r.values[x]) else {
            continue;
        };
        let others: Vec<String> = (0..settings.len())
            .filter(|&k| k != x)
            .map(|k| format!("{} = {}", settings[k].key, r.values[k]))
            .collect();
        let others = others.join(", ");
        for (name, a) in s.bodies.iter().filter(|(_, a)| a.is_finite()) {
            let label = if others.is_empty() {
                name.clone()
            } else {
                format!("{name} ({others})")
            };
            match series.iter_mut().find(|(n, _)| *n == label) {
                Some((_, points)) => points.push((*value, *a)),
                None => series.push((label, vec![(*value, *a)])),
            }
        }
    }
    let key = &settings[x].key;
    crate::output::beam::comfort_chart(
        &dir.join("comfort.svg"),
        &format!("the vehicles' bodies over {key}"),
        &with_unit(key),
        &series,
    )
}

/// The vehicles' bodies of the first case that ran, as `<vehicle>.<body>`.
fn body_names(rows: &[SweepRow]) -> Vec<String> {
    rows.iter()
        .find_map(|r| r.outcome.as_ref().ok())
        .map_or(Vec::new(), |s| {
            s.bodies.iter().map(|b| b.0.clone()).collect()
        })
}

/// The disks any case that ran reports, in the order first met.
/// The disks some case reported, each with whether some case averaged its contact force (a
/// disk that never did has no mean columns).
fn disk_names(rows: &[SweepRow]) -> Vec<(String, bool)> {
    let mut names: Vec<(String, bool)> = Vec::new();
    for s in rows.iter().filter_map(|r| r.outcome.as_ref().ok()) {
        for d in &s.disks {
            let averaged = d.rn_mean_min.is_finite();
            match names.iter_mut().find(|(name, _)| *name == d.name) {
                Some((_, seen)) => *seen |= averaged,
                None => names.push((d.name.clone(), averaged)),
            }
        }
    }
    names
}

/// A disk's cells in a row that has none of its numbers.
fn empty_disk_cells(averaged: bool) -> String {
    if averaged { ",,,,," } else { ",,," }.to_string()
}

/// The probes of the first case that ran.
fn probe_names(rows: &[SweepRow]) -> Vec<String> {
    rows.iter()
        .find_map(|r| r.outcome.as_ref().ok())
        .map_or(Vec::new(), |s| {
            s.probes.iter().map(|p| p.0.clone()).collect()
        })
}

/// `sweep.csv`: one row per case: its values, status, stop, solver effort, and the disk's and
/// probes' extremes.
pub fn sweep_csv(rows: &[SweepRow], keys: &[String]) -> String {
    let probe_names = &probe_names(rows);
    // A scene without a disk (a train, loads) has no disk columns.
    let disks = disk_names(rows);
    let mut csv = format!(
        "{},status,stopped,t_end,energy_drift,steps,rejected,rhs_evals,wall_s",
        keys.join(",")
    );
    for (d, averaged) in &disks {
        let _ = write!(csv, ",{d}.rn_min,{d}.rn_max");
        if *averaged {
            let _ = write!(csv, ",{d}.rn_mean_min,{d}.rn_mean_max");
        }
        let _ = write!(csv, ",{d}.left_track_t");
    }
    for p in probe_names {
        let _ = write!(
            csv,
            ",{p}.w_min,{p}.w_max,{p}.w_amplitude_after_exit,{p}.a_max"
        );
    }
    let bodies = body_names(rows);
    for b in &bodies {
        let _ = write!(csv, ",{b}.a_max");
    }
    csv.push('\n');
    let cell = |v: f64| {
        if v.is_nan() {
            String::new()
        } else {
            format!("{v}")
        }
    };
    for r in rows {
        let values: Vec<String> = r.values.iter().map(csv_cell).collect();
        let values = values.join(",");
        match &r.outcome {
            Ok(s) => {
                let _ = write!(
                    csv,
                    "{values},ok,{},{},{},{},{},{},{}",
                    s.stop, s.t_end, s.energy_drift, s.steps, s.rejected, s.rhs_evals, s.wall_s,
                );
                for (name, averaged) in &disks {
                    match s.disks.iter().find(|d| d.name == *name) {
                        Some(d) => {
                            let _ = write!(csv, ",{},{}", cell(d.rn_min), cell(d.rn_max));
                            if *averaged {
                                let (lo, hi) = (d.rn_mean_min, d.rn_mean_max);
                                let _ = write!(csv, ",{},{}", cell(lo), cell(hi));
                            }
                            let _ = write!(csv, ",{}", cell(d.left_track_t));
                        }
                        None => csv.push_str(&empty_disk_cells(*averaged)),
                    }
                }
                for p in &s.probes {
                    let _ = write!(csv, ",{},{},{},{}", p.1, p.2, cell(p.3), p.4);
                }
                for b in &s.bodies {
                    let _ = write!(csv, ",{}", cell(b.1));
                }
            }
            Err(e) => {
                let _ = write!(csv, "{values},\"failed: {}\",,,,,,,", e.replace('"', "'"));
                for (_, averaged) in &disks {
                    csv.push_str(&empty_disk_cells(*averaged));
                }
                for _ in probe_names {
                    csv.push_str(",,,,");
                }
                for _ in &bodies {
                    csv.push(',');
                }
            }
        }
        csv.push('\n');
    }
    csv
}

/// Over a train's speed (the key at position `x` of each case) and a list of names: the
/// probe's largest acceleration and deflection against speed, a line per name, their
/// envelope, and on the acceleration figure EN 1991-2's limit for ballasted track.
fn train_charts(
    rows: &[SweepRow],
    speed: &Setting,
    x: usize,
    probe: &str,
    dir: &Path,
) -> Result<(), Error> {
    let name_of = |r: &SweepRow| r.values[1 - x].to_string();
    let mut names: Vec<String> = Vec::new();
    for r in rows {
        if !names.contains(&name_of(r)) {
            names.push(name_of(r));
        }
    }
    for (file, what, pick) in [
        (
            "sweep.svg",
            format!("{probe}: largest |a| (m/s²)"),
            (|s: &Summary| s.probes[0].4) as fn(&Summary) -> f64,
        ),
        (
            "sweep-deflection.svg",
            format!("{probe}: largest |w| (m)"),
            |s: &Summary| s.probes[0].1.abs().max(s.probes[0].2.abs()),
        ),
    ] {
        let point = |r: &SweepRow| -> Option<(f64, f64)> {
            let Value::Number(v) = r.values[x] else {
                return None;
            };
            r.outcome.as_ref().ok().map(|s| (v, pick(s)))
        };
        let series: Vec<(String, Vec<(f64, f64)>)> = names
            .iter()
            .map(|n| {
                (
                    n.clone(),
                    rows.iter()
                        .filter(|r| name_of(r) == *n)
                        .filter_map(point)
                        .collect(),
                )
            })
            .collect();
        let envelope: Vec<(f64, f64)> = speed
            .values()
            .iter()
            .filter_map(|&v| {
                rows.iter()
                    .filter(|r| r.values[x] == Value::Number(v))
                    .filter_map(point)
                    .map(|p| p.1)
                    .reduce(f64::max)
                    .map(|a| (v, a))
            })
            .collect();
        let mut references = vec![("envelope".to_string(), envelope)];
        if file == "sweep.svg" {
            let speeds = speed.values();
            let lo = speeds.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = speeds.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            references.push((
                "EN 1991-2 limit, ballasted track".to_string(),
                vec![(lo, BALLASTED_LIMIT), (hi, BALLASTED_LIMIT)],
            ));
        }
        fn drawn(s: &[(String, Vec<(f64, f64)>)]) -> Vec<(&str, Vec<(f64, f64)>)> {
            s.iter()
                .filter(|(_, pts)| !pts.is_empty())
                .map(|(n, pts)| (n.as_str(), pts.clone()))
                .collect()
        }
        line_chart_with_references(
            &dir.join(file),
            &format!("sweep over {} per train", speed.key),
            &with_unit(&speed.key),
            &what,
            &drawn(&series),
            &drawn(&references),
        )?;
    }
    Ok(())
}

/// The probes' lowest deflections and residual amplitudes (or, on a rigid curve, the disk's
/// extreme R_n) against the swept value.
fn sweep_chart(
    rows: &[SweepRow],
    setting: &Setting,
    probe_names: &[String],
    dir: &Path,
) -> Result<(), Error> {
    let ok: Vec<(f64, &Summary)> = rows
        .iter()
        .filter(|r| r.value.is_finite())
        .filter_map(|r| r.outcome.as_ref().ok().map(|s| (r.value, s)))
        .collect();
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for (k, p) in probe_names.iter().enumerate() {
        series.push((
            format!("{p}: lowest w"),
            ok.iter().map(|(v, s)| (*v, s.probes[k].1)).collect(),
        ));
        series.push((
            format!("{p}: amplitude after the last load left"),
            ok.iter()
                .filter(|(_, s)| s.probes[k].3.is_finite())
                .map(|(v, s)| (*v, s.probes[k].3))
                .collect(),
        ));
    }
    let (y_desc, series) = if series.is_empty() {
        (
            "R_n (N)",
            vec![
                (
                    "lowest R_n".to_string(),
                    ok.iter()
                        .filter_map(|(v, s)| s.disks.first().map(|d| (*v, d.rn_min)))
                        .collect(),
                ),
                (
                    "highest R_n".to_string(),
                    ok.iter()
                        .filter_map(|(v, s)| s.disks.first().map(|d| (*v, d.rn_max)))
                        .collect(),
                ),
            ],
        )
    } else {
        ("w (m)", series)
    };
    let series: Vec<(&str, Vec<(f64, f64)>)> = series
        .iter()
        .filter(|(_, pts)| !pts.is_empty())
        .map(|(n, pts)| (n.as_str(), pts.clone()))
        .collect();
    if series.is_empty() {
        return Ok(());
    }
    line_chart(
        &dir.join("sweep.svg"),
        &format!("sweep over {}", setting.key),
        &with_unit(&setting.key),
        y_desc,
        &series,
    )
}

/// A swept key as an axis label, with the unit the scene format gives it.
fn with_unit(key: &str) -> String {
    let unit = match key.rsplit('.').next().unwrap_or(key) {
        "speed" | "v0" => "m/s",
        "omega0" => "1/s",
        "mass" => "kg",
        "radius" | "s0" | "x" | "patch" | "depth" | "x0" => "m",
        "E" | "G" => "Pa",
        "rho" => "kg/m³",
        "A" | "Av" => "m²",
        "I" => "m⁴",
        "duration" | "interval" => "s",
        "load" | "fx" | "fy" => "N",
        "gravity" | "acceleration" => "m/s²",
        "acceleration_cutoff_hz" => "Hz",
        _ => return key.to_string(),
    };
    format!("{key} ({unit})")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A range's values run from FROM to TO inclusive, and a range without a count is refused.
    #[test]
    fn setting_values_span_the_range() {
        assert_eq!(
            Setting::parse("disk.omega0=-10:-120:111").unwrap().values()[110],
            -120.0
        );
        assert!(Setting::parse("disk.omega0=-10:-120").is_err());
    }

    /// A number key takes one value or a list, swept in ascending order; a name key keeps
    /// its names even where they read as numbers, and a word in a number list is refused.
    #[test]
    fn a_number_key_takes_a_list() {
        let speeds = Setting::parse("train.speed=100,80.5,90").unwrap();
        assert_eq!(speeds.values(), vec![100.0, 80.5, 90.0]);
        let ordered: Vec<String> = speeds
            .in_row_order()
            .iter()
            .map(|v| v.to_string())
            .collect();
        assert_eq!(ordered, ["80.5", "90", "100"]);
        assert_eq!(
            Setting::parse("train.speed=90").unwrap().values(),
            vec![90.0]
        );
        assert_eq!(
            Setting::parse("name=1,2").unwrap().sweep,
            Sweep::Names(vec!["1".into(), "2".into()])
        );
        assert!(Setting::parse("train.speed=90,fast").is_err());
        assert!(Setting::parse("train.speed=90,inf").is_err());
    }

    /// A swept number is written so that it reads back to itself, in few characters at
    /// either end of the doubles' range, and as plain digits in between.
    #[test]
    fn a_swept_number_reads_back_in_few_characters() {
        for v in [
            1e-300,
            -2.5e-308,
            f64::MIN_POSITIVE / 3.0,
            1e-5,
            0.1,
            0.0,
            -90.0,
            123456.789,
            9.999e15,
            1e16,
            1.7976931348623157e308,
        ] {
            let text = number_text(v);
            assert_eq!(text.parse::<f64>().unwrap(), v, "{text}");
            assert!(text.len() <= 24, "{text}");
        }
        assert_eq!(number_text(90.0), "90");
        assert_eq!(number_text(1e-300), "1e-300");
    }
}

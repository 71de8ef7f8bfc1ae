//! A sweep that outgrows one machine, without a scheduler of our own: `sweep --plan DIR`
//! writes one scene file per case, `sweep --plan DIR --shard K/N` (or `rollbeam run` on one
//! case file) runs cases anywhere the folder is visible, skipping those done, and
//! `sweep --merge DIR` writes the usual `sweep.csv` and figures. Any job array or `parallel`
//! line drives it (README.md shows both).
//!
//! The folder:
//! - `plan.yaml`: the scene's name, the `--set` options, and the case ids in row order;
//! - `cases/<id>.yaml`: each case's whole scene, its values and solver flags written in, so
//!   that a case file runs alone; the id is the case's row number and the hash of that text;
//! - `done/<id>.yaml`: each case's record (its values and summary, or why it failed), written
//!   whole or not at all, which is what "done" means.
//!
//! The Python package's `sweep` sends the same records through an executor and merges them
//! with the same function.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{
    case_at, case_spec, grid, row, summarise, DiskRow, Setting, Summary, SweepRow, Value, MAX_CASES,
};
use crate::error::{quote, Error};
use crate::files::{read_text, write_whole};
use crate::output::{io_error, yaml};
use crate::plan::Planner;
use crate::run::{Overrides, Run, Stop};
use crate::scene::SceneSpec;

/// Largest plan file read back: the ids of [`MAX_CASES`] cases with room to spare.
const MAX_PLAN_BYTES: u64 = 16 << 20;
/// Largest case record read back: a summary of a few probes is under a kilobyte.
const MAX_RECORD_BYTES: u64 = 1 << 20;

/// `plan.yaml`.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Plan {
    scene: String,
    sets: Vec<String>,
    cases: Vec<String>,
}

/// One case's outcome as `done/<id>.yaml` holds it, and as the Python package passes it
/// between processes. Quantities a run does not have (no exit, no disk) are left out rather
/// than written as NaN.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Record {
    values: Vec<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ok: Option<RecordSummary>,
    #[serde(skip_serializing_if = "Option::is_none")]
    failed: Option<String>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RecordSummary {
    stop: String,
    t_end: f64,
    energy_drift: f64,
    steps: usize,
    rejected: usize,
    rhs_evals: usize,
    wall_s: f64,
    probes: Vec<RecordProbe>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    disks: Vec<RecordDisk>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    bodies: Vec<RecordBody>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RecordBody {
    name: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    a_max: Option<f64>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RecordProbe {
    name: String,
    w_min: f64,
    w_max: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    w_amplitude_after_exit: Option<f64>,
    a_max: f64,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RecordDisk {
    name: String,
    rn_min: f64,
    rn_max: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    rn_mean_min: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    rn_mean_max: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    left_track_t: Option<f64>,
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

impl RecordSummary {
    /// What in the summary no run records, if anything.
    fn implausible(&self) -> Option<String> {
        if !Stop::ALL.iter().any(|s| s.name() == self.stop) {
            let names: Vec<&str> = Stop::ALL.iter().map(|s| s.name()).collect();
            return Some(format!(
                "its stop is {}, none of the ways a run ends ({})",
                quote(&self.stop),
                names.join(", ")
            ));
        }
        let mut sizes = vec![
            ("t_end", Some(self.t_end)),
            ("energy_drift", Some(self.energy_drift)),
            ("wall_s", Some(self.wall_s)),
        ];
        let mut ranges = Vec::new();
        for p in &self.probes {
            sizes.push(("a_max", Some(p.a_max)));
            sizes.push(("w_amplitude_after_exit", p.w_amplitude_after_exit));
            ranges.push(("w_min", p.w_min, "w_max", p.w_max));
        }
        for d in &self.disks {
            sizes.push(("left_track_t", d.left_track_t));
            ranges.push(("rn_min", d.rn_min, "rn_max", d.rn_max));
            if let (Some(lo), Some(hi)) = (d.rn_mean_min, d.rn_mean_max) {
                ranges.push(("rn_mean_min", lo, "rn_mean_max", hi));
            }
        }
        sizes.extend(self.bodies.iter().map(|b| ("a_max", b.a_max)));
        let values = sizes
            .iter()
            .filter_map(|(name, v)| v.map(|v| (*name, v)))
            .chain(ranges.iter().flat_map(|&(a, lo, b, hi)| [(a, lo), (b, hi)]));
        for (name, v) in values {
            if !v.is_finite() {
                return Some(format!("its {name} is {v}, not a finite number"));
            }
        }
        if let Some((name, v)) = sizes
            .iter()
            .find_map(|(name, v)| v.filter(|v| *v < 0.0).map(|v| (name, v)))
        {
            return Some(format!("its {name} is {v}, less than zero"));
        }
        ranges
            .iter()
            .find(|(_, lo, _, hi)| lo > hi)
            .map(|(a, lo, b, hi)| format!("its {a} = {lo} lies above its {b} = {hi}"))
    }
}

impl Record {
    pub fn of(row: &SweepRow) -> Record {
        let (ok, failed) = match &row.outcome {
            Ok(s) => (
                Some(RecordSummary {
                    stop: s.stop.clone(),
                    t_end: s.t_end,
                    energy_drift: s.energy_drift,
                    steps: s.steps,
                    rejected: s.rejected,
                    rhs_evals: s.rhs_evals,
                    wall_s: s.wall_s,
                    probes: s
                        .probes
                        .iter()
                        .map(|p| RecordProbe {
                            name: p.0.clone(),
                            w_min: p.1,
                            w_max: p.2,
                            w_amplitude_after_exit: finite(p.3),
                            a_max: p.4,
                        })
                        .collect(),
                    disks: s
                        .disks
                        .iter()
                        .map(|d| RecordDisk {
                            name: d.name.clone(),
                            rn_min: d.rn_min,
                            rn_max: d.rn_max,
                            rn_mean_min: finite(d.rn_mean_min),
                            rn_mean_max: finite(d.rn_mean_max),
                            left_track_t: finite(d.left_track_t),
                        })
                        .collect(),
                    bodies: s
                        .bodies
                        .iter()
                        .map(|(name, a)| RecordBody {
                            name: name.clone(),
                            a_max: finite(*a),
                        })
                        .collect(),
                }),
                None,
            ),
            Err(e) => (None, Some(e.clone())),
        };
        Record {
            values: row.values.iter().map(Value::to_string).collect(),
            ok,
            failed,
        }
    }

    /// The record as text; a summary that holds a non-finite number (a run whose numbers
    /// overflowed) is recorded as that case's failure.
    pub fn to_yaml(&self) -> Result<String, Error> {
        let text = yaml(self)?;
        match crate::output::non_finite(&text) {
            None => Ok(text),
            Some(_) => yaml(&Record {
                values: self.values.clone(),
                ok: None,
                failed: Some("the run's numbers overflowed".into()),
            }),
        }
    }

    /// The record in `text`, read from `source`, refused where it holds what no run
    /// records: an outcome that is not one of `ok` and `failed`, a way to end no run takes, a
    /// number that is not finite (a run's overflow is recorded as its failure), a negative
    /// time, drift or acceleration, or a least value above the largest.
    pub fn from_yaml(text: &str, source: &str) -> Result<Record, Error> {
        let record: Record = serde_saphyr::from_str(text).map_err(|e| {
            Error::Input(format!("{source} is not a case record: {}", first_line(&e)))
        })?;
        let outcomes = match (&record.ok, &record.failed) {
            (Some(_), Some(_)) => Some("both `ok` and `failed`"),
            (None, None) => Some("neither `ok` nor `failed`"),
            _ => None,
        };
        let why = outcomes
            .map(|both| format!("it holds {both}, where a run records one"))
            .or_else(|| record.ok.as_ref().and_then(RecordSummary::implausible));
        match why {
            None => Ok(record),
            Some(why) => Err(Error::Input(format!(
                "{source} is not a record a run writes: {why}; remove it and run the case again"
            ))),
        }
    }

    /// The row it records; a value that reads as a number is one. A record holds one outcome
    /// ([`Record::of`] writes one, [`Record::from_yaml`] refuses any other).
    pub fn row(&self) -> SweepRow {
        let values = self
            .values
            .iter()
            .map(|v| match v.parse::<f64>() {
                Ok(x) if x.is_finite() => Value::Number(x),
                _ => Value::Name(v.clone()),
            })
            .collect();
        let outcome = match &self.ok {
            Some(s) => Ok(Summary {
                stop: s.stop.clone(),
                t_end: s.t_end,
                energy_drift: s.energy_drift,
                steps: s.steps,
                rejected: s.rejected,
                rhs_evals: s.rhs_evals,
                wall_s: s.wall_s,
                probes: s
                    .probes
                    .iter()
                    .map(|p| {
                        (
                            p.name.clone(),
                            p.w_min,
                            p.w_max,
                            p.w_amplitude_after_exit.unwrap_or(f64::NAN),
                            p.a_max,
                        )
                    })
                    .collect(),
                disks: s
                    .disks
                    .iter()
                    .map(|d| DiskRow {
                        name: d.name.clone(),
                        rn_min: d.rn_min,
                        rn_max: d.rn_max,
                        rn_mean_min: d.rn_mean_min.unwrap_or(f64::NAN),
                        rn_mean_max: d.rn_mean_max.unwrap_or(f64::NAN),
                        left_track_t: d.left_track_t.unwrap_or(f64::NAN),
                    })
                    .collect(),
                bodies: s
                    .bodies
                    .iter()
                    .map(|b| (b.name.clone(), b.a_max.unwrap_or(f64::NAN)))
                    .collect(),
            }),
            None => Err(self.failed.clone().unwrap_or_default()),
        };
        row((values, outcome))
    }
}

/// Where a case's record goes.
fn record_path(dir: &Path, id: &str) -> PathBuf {
    dir.join("done").join(format!("{id}.yaml"))
}

/// Write the plan of a sweep into `dir`: one case file per combination of the settings'
/// values, with the solver settings `solver` sets written into each. Returns the number of
/// cases, and of those already done by an earlier plan of the same cases.
pub fn write_plan(
    spec: &SceneSpec,
    settings: &[Setting],
    sets: &[String],
    solver: impl Fn(&mut SceneSpec) -> Result<(), Error>,
    dir: &Path,
) -> Result<(usize, usize), Error> {
    let cases = grid(spec, settings)?;
    let keys: Vec<String> = settings.iter().map(|s| s.key.clone()).collect();
    let name = Planner::default().plan(spec)?.name;
    let case_dir = dir.join("cases");
    for sub in [&case_dir, &dir.join("done")] {
        std::fs::create_dir_all(sub).map_err(|e| io_error(sub, e))?;
    }
    folders_in_place(dir)?;
    let width = cases.len().saturating_sub(1).to_string().len().max(4);
    let mut ids = Vec::with_capacity(cases.len());
    let mut done = 0;
    for (i, values) in cases.iter().enumerate() {
        let mut case = case_spec(spec, &keys, values)?;
        solver(&mut case)?;
        let text = case.to_yaml()?;
        let hash = crate::files::content_hash(&text);
        let hash = hash.trim_start_matches("fnv1a64:");
        let id = format!("{i:0width$}-{hash}");
        let path = case_dir.join(format!("{id}.yaml"));
        if !path.exists() {
            write_whole(&path, &text)?;
        }
        done += usize::from(record_path(dir, &id).exists());
        ids.push(id);
    }
    let plan = Plan {
        scene: name,
        sets: sets.to_vec(),
        cases: ids,
    };
    write_whole(&dir.join("plan.yaml"), &yaml(&plan)?)?;
    Ok((cases.len(), done))
}

/// The reader's sentence without the excerpt of the file it quotes beneath it.
fn first_line(e: &impl std::fmt::Display) -> String {
    let text = e.to_string();
    text.lines()
        .next()
        .unwrap_or_default()
        .trim_start_matches("error: ")
        .to_string()
}

/// A plan folder read back.
fn read_plan(dir: &Path) -> Result<(Plan, Vec<Setting>), Error> {
    let path = dir.join("plan.yaml");
    if !path.is_file() {
        return Err(Error::Input(format!(
            "{} holds no plan.yaml; write one with `rollbeam sweep SCENE --set … --plan {}`",
            dir.display(),
            dir.display()
        )));
    }
    let text = read_text(&path, MAX_PLAN_BYTES, "plan")?;
    let plan: Plan = serde_saphyr::from_str(&text).map_err(|e| {
        Error::Input(format!(
            "{} is not a sweep plan: {}",
            path.display(),
            first_line(&e)
        ))
    })?;
    if plan.sets.is_empty() {
        return Err(Error::Input(format!(
            "{} sets no key (`sets: []`); a plan sweeps at least one --set; write the plan again",
            path.display()
        )));
    }
    let settings: Vec<Setting> = plan
        .sets
        .iter()
        .map(|s| Setting::parse(s))
        .collect::<Result<_, _>>()
        .map_err(|e| Error::Input(format!("{}: {e}", path.display())))?;
    let count = settings
        .iter()
        .try_fold(1_usize, |n, s| n.checked_mul(s.all().len()));
    if plan.cases.len() > MAX_CASES || count != Some(plan.cases.len()) {
        return Err(Error::Input(format!(
            "{} lists {} cases where its --set options make {}; write the plan again",
            path.display(),
            plan.cases.len(),
            count.map_or("too many".to_string(), |c| c.to_string())
        )));
    }
    if let Some(bad) = plan.cases.iter().find(|id| !valid_id(id)) {
        return Err(Error::Input(format!(
            "{} names the case {}, which is not a case id (digits, '-', hex digits)",
            path.display(),
            quote(bad)
        )));
    }
    folders_in_place(dir)?;
    Ok((plan, settings))
}

/// The plan's `cases/` and `done/` are folders inside it, not links elsewhere: a shard writes
/// its records into the plan folder and nowhere else.
fn folders_in_place(dir: &Path) -> Result<(), Error> {
    for sub in ["cases", "done"] {
        let path = dir.join(sub);
        if !crate::files::is_real_dir(&path) {
            return Err(Error::Input(format!(
                "{} is not a folder of the plan (missing, or a link elsewhere); write the plan again",
                path.display()
            )));
        }
    }
    Ok(())
}

/// The text of case `id`'s scene, checked against the hash its id carries: a case file
/// swapped or edited after planning is not the case the plan lists.
fn case_text(dir: &Path, id: &str) -> Result<String, Error> {
    let path = dir.join("cases").join(format!("{id}.yaml"));
    let text = read_text(&path, crate::scene::MAX_SCENE_BYTES, "case file")?;
    let hash = crate::files::content_hash(&text);
    let (_, expected) = id.split_once('-').unwrap_or(("", id));
    if hash.trim_start_matches("fnv1a64:") != expected {
        return Err(Error::Input(format!(
            "{} is not the case its name says (its text hashes to {}, the id says {expected}): it was edited or swapped after planning; write the plan again",
            path.display(),
            hash.trim_start_matches("fnv1a64:")
        )));
    }
    Ok(text)
}

/// Check that the file `rollbeam run` was given as case `id` of the plan in `dir` is that case.
pub fn check_case(dir: &Path, id: &str) -> Result<(), Error> {
    case_text(dir, id).map(|_| ())
}

/// A case id names a file inside the plan folder and nothing else.
fn valid_id(id: &str) -> bool {
    id.split_once('-').is_some_and(|(n, h)| {
        !n.is_empty()
            && n.bytes().all(|b| b.is_ascii_digit())
            && !h.is_empty()
            && h.bytes().all(|b| b.is_ascii_hexdigit())
    })
}

/// `K/N`: shard K (1-based) of N.
pub fn parse_shard(text: &str) -> Result<(usize, usize), Error> {
    let bad = || {
        Error::Input(format!(
            "--shard {} must be K/N with 1 ≤ K ≤ N (e.g. 3/16)",
            quote(text)
        ))
    };
    let (k, n) = text.split_once('/').ok_or_else(bad)?;
    let k: usize = k.trim().parse().map_err(|_| bad())?;
    let n: usize = n.trim().parse().map_err(|_| bad())?;
    if k == 0 || k > n {
        return Err(bad());
    }
    Ok((k, n))
}

/// What a shard did.
pub struct ShardReport {
    pub ran: usize,
    pub skipped: usize,
    pub failed: usize,
}

/// Run shard k of n of the plan in `dir`: the cases whose row number is k − 1 modulo n,
/// those without a record, on every core of this machine.
pub fn run_shard(
    dir: &Path,
    k: usize,
    n: usize,
    show_progress: bool,
) -> Result<ShardReport, Error> {
    let (plan, settings) = read_plan(dir)?;
    let mine: Vec<&String> = plan
        .cases
        .iter()
        .enumerate()
        .filter(|(i, _)| i % n == k - 1)
        .map(|(_, id)| id)
        .collect();
    let todo: Vec<&String> = mine
        .iter()
        .copied()
        .filter(|id| !record_path(dir, id).exists())
        .collect();
    let planner = Planner::default();
    let outcomes = super::super::parallel::map(&todo, show_progress, |id| {
        let case = dir.join("cases").join(format!("{id}.yaml"));
        let text = case_text(dir, id)?;
        let values = case_values(&plan, &settings, id)?;
        // A case the plan's settings made invalid fails alone, as in a sweep run at once; a
        // case file that is not the plan's stops the shard (`case_text`).
        let outcome = SceneSpec::parse(&text, &case.display().to_string(), id)
            .and_then(|spec| planner.plan(&spec))
            .and_then(|scene| super::run_planned(&scene, &Overrides::default()))
            .map_err(|e| e.to_string());
        let record = Record::of(&row((values, outcome)));
        write_whole(&record_path(dir, id), &record.to_yaml()?)?;
        Ok::<bool, Error>(record.failed.is_some())
    });
    let mut failed = 0;
    for outcome in outcomes {
        failed += usize::from(outcome?);
    }
    Ok(ShardReport {
        ran: todo.len(),
        skipped: mine.len() - todo.len(),
        failed,
    })
}

/// The values of case `id`, from its row number (the id's first part) in the plan's grid.
fn case_values(plan: &Plan, settings: &[Setting], id: &str) -> Result<Vec<Value>, Error> {
    id.split_once('-')
        .and_then(|(i, _)| i.parse::<usize>().ok())
        .filter(|&i| plan.cases.get(i).is_some_and(|c| c == id))
        .and_then(|i| case_at(settings, i))
        .ok_or_else(|| Error::Input(format!("the plan has no case {}", quote(id))))
}

/// The plan folder and id of a case file (`DIR/cases/<id>.yaml` listed in `DIR/plan.yaml`),
/// or `None` for any other scene file.
pub fn planned_case(path: &Path) -> Option<(PathBuf, String)> {
    let cases = path.parent()?;
    if cases.file_name()? != "cases" {
        return None;
    }
    let dir = cases.parent()?.to_path_buf();
    let id = path.file_stem()?.to_str()?.to_string();
    let (plan, _) = read_plan(&dir).ok()?;
    plan.cases.contains(&id).then_some((dir, id))
}

/// Whether case `id` of the plan in `dir` has its record.
pub fn is_done(dir: &Path, id: &str) -> bool {
    record_path(dir, id).exists()
}

/// Record a case that `rollbeam run` ran from its case file.
pub fn record_case(dir: &Path, id: &str, run: &Run) -> Result<(), Error> {
    let (plan, settings) = read_plan(dir)?;
    let values = case_values(&plan, &settings, id)?;
    let record = Record::of(&row((values, Ok(summarise(run)))));
    write_whole(&record_path(dir, id), &record.to_yaml()?)
}

/// The rows and settings of a plan whose cases are all done.
pub fn merge(dir: &Path) -> Result<(String, Vec<SweepRow>, Vec<Setting>), Error> {
    let (plan, settings) = read_plan(dir)?;
    let missing: Vec<&String> = plan
        .cases
        .iter()
        .filter(|id| !record_path(dir, id).exists())
        .collect();
    if let Some(first) = missing.first() {
        return Err(Error::Input(format!(
            "{} of the {} cases planned in {} have no record yet (the first: {first}); run them with `rollbeam sweep --plan {} --shard K/N`",
            missing.len(),
            plan.cases.len(),
            dir.display(),
            dir.display()
        )));
    }
    let records = plan
        .cases
        .iter()
        .map(|id| {
            let path = record_path(dir, id);
            let text = read_text(&path, MAX_RECORD_BYTES, "case record")?;
            let source = path.display().to_string();
            let record = Record::from_yaml(&text, &source)?;
            let values: Vec<String> = case_values(&plan, &settings, id)?
                .iter()
                .map(Value::to_string)
                .collect();
            if record.values != values {
                return Err(Error::Input(format!(
                    "{source} records the values [{}] where the plan's case {id} has [{}]; remove it and run the case again",
                    record.values.join(", "),
                    values.join(", ")
                )));
            }
            Ok((source, record))
        })
        .collect::<Result<Vec<_>, Error>>()?;
    let rows = rows(&records, settings.len())?;
    Ok((plan.scene, rows, settings))
}

/// The rows of the records `(source, record)` of one sweep over `keys` keys, checked against
/// each other before any is used: each holds one value per key, and every case that ran
/// reports the same probes, and a disk if one does. A record that disagrees is named.
pub fn rows(records: &[(String, Record)], keys: usize) -> Result<Vec<SweepRow>, Error> {
    let mut first: Option<(&str, &RecordSummary)> = None;
    for (source, record) in records {
        if record.values.len() != keys {
            return Err(Error::Input(format!(
                "{source} records {} values for a sweep over {keys} keys",
                record.values.len()
            )));
        }
        let Some(summary) = &record.ok else { continue };
        let Some((first_source, expected)) = first else {
            first = Some((source, summary));
            continue;
        };
        let names = |s: &RecordSummary| -> Vec<String> {
            s.probes
                .iter()
                .map(|p| p.name.clone())
                .chain(s.bodies.iter().map(|b| b.name.clone()))
                .collect()
        };
        let disks = |s: &RecordSummary| -> String {
            s.disks.iter().map(|d| format!(" and {}", d.name)).collect()
        };
        if names(summary) != names(expected) || disks(summary) != disks(expected) {
            return Err(Error::Input(format!(
                "{source} reports probes [{}]{} where {first_source} reports [{}]{}: the records are not of one scene",
                names(summary).join(", "),
                disks(summary),
                names(expected).join(", "),
                disks(expected),
            )));
        }
    }
    Ok(records.iter().map(|(_, r)| r.row()).collect())
}

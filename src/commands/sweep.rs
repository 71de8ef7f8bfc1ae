//! `rollbeam sweep SCENE.yaml --set KEY=FROM:TO:COUNT`: one scene over an evenly spaced range
//! of one of its numbers, the runs spread over every core. Each value is set at its key of the
//! scene ([`SceneSpec::set`]) and the scene checked and planned again, so a value the scene
//! cannot take is refused with the same sentence a scene file would get. One summary row per
//! run; a run that fails is a row with its reason.

use super::SolverFlags;
use crate::error::{quote, Error};
use crate::output::plots::line_chart;
use crate::output::write;
use crate::plan::Planner;
use crate::run::{self, Overrides, Run};
use crate::say;
use crate::scene::SceneSpec;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Most cases one sweep runs: each is a whole run, and their rows are held in memory.
pub const MAX_CASES: usize = 100_000;

/// KEY=FROM:TO:COUNT.
#[derive(Clone, Debug, PartialEq)]
pub struct Setting {
    pub key: String,
    pub from: f64,
    pub to: f64,
    pub count: usize,
}

impl Setting {
    pub fn parse(arg: &str) -> Result<Setting, Error> {
        let bad = |why: &str| {
            Error::Input(format!(
                "--set {} {why}; write KEY=FROM:TO:COUNT, e.g. disk.omega0=-10:-120:111",
                quote(arg)
            ))
        };
        let (key, range) = arg.split_once('=').ok_or_else(|| bad("has no '='"))?;
        let parts: Vec<&str> = range.split(':').collect();
        let [from, to, count] = parts[..] else {
            return Err(bad("needs three fields after '='"));
        };
        let number = |s: &str| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(&format!("has {} where a finite number belongs", quote(s))))
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
        if key.split('.').any(|k| k.trim().is_empty()) {
            return Err(bad("has an empty key"));
        }
        Ok(Setting {
            key: key.trim().to_string(),
            from: number(from)?,
            to: number(to)?,
            count,
        })
    }

    pub fn values(&self) -> Vec<f64> {
        if self.count == 1 {
            return vec![self.from];
        }
        (0..self.count)
            .map(|i| self.from + (self.to - self.from) * i as f64 / (self.count - 1) as f64)
            .collect()
    }
}

/// What one run of the sweep reports.
#[derive(Clone, Debug)]
pub struct SweepRow {
    pub value: f64,
    pub outcome: Result<Summary, String>,
}

#[derive(Clone, Debug)]
pub struct Summary {
    pub stop: &'static str,
    pub t_end: f64,
    pub energy_drift: f64,
    pub steps: usize,
    pub wall_s: f64,
    /// Beam scenes: per probe (name, w_min, w_max, amplitude after the disk left or NaN).
    pub probes: Vec<(String, f64, f64, f64)>,
    /// With a disk: (rn_min, rn_max, left_track_t or NaN).
    pub disk: Option<(f64, f64, f64)>,
}

fn summarise(r: &Run) -> Summary {
    let mut probes = Vec::new();
    let mut disk = None;
    match r {
        Run::Beam(b) => {
            for (k, p) in b.setup.probes.iter().enumerate() {
                let w = b.rows.iter().map(|row| row.probes[k].w);
                let (lo, hi) = w.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(v), h.max(v))
                });
                let after = b.amplitude_after_exit(k).unwrap_or(f64::NAN);
                probes.push((p.name.clone(), lo, hi, after));
            }
            let on: Vec<_> = b.rows.iter().filter_map(|row| row.disk).collect();
            if !on.is_empty() {
                let (lo, hi) = on
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), d| {
                        (l.min(d.rn), h.max(d.rn))
                    });
                disk = Some((lo, hi, b.left_track_t.unwrap_or(f64::NAN)));
            }
        }
        Run::Rolling(rr) => {
            let (lo, hi) = rr
                .rows
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), row| {
                    (l.min(row.disk.rn), h.max(row.disk.rn))
                });
            disk = Some((lo, hi, f64::NAN));
        }
    }
    Summary {
        stop: r.header().stop.name(),
        t_end: r.header().t_end,
        energy_drift: r.header().energy.max_rel_drift(),
        steps: r.header().stats.steps,
        wall_s: r.header().stats.wall_s,
        probes,
        disk,
    }
}

/// Run the scene at every value of the setting, on every core.
pub fn run_sweep(
    spec: &SceneSpec,
    setting: &Setting,
    over: &Overrides,
    show_progress: bool,
) -> Result<Vec<SweepRow>, Error> {
    let planner = Planner::default();
    let at = |value: f64| {
        let mut changed = spec.clone();
        changed.set(&setting.key, value)?;
        planner.plan(&changed)
    };
    // A key the scene cannot hold, a value it cannot take (a fraction for an element count),
    // or a scene that fails at both ends of the range is the command's error, not every run's.
    let command_error = |e: Error| Error::Input(format!("--set {}: {e}", setting.key));
    let values = setting.values();
    for &value in &values {
        spec.clone()
            .set(&setting.key, value)
            .map_err(command_error)?;
    }
    if let (Err(e), Err(_)) = (at(setting.from), at(setting.to)) {
        return Err(command_error(e));
    }
    let outcomes = super::parallel::map(&values, show_progress, |&value| {
        at(value)
            .and_then(|scene| run::run(&scene, over, false))
            .map(|r| summarise(&r))
            .map_err(|e| e.to_string())
    });
    let mut rows: Vec<SweepRow> = values
        .into_iter()
        .zip(outcomes)
        .map(|(value, outcome)| SweepRow { value, outcome })
        .collect();
    rows.sort_by(|a, b| a.value.total_cmp(&b.value));
    Ok(rows)
}

/// `sweep.csv` (one row per run) and `sweep.svg` (the probes' extreme deflections, or the
/// disk's normal reaction on a rigid curve, against the parameter).
pub fn write_sweep(rows: &[SweepRow], setting: &Setting, dir: &Path) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(|e| crate::output::io_error(dir, e))?;
    let probe_names: Vec<String> = rows
        .iter()
        .find_map(|r| r.outcome.as_ref().ok())
        .map_or(Vec::new(), |s| {
            s.probes.iter().map(|p| p.0.clone()).collect()
        });
    write(
        &dir.join("sweep.csv"),
        &sweep_csv(rows, setting, &probe_names),
    )?;
    sweep_chart(rows, setting, &probe_names, dir)
}

/// One row per run: its value, status, stop, solver effort, and the disk's and probes' extremes.
fn sweep_csv(rows: &[SweepRow], setting: &Setting, probe_names: &[String]) -> String {
    let mut csv = format!(
        "{},status,stopped,t_end,energy_drift,steps,wall_s,disk.rn_min,disk.rn_max,disk.left_track_t",
        setting.key
    );
    for p in probe_names {
        let _ = write!(csv, ",{p}.w_min,{p}.w_max,{p}.w_amplitude_after_exit");
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
        match &r.outcome {
            Ok(s) => {
                let (lo, hi, left) = s.disk.unwrap_or((f64::NAN, f64::NAN, f64::NAN));
                let _ = write!(
                    csv,
                    "{},ok,{},{},{},{},{},{},{},{}",
                    r.value,
                    s.stop,
                    s.t_end,
                    s.energy_drift,
                    s.steps,
                    s.wall_s,
                    cell(lo),
                    cell(hi),
                    cell(left)
                );
                for p in &s.probes {
                    let _ = write!(csv, ",{},{},{}", p.1, p.2, cell(p.3));
                }
            }
            Err(e) => {
                let _ = write!(
                    csv,
                    "{},\"failed: {}\",,,,,,,,",
                    r.value,
                    e.replace('"', "'")
                );
                for _ in probe_names {
                    csv.push_str(",,,");
                }
            }
        }
        csv.push('\n');
    }
    csv
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
        .filter_map(|r| r.outcome.as_ref().ok().map(|s| (r.value, s)))
        .collect();
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for (k, p) in probe_names.iter().enumerate() {
        series.push((
            format!("{p}: lowest w"),
            ok.iter().map(|(v, s)| (*v, s.probes[k].1)).collect(),
        ));
        series.push((
            format!("{p}: amplitude after the disk left"),
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
                        .filter_map(|(v, s)| s.disk.map(|d| (*v, d.0)))
                        .collect(),
                ),
                (
                    "highest R_n".to_string(),
                    ok.iter()
                        .filter_map(|(v, s)| s.disk.map(|d| (*v, d.1)))
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
        &setting.key,
        y_desc,
        &series,
    )
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
}

#[derive(clap::Args)]
pub struct SweepArgs {
    scene: PathBuf,
    /// KEY=FROM:TO:COUNT, e.g. disk.omega0=-10:-120:111 (any number the scene holds).
    #[arg(long = "set")]
    set: String,
    /// Output folder (default out/<scene name>-sweep).
    #[arg(long)]
    out: Option<PathBuf>,
    #[command(flatten)]
    solver: SolverFlags,
}

/// `rollbeam sweep`.
pub fn sweep(args: SweepArgs) -> Result<(), Error> {
    let SweepArgs {
        scene: path,
        set,
        out,
        solver,
    } = args;
    let spec = SceneSpec::load(&path)?;
    let scene = Planner::default().plan(&spec)?;
    let setting = Setting::parse(&set)?;
    let over = solver.overrides(&scene)?;
    let rows = run_sweep(&spec, &setting, &over, true)?;
    let dir = out.unwrap_or_else(|| Path::new("out").join(format!("{}-sweep", scene.name)));
    write_sweep(&rows, &setting, &dir)?;
    let failed = rows.iter().filter(|r| r.outcome.is_err()).count();
    say!(
        "{}: {} runs over {} from {} to {}, {} failed; wrote {}",
        scene.name,
        rows.len(),
        setting.key,
        setting.from,
        setting.to,
        failed,
        dir.display()
    );
    Ok(())
}

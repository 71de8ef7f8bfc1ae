//! `rollbeam studies`: rerun every scene under `studies/` and regenerate the figures REPORT.md
//! shows, including the side-by-side comparison of the parabola cases.

use std::path::{Path, PathBuf};

use crate::error::Error;
use crate::output::{self, io_error, plots};
use crate::run::{self, Overrides, Run, RunResult};
use crate::say;
use crate::scene::Scene;

/// The scenes under `dir`, sorted by file name.
pub fn scene_files(dir: &Path) -> Result<Vec<PathBuf>, Error> {
    let entries = std::fs::read_dir(dir).map_err(|e| {
        Error::Input(format!(
            "cannot read the studies folder {}: {e}",
            dir.display()
        ))
    })?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "yaml"))
        .collect();
    files.sort();
    Ok(files)
}

/// Run every study, write each into `out/<name>`, and the report figures into `figures`.
pub fn run_all(studies: &Path, out: &Path, figures: &Path) -> Result<Vec<Run>, Error> {
    std::fs::create_dir_all(figures).map_err(|e| io_error(figures, e))?;
    let mut results = Vec::new();
    for file in scene_files(studies)? {
        let scene = Scene::load(&file)?;
        let result = run::run(&scene, &Overrides::default(), true)?;
        let dir = out.join(&scene.name);
        output::write_all(&result, &dir)?;
        if let Run::Beam(b) = &result {
            if b.setup.disk.is_some() {
                output::animation::write_animation(b, &dir.join("animation.svg"))?;
            }
        }
        for fig in result.figures() {
            let from = dir.join(format!("{fig}.svg"));
            let to = figures.join(format!("{}-{fig}.svg", scene.name));
            std::fs::copy(&from, &to).map_err(|e| io_error(&to, e))?;
        }
        say!(
            "{:<14} {:<12} t = {:>7.3} s  steps {:>6}  rejected {:>4}  energy drift {:.1e}  {:.3} s",
            scene.name,
            result.stop().name(),
            result.t_end(),
            result.stats().steps,
            result.stats().rejected,
            result.energy().max_rel_drift(),
            result.stats().wall_s
        );
        results.push(result);
    }
    let rolling: Vec<&RunResult> = results
        .iter()
        .filter_map(|r| {
            if let Run::Rolling(r) = r {
                Some(r)
            } else {
                None
            }
        })
        .collect();
    compare_parabola(&rolling, figures)?;
    Ok(results)
}

/// Study 1 side by side: the four disks' speeds, angular velocities and normal reactions.
fn compare_parabola(results: &[&RunResult], figures: &Path) -> Result<(), Error> {
    let cases: Vec<&RunResult> = results
        .iter()
        .copied()
        .filter(|r| r.scene.name.starts_with("parabola-p"))
        .collect();
    if cases.is_empty() {
        return Ok(());
    }
    let label = |r: &RunResult| {
        format!(
            "{} (m = {}, a = {})",
            &r.scene.name["parabola-".len()..].to_uppercase(),
            r.setup.rolling.disk.mass,
            r.setup.rolling.disk.radius
        )
    };
    let labels: Vec<String> = cases.iter().map(|r| label(r)).collect();
    let pick = |f: fn(&run::Row) -> f64| -> Vec<(&str, Vec<(f64, f64)>)> {
        cases
            .iter()
            .zip(&labels)
            .map(|(r, l)| {
                (
                    l.as_str(),
                    r.rows.iter().map(|row| (row.t, f(row))).collect(),
                )
            })
            .collect()
    };
    plots::line_chart(
        &figures.join("parabola-compare-vx.svg"),
        "Study 1: horizontal centre velocity",
        "t (s)",
        "vx (m/s)",
        &pick(|r| r.disk.vx),
    )?;
    plots::line_chart(
        &figures.join("parabola-compare-omega.svg"),
        "Study 1: angular velocity",
        "t (s)",
        "Ω (1/s)",
        &pick(|r| r.disk.omega),
    )?;
    plots::line_chart(
        &figures.join("parabola-compare-rn.svg"),
        "Study 1: normal reaction",
        "t (s)",
        "R_n (N)",
        &pick(|r| r.disk.rn),
    )?;
    plots::line_chart(
        &figures.join("parabola-compare-rt.svg"),
        "Study 1: tangential reaction",
        "t (s)",
        "R_t (N)",
        &pick(|r| r.disk.rt),
    )
}

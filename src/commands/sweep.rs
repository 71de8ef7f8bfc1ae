//! `rollbeam sweep`: a sweep run here, planned into case files, run in shards, or merged
//! (the work is `workflows::sweep`).

use std::path::{Path, PathBuf};

use super::SolverFlags;
use crate::error::Error;
use crate::plan::Planner;
use crate::say;
use crate::scene::SceneSpec;
use crate::workflows::settings::write_solver;
use crate::workflows::sweep::{cluster, run_grid, write_grid, Setting, SweepRow};

#[derive(clap::Args)]
pub struct SweepArgs {
    /// The scene (not with --merge, nor with --plan and --shard).
    scene: Option<PathBuf>,
    /// KEY=FROM:TO:COUNT (any number the scene holds, e.g. disk.omega0=-10:-120:111), KEY=X,X
    /// (numbers listed, e.g. train.speed=80,90) or KEY=NAME,NAME (a name, e.g.
    /// train.hslm=A1,A2); several make a grid.
    #[arg(long = "set")]
    set: Vec<String>,
    /// Output folder (default out/<scene name>-sweep; with --merge, the plan folder).
    #[arg(long)]
    out: Option<PathBuf>,
    /// With a scene and --set: write the sweep's cases into this folder instead of running
    /// them. With --shard: the plan folder whose cases to run.
    #[arg(long)]
    plan: Option<PathBuf>,
    /// K/N: run the K-th of N shares of the plan's cases (with --plan), skipping those done.
    #[arg(long)]
    shard: Option<String>,
    /// Write sweep.csv and the figures of a plan folder whose cases are all done.
    #[arg(long)]
    merge: Option<PathBuf>,
    #[command(flatten)]
    solver: SolverFlags,
}

/// `rollbeam sweep`.
pub fn sweep(args: SweepArgs) -> Result<(), Error> {
    let SweepArgs {
        scene: path,
        set,
        out,
        plan,
        shard,
        merge,
        solver,
    } = args;
    let no_scene = |what: &str| -> Result<(), Error> {
        if path.is_some() || !set.is_empty() || solver.given() {
            return Err(Error::Input(format!(
                "{what} takes no scene, --set or solver flag: the plan holds them"
            )));
        }
        Ok(())
    };
    match (merge, plan, shard) {
        (Some(dir), None, None) => {
            no_scene("--merge")?;
            let (name, rows, settings) = cluster::merge(&dir)?;
            let out = out.unwrap_or(dir);
            write_grid(&rows, &settings, &out)?;
            report(&name, &rows, &settings, &out);
            Ok(())
        }
        (Some(_), _, _) => Err(Error::Input(
            "--merge is given alone with its plan folder (and --out)".into(),
        )),
        (None, Some(dir), Some(share)) => {
            no_scene("--shard")?;
            if out.is_some() {
                return Err(Error::Input(
                    "--shard writes its records into the plan folder; --out belongs to --merge"
                        .into(),
                ));
            }
            let (k, n) = cluster::parse_shard(&share)?;
            let r = cluster::run_shard(&dir, k, n, true)?;
            say!(
                "shard {k}/{n} of {}: {} cases run ({} failed), {} already done",
                dir.display(),
                r.ran,
                r.failed,
                r.skipped
            );
            Ok(())
        }
        (None, None, Some(_)) => Err(Error::Input(
            "--shard K/N runs a share of a plan; give the plan folder with --plan".into(),
        )),
        (None, plan, None) => {
            let path = path.ok_or_else(|| {
                Error::Input(
                    "sweep needs a scene file, or --merge DIR, or --plan DIR --shard K/N".into(),
                )
            })?;
            if set.is_empty() {
                return Err(Error::Input(
                    "sweep needs at least one --set KEY=FROM:TO:COUNT or KEY=NAME,NAME".into(),
                ));
            }
            let spec = SceneSpec::load(&path)?;
            let scene = Planner::default().plan(&spec)?;
            let settings = parse_settings(&set)?;
            let over = solver.overrides(&scene)?;
            if let Some(dir) = plan {
                if out.is_some() {
                    return Err(Error::Input(
                        "--plan writes into its own folder; --out belongs to a sweep run here or to --merge".into(),
                    ));
                }
                let (cases, done) =
                    cluster::write_plan(&spec, &settings, &set, |c| write_solver(&over, c), &dir)?;
                say!(
                    "{}: planned {cases} cases in {} ({done} already done); run them with `rollbeam sweep --plan {} --shard K/N`, then `rollbeam sweep --merge {}`",
                    scene.name,
                    dir.display(),
                    dir.display(),
                    dir.display()
                );
                return Ok(());
            }
            let rows = run_grid(&spec, &settings, &over, true)?;
            let dir = out.unwrap_or_else(|| Path::new("out").join(format!("{}-sweep", scene.name)));
            write_grid(&rows, &settings, &dir)?;
            report(&scene.name, &rows, &settings, &dir);
            Ok(())
        }
    }
}

/// The --set options, each key once.
fn parse_settings(set: &[String]) -> Result<Vec<Setting>, Error> {
    let settings: Vec<Setting> = set
        .iter()
        .map(|s| Setting::parse(s))
        .collect::<Result<_, _>>()?;
    if let Some(twice) = settings
        .iter()
        .enumerate()
        .find(|(i, s)| settings[..*i].iter().any(|t| t.key == s.key))
    {
        return Err(Error::Input(format!(
            "--set {} is given twice; sweep each key once",
            twice.1.key
        )));
    }
    Ok(settings)
}

fn report(name: &str, rows: &[SweepRow], settings: &[Setting], dir: &Path) {
    let failed = rows.iter().filter(|r| r.outcome.is_err()).count();
    let over_keys: Vec<String> = settings
        .iter()
        .map(|s| format!("{} {}", s.key, s.describe()))
        .collect();
    say!(
        "{}: {} run{} over {}, {} failed; wrote {}",
        name,
        rows.len(),
        if rows.len() == 1 { "" } else { "s" },
        over_keys.join(" × "),
        failed,
        dir.display()
    );
}

//! `rollbeam studies`: rerun every scene under `studies/` and regenerate the figures REPORT.md
//! shows, including the side-by-side comparison of the parabola cases.

use std::path::{Path, PathBuf};

use super::sweep::{run_sweep, Setting};
use super::tradeoff;
use crate::analysis::moving_load::MovingForce;
use crate::beam::{BeamModel, MAX_ORDER};
use crate::coupling::Coupling;
use crate::error::Error;
use crate::ode::Method;
use crate::output::{self, io_error, plots};
use crate::plan::{self, Planner};
use crate::run::{self, Overrides, RollingRun, Run};
use crate::say;
use crate::scene::{BeamScene, Scene, SceneSpec};

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

/// Run every study, write each into `out/<name>`, and the report figures into `figures`;
/// with `with_work_precision`, also each study's work–precision diagram (most of the time).
pub fn run_all(
    studies: &Path,
    out: &Path,
    figures: &Path,
    with_work_precision: bool,
) -> Result<Vec<Run>, Error> {
    std::fs::create_dir_all(figures).map_err(|e| io_error(figures, e))?;
    let scenes = scene_files(studies)?
        .iter()
        .map(|file| Scene::load(file))
        .collect::<Result<Vec<Scene>, Error>>()?;
    // Every beam study with a disk is animated: its frames are kept.
    let over = Overrides {
        animate: true,
        ..Default::default()
    };
    // The studies are independent: they share the cores, and are reported in their order.
    let done = super::parallel::map(&scenes, true, |scene| -> Result<Run, Error> {
        let result = run::run(scene, &over, false)?;
        let dir = out.join(&scene.name);
        output::write_all(&result, &dir, true)?;
        if let Run::Beam(b) = &result {
            if b.setup.disk().is_some() {
                output::animation::write_animation(b, &dir.join("animation.svg"))?;
            }
        }
        for fig in result.figures() {
            let from = dir.join(format!("{fig}.svg"));
            let to = figures.join(format!("{}-{fig}.svg", scene.name));
            std::fs::copy(&from, &to).map_err(|e| io_error(&to, e))?;
        }
        Ok(result)
    });
    let mut results = Vec::new();
    for (scene, result) in scenes.iter().zip(done) {
        let result = result?;
        say!(
            "{:<14} {:<12} t = {:>7.3} s  steps {:>6}  rejected {:>4}  energy drift {:.1e}  {:.3} s",
            scene.name,
            result.header().stop.name(),
            result.header().t_end,
            result.header().stats.steps,
            result.header().stats.rejected,
            result.header().energy.max_rel_drift(),
            result.header().stats.wall_s
        );
        results.push(result);
    }
    let rolling: Vec<&RollingRun> = results
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
    bridge_speed_sweep(studies, figures)?;
    hslm_sweep(studies, out, figures)?;
    railcar_sweep(studies, out, figures)?;
    if with_work_precision {
        work_precision(studies, out, figures)?;
    }
    Ok(results)
}

/// The work–precision diagram of every study, on the grid [`study_plan`] gives it: where
/// each integrator wins, against the reference stored beside the scene.
///
/// Every study's runs share one pool, the tightest rtols first: one study's grid alone waits
/// for its longest run (the rubber's ESDIRK4 at 1e-5 takes half a minute) with a core idle.
fn work_precision(studies: &Path, out: &Path, figures: &Path) -> Result<(), Error> {
    let started = std::time::Instant::now();
    let mut diagrams = Vec::new();
    for file in scene_files(studies)? {
        let scene = Scene::load(&file)?;
        let plan = study_plan(&scene);
        let (reference, origin) =
            tradeoff::reference_for(&scene, &file, &plan, false, "rollbeam studies --references")?;
        say!("{:<14} {origin}", format!("tradeoff {}", scene.name));
        diagrams.push((scene, plan, reference));
    }
    let mut runs: Vec<(usize, usize, tradeoff::GridPoint)> = diagrams
        .iter()
        .enumerate()
        .flat_map(|(k, (_, plan, _))| {
            tradeoff::grid(plan)
                .into_iter()
                .enumerate()
                .map(move |(i, point)| (k, i, point))
        })
        .collect();
    runs.sort_by(|a, b| a.2.rtol.total_cmp(&b.2.rtol));
    let done = super::parallel::map(&runs, true, |&(k, _, point)| {
        let (scene, plan, reference) = &diagrams[k];
        tradeoff::trial(scene, plan, reference, point)
    });
    let mut by_study: Vec<Vec<(usize, tradeoff::Trial)>> =
        diagrams.iter().map(|_| Vec::new()).collect();
    for ((k, i, _), trial) in runs.iter().zip(done) {
        by_study[*k].push((*i, trial));
    }
    for ((scene, _, reference), mut trials) in diagrams.iter().zip(by_study) {
        trials.sort_by_key(|(i, _)| *i);
        let trials: Vec<tradeoff::Trial> = trials.into_iter().map(|(_, t)| t).collect();
        let name = &scene.name;
        let dir = out.join(format!("{name}-tradeoff"));
        for line in tradeoff::write_tradeoff(scene, reference, &trials, &dir)? {
            say!("{:<14} {line}", format!("tradeoff {name}"));
        }
        for figure in ["tradeoff", "tradeoff-means"] {
            let from = dir.join(format!("{figure}.svg"));
            if figure == "tradeoff" || from.exists() {
                let to = figures.join(format!("{name}-{figure}.svg"));
                std::fs::copy(&from, &to).map_err(|e| io_error(&to, e))?;
            }
        }
    }
    say!(
        "{:<14} {} runs for {} diagrams in {:.1} s",
        "tradeoff",
        runs.len(),
        diagrams.len(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Steps a run of a switched-load study's grid may take: the most that ESDIRK4 takes at rtol
/// 1e-4 on them (103 000, C3 on 4 elements) with a margin.
const SWITCHED_LOAD_STEPS: usize = 120_000;

/// The large-deflection study whose diagram reaches 10⁻⁶ in the windowed means within the
/// main job; the zip-line's would take minutes a run.
const DEEP_NONLINEAR: &str = "rubber";

/// The study whose diagram also trades the beam model: the thesis' exact beam against the
/// linear one and modal ones of 4 to 32 modes (REPORT.md, "Beam models and couplings: which to choose").
const MODEL_TRADE: &str = "bridge-d44";

/// The grid a study's work–precision diagram is drawn from, and its reference made against:
/// the method's default (rtol to 1e-8 on a rigid curve, 1e-6 on a beam), cut or deepened by
/// what the study's physics makes a tenfold cut of rtol cost and buy.
pub fn study_plan(scene: &Scene) -> tradeoff::Plan {
    let mut plan = tradeoff::Plan::default_for(scene);
    // The grid of a beam whose damping takes the high modes runs on to rtol 1e-8, past the
    // default on a beam: nothing of the modes a load excites high up rides on the headline, so
    // its reference settles below 10⁻⁶ cheaply (HSLM: rtol 1e-11 and a mesh check) and its
    // diagram can show what 10⁻⁶ costs.
    let damped = scene
        .beam()
        .and_then(|b| b.beam.damping)
        .is_some_and(|d| d.damps_high_modes());
    let switched = scene.beam().is_some_and(|b| b.load_switched());
    if damped {
        plan.rtols = (2..=8).map(|k| 10f64.powi(-k)).collect();
    } else if switched {
        // A load switched on or off excites every mode the mesh holds, and undamped they all
        // stay: ESDIRK4 takes 41 000–103 000 steps at rtol 1e-4 on B1–C3, where it reaches
        // 10⁻⁴–10⁻³, and 205 000–481 000 at 1e-5, which would take the main job past three
        // minutes (docs/numerics.md, "The work–precision grids").
        // Their references still start at 1e-6: a cut made for time must not loosen what the
        // runs are scored against.
        plan.rtols.retain(|&r| r >= 1e-4);
        plan.max_steps = SWITCHED_LOAD_STEPS;
        plan.reference_from = Some(1e-5);
    } else if let Some(b) = scene.beam().filter(|b| plan::responds_nonlinearly(b)) {
        // A large deflection (the rubber, the zip-line): every step iterates on a new tangent,
        // so each tenfold cut of the reference's rtol costs more than the whole job, and their
        // references' meshes resolve only 3.5·10⁻⁴ and 4.7·10⁻⁵: a decade more of grid could
        // not be scored. The grid stops at 1e-4: on the study's meshes rtol 1e-5 bought nothing
        // (no run of it on the rubber's fronts of cost against error, none finished within its
        // budget on the zip-line). The references still start at 1e-6.
        plan.rtols.retain(|&r| r >= 1e-4);
        plan.reference_from = Some(1e-5);
        // 10⁻⁶ in the windowed means takes, on the rubber, twice the mesh at two degrees more
        // and ESDIRK4 at rtol 1e-8 (45 000 steps); on the zip-line generalized-α at 1e-7 on 64
        // elements, 650 000 steps, more than the job's whole budget (REPORT.md,
        // "Work–precision").
        if scene.name == DEEP_NONLINEAR {
            plan.points = vec![finer_point(b, 1e-8)];
        }
    } else if let Some(b) = scene.beam().filter(|b| b.disk().is_some()) {
        // An undamped bridge under a rolling disk (D44, D50). At rtol 1e-6 no run of the exact
        // or linear beam comes within the step budget on the grid's meshes, and the modal ones
        // stay at their truncation's 10⁻⁴; the windowed means on the scene's mesh stop at
        // 4–7·10⁻⁶. Twice the mesh at two degrees more, at rtol 1e-4 (ESDIRK4), brings the
        // means to what the references resolve, 0.4–1.4·10⁻⁶ as the steps fall: that point is
        // run instead of the decades that buy nothing, 1e-6 and 1e-5
        // (no run at 1e-5 was on either bridge's front of cost against error but D44's modal
        // 8 by generalized-α, a hair from 16 modes by ESDIRK4 at 1e-4).
        plan.rtols.retain(|&r| r >= 1e-4);
        plan.reference_from = Some(1e-6);
        plan.points = vec![finer_point(b, 1e-4)];
    }
    if scene.name == MODEL_TRADE {
        plan.models = std::iter::once(BeamModel::Exact)
            .chain(std::iter::once(BeamModel::Linear))
            .chain([4, 8, 16, 32].map(|modes| BeamModel::Modal { modes }))
            .collect();
    }
    plan
}

/// The point past a grid where a study's windowed means reach 10⁻⁶: ESDIRK4 at `rtol` on twice
/// the scene's mesh at two degrees more (the bridges at 1e-4, the rubber at 1e-8).
fn finer_point(b: &BeamScene, rtol: f64) -> tradeoff::GridPoint {
    tradeoff::GridPoint {
        method: Method::Esdirk4,
        rtol,
        elements: Some(2 * b.beam.elements),
        order: Some((b.beam.order + 2).min(MAX_ORDER)),
        model: None,
    }
}

/// The HSLM study (`hslm-15m.yaml`) as EN 1991-2 §6.4 asks it: every train A1–A10 at every
/// speed from 40 to 120 m/s in steps of 1 m/s, 810 runs; the deck acceleration and deflection
/// against speed, a line per train and their envelope (REPORT.md, "Trains and the HSLM sweep").
fn hslm_sweep(studies: &Path, out: &Path, figures: &Path) -> Result<(), Error> {
    let file = studies.join("hslm-15m.yaml");
    if !file.exists() {
        return Ok(());
    }
    let spec = SceneSpec::load(&file)?;
    let names: Vec<String> = (1..=10).map(|k| format!("A{k}")).collect();
    let settings = [
        Setting::parse("train.speed=40:120:81")?,
        Setting::parse(&format!("train.hslm={}", names.join(",")))?,
    ];
    let started = std::time::Instant::now();
    let rows = super::sweep::run_grid(&spec, &settings, &Overrides::default(), true)?;
    let dir = out.join("hslm-15m-sweep");
    super::sweep::write_grid(&rows, &settings, &dir)?;
    say!(
        "{:<14} {} runs in {:.1} s; wrote {}",
        "hslm-15m",
        rows.len(),
        started.elapsed().as_secs_f64(),
        dir.display()
    );
    for (from, to) in [
        ("sweep.svg", "hslm-15m-acceleration.svg"),
        ("sweep-deflection.svg", "hslm-15m-deflection.svg"),
    ] {
        let to = figures.join(to);
        std::fs::copy(dir.join(from), &to).map_err(|e| io_error(&to, e))?;
    }
    Ok(())
}

/// A study's scene as read and as planned, where the studies folder holds it.
fn planned(file: &Path) -> Result<Option<(SceneSpec, Scene)>, Error> {
    if !file.is_file() {
        return Ok(None);
    }
    let spec = SceneSpec::load(file)?;
    let scene = Planner::default().plan(&spec)?;
    Ok(Some((spec, scene)))
}

/// The train of railway cars over the HSLM bridge at every speed from 40 to 130 m/s, beside
/// the moving-force and the moving-mass trains of the same axles and static axle loads: the
/// deck's largest acceleration by each model, and the car bodies' largest acceleration against
/// EN 1990's levels of comfort. `sweep.csv` of each model goes to `out/vehicle-railcar-sweep/`.
fn railcar_sweep(studies: &Path, out: &Path, figures: &Path) -> Result<(), Error> {
    let file = studies.join("vehicle-railcar.yaml");
    let Some((spec, scene)) = planned(&file)? else {
        return Ok(());
    };
    let Some(beam) = scene.beam() else {
        return Ok(());
    };
    let (masses, forces) = trains_of_the_cars(&file, &spec, beam)?;
    // The wheels as what they are, rigid disks of 0.46 m (920 mm wheels): they round the kink
    // the deck's end rotation makes at each abutment, and fly where they lift off.
    let mut on_disks = spec.clone();
    on_disks.set_name("vehicles.*.wheel", "disk")?;
    on_disks.set("vehicles.*.radius", 0.46)?;
    let started = std::time::Instant::now();
    let dir = out.join("vehicle-railcar-sweep");
    let mut deck = Vec::new();
    let mut bodies = Vec::new();
    for (label, swept, key) in [
        ("vehicles", spec.clone(), "vehicles.*.speed"),
        ("vehicles on disk wheels", on_disks, "vehicles.*.speed"),
        ("moving masses", masses, "train.speed"),
        ("moving forces", forces, "train.speed"),
    ] {
        let setting = Setting::parse(&format!("{key}=40:130:91"))?;
        let rows = run_sweep(&swept, &setting, &Overrides::default(), true)?;
        super::sweep::write_sweep(&rows, &setting, &dir.join(label.replace(' ', "-")))?;
        let (on_deck, in_bodies) = railcar_series(label, &rows);
        deck.push(on_deck);
        if key.starts_with("vehicles") {
            bodies.push(in_bodies);
        }
    }
    say!(
        "{:<14} 4 × 91 speeds in {:.1} s; wrote {}",
        "vehicle-railcar",
        started.elapsed().as_secs_f64(),
        dir.display()
    );
    let deck: Vec<(&str, Vec<(f64, f64)>)> =
        deck.iter().map(|(n, p)| (n.as_str(), p.clone())).collect();
    plots::line_chart(
        &figures.join("vehicle-railcar-deck.svg"),
        "four railway cars over the 15 m HSLM bridge: the deck's largest acceleration",
        "speed (m/s)",
        "max |a| at midspan (m/s²)",
        &deck,
    )?;
    output::beam::comfort_chart(
        &figures.join("vehicle-railcar-comfort.svg"),
        "the same crossings: the car bodies' largest vertical acceleration",
        "speed (m/s)",
        &bodies,
    )
}

/// The moving-mass and moving-force trains of the cars' static axle loads, in the study's
/// scene with its vehicles replaced.
fn trains_of_the_cars(
    file: &Path,
    spec: &SceneSpec,
    beam: &crate::scene::BeamScene,
) -> Result<(SceneSpec, SceneSpec), Error> {
    let first = beam.vehicles.first().map_or(0.0, |v| v.x0);
    let (axles, loads): (Vec<f64>, Vec<f64>) = beam
        .vehicles
        .iter()
        .flat_map(|v| {
            v.axles
                .iter()
                .zip(&v.static_loads)
                .map(move |(a, p)| (first - v.x0 + a.x, *p))
        })
        .unzip();
    let text = spec.to_yaml()?;
    let (Some(cut), Some(rest)) = (text.find("\nvehicles:"), text.find("\noutput:")) else {
        return Err(Error::Input(format!(
            "{}: the railway study's vehicles must come before its output",
            file.display()
        )));
    };
    let train = |model: &str| -> Result<SceneSpec, Error> {
        let text = format!(
            "{}\ntrain: {{axles: {axles:?}, load: {loads:?}, speed: 100.0, model: {model}}}{}",
            &text[..cut],
            &text[rest..]
        );
        SceneSpec::parse(&text, &file.display().to_string(), "vehicle-railcar")
    };
    Ok((train("moving-mass")?, train("moving-force")?))
}

/// A labelled line of a chart.
type Series = (String, Vec<(f64, f64)>);

/// One model's deck series (its largest midspan acceleration against speed, labelled with
/// the speed from which a wheel lifts off, if one does) and its car bodies' largest
/// acceleration; a run a wheel's lift-off stopped is not a crossing, and is left out.
fn railcar_series(label: &str, rows: &[super::sweep::SweepRow]) -> (Series, Series) {
    let ok = || {
        rows.iter()
            .filter_map(|r| Some((r.value, r.outcome.as_ref().ok()?)))
            .filter(|(_, s)| s.stop == "end")
    };
    let lifted = rows
        .iter()
        .filter(|r| r.outcome.as_ref().is_ok_and(|s| s.stop == "contact-lost"))
        .map(|r| r.value)
        .fold(f64::INFINITY, f64::min);
    let shown = if lifted.is_finite() {
        format!("{label} (from {lifted} m/s a wheel lifts off the deck)")
    } else {
        label.to_string()
    };
    let deck = ok()
        .filter_map(|(v, s)| Some((v, s.probes.first()?.4)))
        .collect();
    let bodies = ok()
        .map(|(v, s)| {
            let body = s
                .bodies
                .iter()
                .filter(|b| b.0.ends_with(".body"))
                .fold(0.0_f64, |m, b| m.max(b.1));
            (v, body)
        })
        .collect();
    (
        (format!("deck at midspan: {shown}"), deck),
        (format!("largest over the car bodies: {label}"), bodies),
    )
}

/// Compute every study's work–precision reference again, two at a time, and store each beside
/// its scene (`references/`): what `--references` does before the rest of the job.
pub fn store_references(studies: &Path) -> Result<(), Error> {
    let mut scenes = Vec::new();
    for file in scene_files(studies)? {
        scenes.push((Scene::load(&file)?, file));
    }
    let done = super::parallel::map(&scenes, false, |(scene, file)| {
        tradeoff::reference_for(
            scene,
            file,
            &study_plan(scene),
            true,
            "rollbeam studies --references",
        )
    });
    for ((scene, _), outcome) in scenes.iter().zip(done) {
        let (_, line) = outcome?;
        say!("{:<14} {line}", scene.name);
    }
    Ok(())
}

/// Study 1 side by side: the four disks' speeds, angular velocities and normal reactions.
fn compare_parabola(results: &[&RollingRun], figures: &Path) -> Result<(), Error> {
    let cases: Vec<&RollingRun> = results
        .iter()
        .copied()
        .filter(|r| r.header.scene.name.starts_with("parabola-p"))
        .collect();
    if cases.is_empty() {
        return Ok(());
    }
    let label = |r: &RollingRun| {
        format!(
            "{} (m = {}, a = {})",
            &r.header.scene.name["parabola-".len()..].to_uppercase(),
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

/// The speed sweep's rtol, looser than the study's 1e-5: the amplification it plots then lies
/// within 7·10⁻⁴ of rtol 1e-6's at every speed (1e-5: 1·10⁻⁴), ten times below the 0.7 % of
/// shear deflection by which it stands above Frýba's closed form, at about a third of the
/// cost (REPORT.md, "Study 4").
const SPEED_SWEEP_RTOL: f64 = 1e-4;

/// Dynamic amplification of the bridge's midspan deflection (largest over the run, crossing
/// and free vibration, over the static P L³/(48 EI)) against the disk's speed: D44's scene
/// swept over Ω0 with the moving force and with the consistent coupling, beside Frýba's
/// closed form for the moving force.
fn bridge_speed_sweep(studies: &Path, figures: &Path) -> Result<(), Error> {
    let file = studies.join("bridge-d44.yaml");
    let Some((spec, scene)) = planned(&file)? else {
        return Ok(());
    };
    let Some(beam) = scene.beam() else {
        return Ok(());
    };
    let Some(disk) = beam.disk() else {
        return Ok(());
    };
    let section = &beam.beam.section;
    let span = (beam.beam.to[0] - beam.beam.from[0]).hypot(beam.beam.to[1] - beam.beam.from[1]);
    let radius = disk.disk.radius;
    let fryba = |v: f64| MovingForce {
        p: disk.disk.mass * disk.gravity,
        span,
        ei: section.ei,
        mu: section.rho_a,
        v,
    };
    let setting = Setting::parse("disk.omega0=-10:-120:23")?;
    let over = Overrides {
        rtol: Some(SPEED_SWEEP_RTOL),
        ..Default::default()
    };
    let mut series = Vec::new();
    for coupling in [Coupling::MovingForce, Coupling::Consistent] {
        let mut swept = spec.clone();
        swept.set_name("disk.coupling", coupling.name())?;
        let rows = run_sweep(&swept, &setting, &over, true)?;
        let points: Vec<(f64, f64)> = rows
            .iter()
            .filter_map(|r| {
                let s = r.outcome.as_ref().ok()?;
                let mid = s.probes.iter().find(|p| p.0 == "mid")?;
                Some((-radius * r.value, -mid.1 / fryba(1.0).static_midspan()))
            })
            .collect();
        series.push((format!("{} (rollbeam)", coupling.name()), points));
    }
    let closed: Vec<(f64, f64)> = (0..=110)
        .map(|k| {
            let v = 4.0 + 44.0 * k as f64 / 110.0;
            (v, fryba(v).amplification(scene.duration, 2e-3))
        })
        .collect();
    series.push(("moving force, Frýba's closed form".to_string(), closed));
    let borrowed: Vec<(&str, Vec<(f64, f64)>)> = series
        .iter()
        .map(|(n, p)| (n.as_str(), p.clone()))
        .collect();
    plots::line_chart(
        &figures.join("bridge-speed-sweep.svg"),
        "bridge D44: dynamic amplification of the midspan deflection",
        "speed v = −a Ω0 (m/s)",
        "max |w_mid| / static",
        &borrowed,
    )
}

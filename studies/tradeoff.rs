//! The work–precision measurement (`rollbeam tradeoff`) checked on the parabola, where every
//! run is cheap: the reference settles, every method converges to it as its tolerance is
//! tightened (an independent check of both), and the fourth-order ESDIRK buys tight accuracy
//! with fewer right-hand-side evaluations than the second-order TR-BDF2, which is why it is
//! there. Costs are compared in right-hand-side evaluations, which do not depend on the
//! machine; wall times are what the command reports, and REPORT.md shows.

use crate::common;

use common::{changed, load, Set};
use rollbeam::ode::Method;
use rollbeam::run::{self, Overrides};
use rollbeam::scene::{Model, Scene};
use rollbeam::workflows::tradeoff::store::{self, Stored};
use rollbeam::workflows::tradeoff::{self, Plan, Trial, REFERENCE_SETTLED};

fn errors(trials: &[Trial], method: Method) -> Vec<(f64, f64, usize)> {
    trials
        .iter()
        .filter(|t| t.point.method == method)
        .map(|t| {
            let m = t.outcome.as_ref().expect("every parabola run completes");
            (t.point.rtol, m.headline_error, m.rhs_evals)
        })
        .collect()
}

#[test]
fn work_precision_on_the_parabola() {
    let scene = load("parabola-p1.yaml");
    let plan = Plan::default_for(&scene);
    let reference = tradeoff::reference(&scene, &plan, "test").expect("the reference runs");
    assert!(
        reference.settled_to <= REFERENCE_SETTLED,
        "reference settled only to {:.1e}",
        reference.settled_to
    );
    assert_eq!(reference.mesh_gap, None, "a rigid curve has no mesh");
    let trials = tradeoff::trials(&scene, &plan, &reference, false);

    // Convergence to the reference: from rtol 1e-2 to 1e-8 each method's headline error falls
    // by at least 10³ (a second-order method gains 10^(6·2/3) = 10⁴ over those six decades;
    // a shortfall would mean the reference and the runs disagree on what they compute).
    for method in plan.methods.iter().copied() {
        let e = errors(&trials, method);
        let (loose, tight) = (e[0].1, e[e.len() - 1].1);
        eprintln!("{}: {e:?}", method.name());
        assert!(
            tight * 1e3 <= loose,
            "{}: error {loose:.2e} at rtol 1e-2, {tight:.2e} at 1e-8",
            method.name()
        );
        assert!(tight <= 1e-4, "{}: {tight:.2e} at rtol 1e-8", method.name());
    }

    // Where the fourth-order implicit method wins: the cheapest run within 1e-4 costs it
    // fewer evaluations than TR-BDF2's cheapest within 1e-4 (TR-BDF2 does not reach 1e-5
    // by rtol 1e-8 at all).
    let cheapest_within = |method: Method, target: f64| {
        errors(&trials, method)
            .iter()
            .filter(|e| e.1 <= target)
            .map(|e| e.2)
            .min()
    };
    let esdirk = cheapest_within(Method::Esdirk4, 1e-4).expect("ESDIRK4 reaches 1e-4");
    let trbdf2 = cheapest_within(Method::TrBdf2, 1e-4).expect("TR-BDF2 reaches 1e-4");
    assert!(
        esdirk < trbdf2,
        "to 1e-4: ESDIRK4 {esdirk} evaluations, TR-BDF2 {trbdf2}"
    );

    // The command's own choice reaches what it names.
    for target in tradeoff::TARGETS {
        let t = tradeoff::cheapest(&trials, target).expect("some setting reaches it");
        let m = t.outcome.as_ref().expect("a finished run");
        assert!(m.headline_error <= target);
        // The history follows the headlines: a run within its target at the headlines is
        // within ten times it over the whole history.
        assert!(
            m.history_error <= 10.0 * target.max(reference.settled_to),
            "{}: history error {:.1e}",
            t.settings(),
            m.history_error
        );
    }
}

/// A beam (C1's cantilever under its sudden tip load, 0.1 s, degree-2 elements so that the mesh
/// has an error of its own). On 2 elements the mesh's error dominates: a hundredfold tighter
/// rtol leaves the headline error where it was (within a factor 2), for the implicit and the
/// explicit method alike, while a mesh twice as fine more than halves it. The reference checks
/// its own mesh against one twice as fine, and the accuracies below that are named as beyond
/// it. A run past its step budget is a row with the reason, not a crash.
#[test]
fn work_precision_on_a_beam_separates_mesh_and_time_error() {
    let scene = changed(
        "cantilever-c1.yaml",
        &[
            Set::Number("duration", 0.1),
            Set::Number("track.beam.order", 2.0),
            Set::LeftOut("output.shapes"),
        ],
    );
    let plan = Plan {
        methods: vec![Method::GenAlpha, Method::Dopri5],
        rtols: vec![1e-3, 1e-5],
        meshes: vec![2, 4],
        orders: Vec::new(),
        models: Vec::new(),
        max_steps: 20_000,
        reference_from: None,
        points: Vec::new(),
    };
    let reference = tradeoff::reference(&scene, &plan, "test").expect("the reference runs");
    let trials = tradeoff::trials(&scene, &plan, &reference, false);
    assert_eq!(trials.len(), 8);
    for method in plan.methods.iter().copied() {
        let error = |n: usize, rtol: f64| {
            trials
                .iter()
                .find(|t| {
                    let p = &t.point;
                    p.method == method && p.elements == Some(n) && p.rtol == rtol
                })
                .and_then(|t| t.outcome.as_ref().ok())
                .expect("every run completes")
                .headline_error
        };
        let (loose, tight, finer) = (error(2, 1e-3), error(2, 1e-5), error(4, 1e-5));
        eprintln!(
            "{}: 2 el. {loose:.2e} → {tight:.2e}; 4 el. {finer:.2e}",
            method.name()
        );
        assert!(tight >= 0.5 * loose, "{}: not mesh-bound", method.name());
        assert!(
            finer <= 0.5 * tight,
            "{}: the finer mesh is no better",
            method.name()
        );
    }
    // The reference's mesh check (8 against 16 elements) measured 4.9·10⁻⁴, as large as the
    // 4-element runs' error (5.5·10⁻⁴): each halving adds higher modes that ride on the sudden
    // load's peak, so it stops converging there. No cut of rtol shows that; the check does,
    // and every accuracy below it is then named as beyond what the reference resolves.
    let gap = reference
        .mesh_gap
        .expect("a beam's reference checks its mesh");
    assert!(gap.is_finite() && gap > 0.0, "mesh gap {gap}");
    let dir = std::env::temp_dir().join(format!("rollbeam-tradeoff-{}", std::process::id()));
    let lines = tradeoff::write_tradeoff(&scene, &reference, &trials, &dir).expect("written");
    assert!(
        lines[0].contains("from a mesh twice as fine"),
        "{}",
        lines[0]
    );
    for (target, line) in tradeoff::TARGETS.iter().zip(&lines[1..]) {
        assert_eq!(
            line.contains("below what the reference resolves"),
            *target < reference.resolves(),
            "{line}"
        );
    }

    let starved = Plan {
        methods: vec![Method::Dopri5],
        rtols: vec![1e-5],
        meshes: vec![4],
        orders: Vec::new(),
        models: Vec::new(),
        max_steps: 100,
        reference_from: None,
        points: Vec::new(),
    };
    let t = tradeoff::trials(&scene, &starved, &reference, false);
    assert!(
        t[0].outcome
            .as_ref()
            .is_err_and(|e| e.contains("gave up after 100 steps")),
        "{:?}",
        t[0].outcome
    );
    // A run that gave up still reports what it cost: its time in the table's wall_s, the
    // column after the quoted reason and the two empty errors.
    let starved_dir = dir.join("starved");
    tradeoff::write_tradeoff(&scene, &reference, &t, &starved_dir).expect("written");
    let csv = std::fs::read_to_string(starved_dir.join("tradeoff.csv")).expect("tradeoff.csv");
    let row = csv.lines().nth(1).expect("one run");
    let after_reason = row.rsplit('"').next().expect("a quoted reason");
    let wall: f64 = after_reason
        .split(',')
        .nth(3)
        .expect("wall_s")
        .parse()
        .expect("a time");
    assert!(wall > 0.0 && wall == t[0].spent_s, "{row}");
}

/// The same beam on 2 elements with the degree swept instead of the mesh: the reference takes
/// the highest degree tried (on twice the finest mesh), and degree 3 more than halves degree 2's
/// error at an rtol that leaves the mesh's error dominant (the test above), as p-refinement must
/// on a displacement that is smooth between the load and the clamp.
#[test]
fn work_precision_sweeps_the_element_degree() {
    let scene = changed(
        "cantilever-c1.yaml",
        &[Set::Number("duration", 0.1), Set::LeftOut("output.shapes")],
    );
    let plan = Plan {
        methods: vec![Method::GenAlpha],
        rtols: vec![1e-5],
        meshes: vec![2],
        orders: vec![2, 3],
        models: Vec::new(),
        max_steps: 20_000,
        reference_from: None,
        points: Vec::new(),
    };
    let reference = tradeoff::reference(&scene, &plan, "test").expect("the reference runs");
    assert_eq!((reference.elements, reference.order), (Some(4), Some(3)));
    let trials = tradeoff::trials(&scene, &plan, &reference, false);
    let error = |k: usize| {
        trials
            .iter()
            .find(|t| t.point.order == Some(k))
            .and_then(|t| t.outcome.as_ref().ok())
            .expect("every run completes")
            .headline_error
    };
    eprintln!("degree 2: {:.2e}; degree 3: {:.2e}", error(2), error(3));
    assert!(error(3) <= 0.5 * error(2), "degree 3 is no better");
}

/// A study's grid cut for the main job's time (the sudden loads stop at rtol 1e-4) does not
/// loosen what its runs are scored against: every study's reference starts a decade below its
/// grid's tightest rtol and at 1e-6 or below, where the beam studies' references settle to
/// 10⁻⁵ or better (docs/numerics.md, "The work–precision grids").
#[test]
fn a_grid_cut_for_time_keeps_its_reference_tight() {
    use rollbeam::workflows::studies;

    for file in studies::scene_files(&common::studies_dir()).expect("the studies folder") {
        let scene = Scene::load(&file).expect("a valid study");
        let plan = studies::study_plan(&scene);
        let tightest = plan.rtols.iter().copied().fold(1.0, f64::min);
        let start = plan.reference_rtol();
        eprintln!(
            "{}: grid to {tightest:.0e}, reference from {start:.0e}",
            scene.name
        );
        assert!(start <= tightest / 10.0 * (1.0 + 1e-9), "{}", scene.name);
        assert!(start <= 1e-6 * (1.0 + 1e-9), "{}", scene.name);
    }
}

/// Each study, its grid's plan, and what loading its stored reference found: the reference
/// `rollbeam studies` scores its diagram against.
fn stored_references() -> Vec<(Scene, Plan, Stored)> {
    use rollbeam::workflows::studies;
    let files = studies::scene_files(&common::studies_dir()).expect("the studies folder");
    files
        .into_iter()
        .map(|file| {
            let scene = Scene::load(&file).expect("a valid study");
            let plan = studies::study_plan(&scene);
            let path = store::stored_path(&file, &scene.name);
            let hash = store::scene_hash(&file).expect("a readable scene");
            let method = tradeoff::reference_method(&scene);
            let order = scene.beam().map(|b| b.beam.order);
            let stored = store::load(&path, &hash, &plan, method, order);
            (scene, plan, stored)
        })
        .collect()
}

/// Every stored work–precision reference of a study (`studies/references/`, what
/// `rollbeam studies` scores its diagrams against) was made from its scene file as it is now,
/// at least as fine as the study's grid asks; and each still reproduces. (A study without one
/// is computed when `rollbeam studies` needs it, and said so.) The first sixtieth of its
/// history is run again with the same method on the same mesh at ten times its rtol: 0.05 s
/// of the sudden loads, which holds the first peak under the load (at 0.024–0.034 s) and
/// three quarters of a period of B1–B3's first mode, one and a half of C1–C3's. Their fine
/// meshes make these six most of the test's cost, which grows with the window.
/// - It must have the same output times, its start included. B1–B3's references were once
///   stored without it, which floored their diagrams at 2–5·10⁻³, since the loaded point's
///   highest position is the rest it starts from.
/// - Each history column's extremes over the window must agree to twice the larger of what
///   the reference's headlines moved at its own last tenfold cut of rtol (`settled_to`, at
///   least 10⁻⁷) and ten times the rerun's rtol, of the largest value of the whole stored
///   history: the scale the headlines and their `settled_to` are measured against (of the
///   window's own largest value, the zip-line's first thirtieth, where the rope has barely
///   begun to sag, was off by 8.6·10⁻⁶ against 2.0·10⁻⁶). Extremes, as the headlines are,
///   and not the history point by point: a history carries the phase error a run
///   accumulates, which rtol does not bound and stationary values do not feel. Over the first
///   tenth, B3's rerun at rtol 10⁻⁸ is off by 2.4·10⁻⁵ point by point, against 5·10⁻⁶ in its
///   extremes and a reference settled to 8.5·10⁻⁶.
///
/// A change of the code that moves the physics by more than that makes the stored references
/// stale: `rollbeam studies --references` makes them again.
#[test]
fn stored_references_serve_and_reproduce() {
    for (scene, _, stored) in stored_references() {
        let method = tradeoff::reference_method(&scene);
        let stored = match stored {
            Stored::Usable(r) => r,
            Stored::Missing => {
                eprintln!("{}: no stored reference", scene.name);
                continue;
            }
            Stored::Stale(why) => panic!("{}: {why}", scene.name),
        };
        let rows = (stored.history.len() / 60).max(2);
        let window = &stored.history[..=rows];
        let mut short = scene.clone();
        // Half an output interval past the window's last row, so that round-off in the times
        // cannot leave that row out.
        short.duration = window[rows].0 + 0.5 * short.interval;
        if let (Model::Beam(b), Some(n)) = (&mut short.model, stored.elements) {
            b.beam.elements = n;
            b.beam.order = stored.order.unwrap_or(b.beam.order);
            let end = short.duration;
            b.shapes.retain(|&t| t <= end);
        }
        let over = Overrides {
            method: Some(method),
            rtol: Some(stored.rtol * 10.0),
            atol: Some(stored.rtol * 1e-2),
            ..Default::default()
        };
        let again = run::run(&short, &over, false).expect("the reference's settings run");
        let last = window[rows].0;
        let rerun: Vec<(f64, Vec<f64>)> = tradeoff::history(&again)
            .into_iter()
            .filter(|(t, _)| *t <= last + 1e-9 * last.max(1.0))
            .collect();
        // The same output times, the start included: a run's extremes are scored over all of
        // its rows, so a reference missing one scores every run by it.
        let times = |h: &[(f64, Vec<f64>)]| -> Vec<f64> { h.iter().map(|(t, _)| *t).collect() };
        let (stored_times, rerun_times) = (times(window), times(&rerun));
        assert!(
            stored_times.len() == rerun_times.len()
                && stored_times
                    .iter()
                    .zip(&rerun_times)
                    .all(|(a, b)| (a - b).abs() <= 1e-9 * a.max(1.0)),
            "{}: the reference's output times {:?}… are not the run's {:?}…",
            scene.name,
            &stored_times[..3],
            &rerun_times[..3.min(rerun_times.len())]
        );
        // Each column's extremes over the window: stationary values, as the headlines are.
        let extremes = |h: &[(f64, Vec<f64>)]| -> Vec<f64> {
            (0..h[0].1.len())
                .flat_map(|c| {
                    let (lo, hi) = h
                        .iter()
                        .map(|(_, v)| v[c])
                        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                            (lo.min(x), hi.max(x))
                        });
                    [lo, hi]
                })
                .collect()
        };
        let scale = stored
            .history
            .iter()
            .flat_map(|(_, v)| v.iter())
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        let error = extremes(window)
            .iter()
            .zip(extremes(&rerun))
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / scale;
        eprintln!(
            "{}: first {:.3} s at rtol {:.0e}: {error:.1e}",
            scene.name,
            short.duration,
            stored.rtol * 10.0
        );
        let resolved = 2.0
            * stored
                .settled_to
                .max(1e-7)
                .max(10.0 * over.rtol.unwrap_or(0.0));
        assert!(
            error <= resolved,
            "{}: {error:.1e} > {resolved:.1e}",
            scene.name
        );
    }
}

/// The stored windowed means: a setting none of them was made with lands
/// within 10⁻⁶ of each, on the sudden loads (REPORT.md, "Work–precision"). It is ESDIRK4 at rtol 10⁻⁴ on the grid's coarsest mesh: measured, it lands
/// 0.5–58·10⁻⁹ away, and the means' references resolve 1.6·10⁻⁹–8.9·10⁻⁸, so at least a
/// tenfold margin stands between the target and both. The extremes of the same runs lie
/// 6·10⁻⁵–9·10⁻⁴ off: the means are what makes the target reachable, not the runs.
#[test]
fn stored_windowed_means_are_reached_within_1e_6() {
    let scored = means_within(false, 1e-7, 1e-6);
    assert!(
        scored >= 6,
        "the six sudden loads carry windowed means; {scored} did"
    );
}

/// The same on the bridges and the rubber (REPORT.md, "Work–precision"), at the point each grid
/// runs past its meshes for: ESDIRK4 on 20 elements of degree 6, at rtol 10⁻⁴ on the bridges
/// and 10⁻⁸ on the rubber, against references made on 40 elements, which resolve 2.7·10⁻⁷
/// (D44), 8.7·10⁻⁷ (D50) and 3.1·10⁻⁷ (rubber). The rubber converges smoothly there (7.5, 8.0,
/// 8.2, 8.5·10⁻⁷ at rtol 0.8, 0.9, 0.95, 1·10⁻⁸). The bridges do not: their means sit at what
/// the references resolve and scatter with the step sequence, 3.9·10⁻⁷–1.3·10⁻⁶ (D44) and
/// 6.5·10⁻⁷–1.4·10⁻⁶ (D50) as rtol moves between 0.8 and 1.25·10⁻⁴ (at 5·10⁻⁵ still 4.2·10⁻⁷
/// and 7.9·10⁻⁷), and a change of round-off alone (another pivot order of the same LU) moved
/// D44's from 8.7·10⁻⁷ to 1.3·10⁻⁶. So the bound is that band's top, 1.5·10⁻⁶, not the 10⁻⁶
/// a single rtol happens to meet. The extremes of the same runs lie 2–3·10⁻⁵ off on the bridges.
#[test]
fn the_bridges_and_the_rubber_reach_their_references_in_the_windowed_means_past_their_grid() {
    let scored = means_within(true, 1e-6, 1.5e-6);
    assert!(
        scored >= 3,
        "the two bridges and the rubber carry windowed means; {scored} did"
    );
}

/// Runs each study with stored means (those whose grid has points past it, or those whose has
/// not), asserts that its means' reference resolves `resolves` or better and that the run lands
/// within `bound` of it; how many it scored.
fn means_within(past_grid: bool, resolves: f64, bound: f64) -> usize {
    let mut scored = 0;
    for (scene, plan, means) in with_means(past_grid) {
        assert!(
            means.resolves <= resolves,
            "{}: resolves {:.1e}",
            scene.name,
            means.resolves
        );
        let error = means_error(&scene, &plan, &means, 1.0);
        eprintln!("{}: windowed means {error:.1e} off", scene.name);
        assert!(error <= bound, "{}: {error:.1e}", scene.name);
        scored += 1;
    }
    scored
}

/// The studies whose stored reference has windowed means, past their grid or not.
fn with_means(past_grid: bool) -> Vec<(Scene, Plan, tradeoff::MeansReference)> {
    stored_references()
        .into_iter()
        .filter_map(|(scene, plan, stored)| match stored {
            Stored::Usable(stored) => stored.means.map(|m| (scene, plan, m)),
            _ => None,
        })
        .filter(|(_, plan, _)| plan.points.is_empty() != past_grid)
        .collect()
}

/// How far the windowed means of `scene` at its grid's point past its meshes (ESDIRK4 at
/// 10⁻⁴ on its coarsest mesh where it has none), its rtol times `rtol_factor`, land from
/// `means`.
fn means_error(
    scene: &Scene,
    plan: &Plan,
    means: &tradeoff::MeansReference,
    rtol_factor: f64,
) -> f64 {
    let mut coarse = scene.clone();
    let (method, elements, order, rtol) = match plan.points.first() {
        Some(p) => (p.method, p.elements, p.order, p.rtol),
        None => (
            Method::Esdirk4,
            plan.meshes.iter().min().copied(),
            None,
            1e-4,
        ),
    };
    let rtol = rtol * rtol_factor;
    if let (Model::Beam(b), Some(n)) = (&mut coarse.model, elements) {
        b.beam.elements = n;
        b.beam.order = order.unwrap_or(b.beam.order);
        b.shapes.clear();
    }
    let over = Overrides {
        method: Some(method),
        rtol: Some(rtol),
        atol: Some(rtol * 1e-3),
        windowed_means: true,
        ..Default::default()
    };
    let r = run::run(&coarse, &over, false).expect("the study runs");
    let values = tradeoff::windowed_means(&r).expect("a beam run has means");
    tradeoff::mean_error(values, means)
}

/// The measurement behind the bound above (run with `--ignored means_scatter`): the bridges'
/// windowed means at their point past the grid, its rtol moved by −20 % to +25 %, each within
/// 1.5·10⁻⁶ of the reference; prints the band (REPORT.md, "Work–precision").
#[test]
#[ignore]
fn the_bridges_windowed_means_scatter_with_the_steps() {
    for (scene, plan, means) in with_means(true) {
        if !scene.name.starts_with("bridge") {
            continue;
        }
        let errors: Vec<f64> = [0.8, 0.9, 0.95, 1.0, 1.05, 1.1, 1.25]
            .iter()
            .map(|&f| means_error(&scene, &plan, &means, f))
            .collect();
        let (least, most) = errors
            .iter()
            .fold((f64::INFINITY, 0.0_f64), |(l, m), &e| (l.min(e), m.max(e)));
        eprintln!("{}: windowed means {least:.2e}–{most:.2e} off", scene.name);
        assert!(most <= 1.5e-6, "{}: {errors:?}", scene.name);
    }
}

/// Nothing read back from disk is trusted: a stored reference whose history was cut to three
/// rows (it served, and every run's history error dropped from ~6·10⁻⁷ to ~6·10⁻¹⁶, each run
/// scored against itself) or replaced by a device, or whose own file holds a headline, an
/// rtol or a wall time that is not a finite number, is stale, and says why; the same files
/// untouched serve.
#[test]
fn a_stored_reference_cut_edited_or_replaced_is_stale() {
    use rollbeam::workflows::studies;
    let dir = std::env::temp_dir().join(format!("rollbeam-stored-{}", std::process::id()));
    let refs = dir.join("references");
    std::fs::create_dir_all(&refs).expect("temp dir");
    let from = common::studies_dir();
    std::fs::copy(from.join("parabola-p1.yaml"), dir.join("parabola-p1.yaml")).expect("copy");
    for ext in ["yaml", "history.csv"] {
        let name = format!("parabola-p1.{ext}");
        std::fs::copy(from.join("references").join(&name), refs.join(&name)).expect("copy");
    }
    let file = dir.join("parabola-p1.yaml");
    let scene = Scene::load(&file).expect("a valid study");
    let plan = studies::study_plan(&scene);
    let path = store::stored_path(&file, &scene.name);
    let hash = store::scene_hash(&file).expect("a readable scene");
    let method = tradeoff::reference_method(&scene);
    let load = || store::load(&path, &hash, &plan, method, None);
    assert!(matches!(load(), Stored::Usable(_)), "the copy serves");
    let history = refs.join("parabola-p1.history.csv");
    let text = std::fs::read_to_string(&history).expect("history");
    let cut: String = text.lines().take(3).map(|l| format!("{l}\n")).collect();
    std::fs::write(&history, cut).expect("cut");
    match load() {
        Stored::Stale(why) => assert!(why.contains("hash differs"), "{why}"),
        _ => panic!("a history cut to three rows served"),
    }
    std::fs::remove_file(&history).expect("remove");
    std::os::unix::fs::symlink("/dev/zero", &history).expect("link");
    match load() {
        Stored::Stale(why) => assert!(why.contains("a device"), "{why}"),
        _ => panic!("a device served as a history"),
    }
    // The reference's own file carries no hash: each number in it is checked instead, for a
    // headline that is not a number would drop out of every score taken against it.
    std::fs::remove_file(&history).expect("remove");
    std::fs::copy(
        from.join("references").join("parabola-p1.history.csv"),
        &history,
    )
    .expect("copy");
    let stored = std::fs::read_to_string(&path).expect("the reference");
    for (from, to, needle) in [
        (
            "value: 0.9043378198008877",
            "value: .nan",
            "disk.x_end is NaN",
        ),
        ("rtol: 1.0e-10", "rtol: .nan", "rtol or wall time"),
        ("wall_s: 0.000486802", "wall_s: -.inf", "rtol or wall time"),
    ] {
        assert!(stored.contains(from), "the stored reference holds {from}");
        std::fs::write(&path, stored.replacen(from, to, 1)).expect("edit");
        match load() {
            Stored::Stale(why) => assert!(why.contains(needle), "{why}"),
            _ => panic!("a reference with {to} served"),
        }
    }
}

/// Studies whose own mesh misses the accuracy by itself, measured on the reference's: the
/// rubber beam's 10 elements put its midspan rebound 1.1·10⁻³ from the reference on 20
/// (whose own gap to 40 is 3.5·10⁻⁴; the plan, left the mesh, takes 44), where on 20 the
/// defaults land within 4.1·10⁻⁴. They are run on the reference's mesh.
const COARSER_THAN_ASKED: [&str; 1] = ["rubber"];

/// Each study as a user meets it with an empty solver block (method, tolerances and ρ∞ left
/// to the plan; the scene's mesh kept, but the rubber beam's, see [`COARSER_THAN_ASKED`]) lands
/// within the accuracy asked of its stored reference, in the reference's own measure: the
/// headlines read on the output grid, each against the largest of its family. Measured at
/// most 4.1·10⁻⁴ (the rubber beam's midspan rebound), 3.2·10⁻⁴ on the zip-line, 2.3·10⁻⁴ on
/// B1–B3 and C1–C3, 2.6·10⁻⁴ on D50, 1.3·10⁻⁴ on D44, 10⁻⁵ on the vehicles, 10⁻⁷ on the HSLM
/// bridge (integrated exactly). C1's run at the defaults is
/// the one [`crate::accuracy`] checks against the same model converged, and is scored there.
fn land_within_their_references_at_the_defaults(names: &[&str]) {
    for name in names {
        let file = common::studies_dir().join(format!("{name}.yaml"));
        let mut spec = rollbeam::scene::SceneSpec::load(&file).expect("the study");
        for key in [
            "solver.method",
            "solver.rtol",
            "solver.atol",
            "solver.rho_inf",
        ] {
            spec.unset(key).expect("a solver key");
        }
        if COARSER_THAN_ASKED.contains(name) {
            let elements = stored_reference(name).elements;
            if let Some(n) = elements {
                spec.set("track.beam.elements", n as f64)
                    .expect("a mesh key");
            }
        }
        let planned = rollbeam::plan::Planner::default()
            .plan(&spec)
            .expect("planned");
        let r = run::run(&planned, &Overrides::default(), false).expect("the run");
        lands_within_its_reference(name, &r);
    }
}

/// The stored reference of the study `name`, which must serve.
fn stored_reference(name: &str) -> Box<tradeoff::Reference> {
    let (_, _, stored) = stored_references()
        .into_iter()
        .find(|(s, _, _)| s.name == name)
        .expect("the study");
    match stored {
        Stored::Usable(reference) => reference,
        _ => panic!("{name}: no usable stored reference"),
    }
}

/// The run `r` of the study `name` lands within the study's accuracy of its stored reference,
/// in the reference's measure.
pub(crate) fn lands_within_its_reference(name: &str, r: &run::Run) {
    let reference = stored_reference(name);
    let scene =
        Scene::load(&common::studies_dir().join(format!("{name}.yaml"))).expect("the study");
    let accuracy = scene.beam().expect("a beam study").accuracy;
    let error = tradeoff::headline_error(&tradeoff::headlines(r), &reference.headlines);
    eprintln!("{name}: {error:.1e} of its reference at the defaults");
    assert!(error <= accuracy, "{name}: {error:.1e} from its reference");
}

#[test]
fn beam_b1_lands_within_its_reference_at_the_defaults() {
    land_within_their_references_at_the_defaults(&["beam-b1"]);
}

#[test]
fn beam_b2_lands_within_its_reference_at_the_defaults() {
    land_within_their_references_at_the_defaults(&["beam-b2"]);
}

#[test]
fn beam_b3_lands_within_its_reference_at_the_defaults() {
    land_within_their_references_at_the_defaults(&["beam-b3"]);
}

#[test]
fn cantilever_c2_lands_within_its_reference_at_the_defaults() {
    land_within_their_references_at_the_defaults(&["cantilever-c2"]);
}

#[test]
fn cantilever_c3_lands_within_its_reference_at_the_defaults() {
    land_within_their_references_at_the_defaults(&["cantilever-c3"]);
}

#[test]
fn the_bridges_and_ropes_land_within_their_references_at_the_defaults() {
    land_within_their_references_at_the_defaults(&[
        "bridge-d44",
        "bridge-d50",
        "hslm-15m",
        "rubber",
        "zipline",
        "vehicle-sprung",
        "vehicle-truck",
        "vehicle-railcar",
    ]);
}

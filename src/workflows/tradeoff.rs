//! `rollbeam tradeoff SCENE.yaml`: the speed–accuracy trade of a scene, measured.
//!
//! 1. A reference: the most accurate method for the kind of scene (Dormand–Prince on a rigid
//!    curve, generalized-α on a beam), on a mesh twice as fine as the finest tried, of the
//!    highest degree tried, its rtol cut tenfold until its headline quantities move by less
//!    than [`REFERENCE_SETTLED`]; how far they moved at the last cut is reported, and on a
//!    beam how far its headlines lie from one more run on a mesh twice as fine, since errors
//!    below either mean nothing.
//! 2. A grid: every method × every rtol × every mesh and degree (and beam model, where asked),
//!    run on every core, each run capped at a number of steps (a method that needs more "gives
//!    up", which is itself the answer).
//! 3. For every run the largest relative error of the headline quantities (the probes' extreme
//!    deflections on a beam; the disk's final position and extreme normal reaction on a rigid
//!    curve) and of the whole history (probe deflections or disk centre, on the output grid),
//!    against the reference; wall time, steps, rejected steps and right-hand-side evaluations.
//!    The disk's largest contact force on a beam is not a headline: it carries the beam's
//!    high-frequency content, and on D44 its peak moved by 2 % between rtol 1e-8 and 1e-9
//!    while the deflections had settled.
//! 4. tradeoff.csv, tradeoff.svg (headline error against the work, log–log, a line per method,
//!    mesh and degree), and the cheapest settings that reach 1e-2, 1e-4 and 1e-6.

use std::fmt::Write as _;
use std::path::Path;

use plotters::prelude::*;

use super::settings::{parse_method, rtol_flag};
use crate::beam::{BeamModel, MAX_ORDER};
use crate::error::{quote, Error};
use crate::ode::Method;
use crate::output::plots::PALETTE;
use crate::output::{io_error, write};
use crate::run::{self, Overrides, Run};
use crate::say;
use crate::scene::{Model, Scene};

/// The reference is taken as settled when a tenfold cut of rtol moves no headline by more than
/// this (relative): a decade below the tightest accuracy the command reports on.
pub const REFERENCE_SETTLED: f64 = 1e-7;
/// At most this many tenfold cuts of the reference's rtol: a second-order reference costs
/// 10^(1/3) ≈ 2.2 times more per cut.
const REFERENCE_CUTS: usize = 2;
/// Runs shorter than this (s) are timed as the mean of repeats that add up to it.
const TIMING_FLOOR: f64 = 0.05;
/// The accuracies the command names the cheapest settings for.
pub const TARGETS: [f64; 3] = [1e-2, 1e-4, 1e-6];

/// What to try.
#[derive(Clone, Debug)]
pub struct Plan {
    pub methods: Vec<Method>,
    pub rtols: Vec<f64>,
    /// Element counts (beam scenes; empty on a rigid curve).
    pub meshes: Vec<usize>,
    /// Lagrange degrees of the elements (beam scenes; empty: the scene's own).
    pub orders: Vec<usize>,
    /// Beam models (beam scenes; empty: the scene's own).
    pub models: Vec<BeamModel>,
    pub max_steps: usize,
    /// An rtol the reference starts a decade below even where the grid stops short of it:
    /// a grid cut for time must not loosen what its runs are scored against.
    pub reference_from: Option<f64>,
    /// Settings past the grid, each run once: a mesh finer and of a higher degree than any the
    /// grid tries, where only that reaches a target (the bridges' 10⁻⁶ in the windowed means).
    /// Chosen for what they reach, they may take [`POINT_STEPS_FACTOR`] times a grid run's steps,
    /// and are not judged by the pace of their first steps: the zip-line's first 2000 project
    /// 16–27 times the steps its runs take.
    pub points: Vec<GridPoint>,
}

/// How many times `max_steps` a point past the grid may take.
pub const POINT_STEPS_FACTOR: usize = 10;

impl Plan {
    /// The rtol the reference starts at: a decade below the tightest rtol tried, or below
    /// `reference_from` where that is tighter.
    pub fn reference_rtol(&self) -> f64 {
        let tightest = self.rtols.iter().copied().fold(1.0, f64::min);
        tightest.min(self.reference_from.unwrap_or(1.0)) / 10.0
    }

    /// The degree the reference is computed with: the highest tried (`None`: the scene's).
    pub fn reference_order(&self) -> Option<usize> {
        self.orders.iter().copied().max()
    }

    /// The mesh the windowed means' reference is made on: twice the finest tried, of the
    /// highest degree tried, the points past the grid included (`None`: the scene's).
    pub fn means_mesh(&self) -> (Option<usize>, Option<usize>) {
        let highest = |grid: &[usize], of_point: fn(&GridPoint) -> Option<usize>| {
            grid.iter()
                .copied()
                .chain(self.points.iter().filter_map(of_point))
                .max()
        };
        (
            highest(&self.meshes, |p| p.elements).map(|n| 2 * n),
            highest(&self.orders, |p| p.order),
        )
    }

    /// The rtol the windowed means' reference is made at: a decade below the tightest tried,
    /// the points past the grid included. On the sudden loads (grid to 1e-4) that is 1e-5,
    /// which settles the means to 10⁻⁹, mesh and time together (REPORT.md), in a minute or
    /// two. The bridges' stored means were made with their grid to 1e-5 (`--rtols`, in the
    /// command each records), so at 1e-6: at 1e-5 D44's resolved only 8.9·10⁻⁷, too near the
    /// 10⁻⁶ its point is scored to. The rubber's point at 1e-8 puts its means at 1e-9.
    pub fn means_rtol(&self) -> f64 {
        self.rtols
            .iter()
            .copied()
            .chain(self.points.iter().map(|p| p.rtol))
            .fold(1.0, f64::min)
            / 10.0
    }

    /// The method the windowed means' reference is made with: that of the tightest point past
    /// the grid, the setting chosen to reach deepest (on the zip-line generalized-α: ESDIRK4
    /// gives up there below rtol 1e-3), and otherwise ESDIRK4, whose fourth order settles the
    /// sudden loads' means to 10⁻⁹.
    pub fn means_method(&self) -> Method {
        self.points
            .iter()
            .min_by(|a, b| a.rtol.total_cmp(&b.rtol))
            .map_or(Method::Esdirk4, |p| p.method)
    }

    /// The steps a run of this point may take, and whether it spends them whole: a point past
    /// the grid does, and may take [`POINT_STEPS_FACTOR`] times a grid run's.
    pub fn budget(&self, point: &GridPoint) -> (usize, bool) {
        if self.points.contains(point) {
            (POINT_STEPS_FACTOR.saturating_mul(self.max_steps), true)
        } else {
            (self.max_steps, false)
        }
    }

    /// Every method that can integrate the scene, rtol from 1e-2 to 1e-8 (1e-6 on a beam), and
    /// on a beam the scene's mesh and one half as fine. Dormand–Prince is left out on a beam:
    /// explicit, it is held to the stability limit of the stiffest mode (its steps grow as √E,
    /// test `stiffness_from_rubber_to_fifty_times_steel`), and with a disk on the beam it
    /// factorises the state-dependent mass at every evaluation; `--methods` brings it back.
    pub fn default_for(scene: &Scene) -> Plan {
        match &scene.model {
            Model::Rolling(_) => Plan {
                methods: vec![Method::Dopri5, Method::TrBdf2, Method::Esdirk4],
                rtols: (2..=8).map(|k| 10f64.powi(-k)).collect(),
                meshes: Vec::new(),
                orders: Vec::new(),
                models: Vec::new(),
                max_steps: 200_000,
                reference_from: None,
                points: Vec::new(),
            },
            Model::Beam(b) => Plan {
                methods: vec![Method::GenAlpha, Method::Esdirk4, Method::TrBdf2],
                rtols: (2..=6).map(|k| 10f64.powi(-k)).collect(),
                meshes: vec![b.beam.elements.div_ceil(2), b.beam.elements],
                orders: Vec::new(),
                models: Vec::new(),
                max_steps: 20_000,
                reference_from: None,
                points: Vec::new(),
            },
        }
    }
}

/// One quantity a user reads off a run, and the family whose largest value scales its error.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Headline {
    pub name: String,
    pub value: f64,
    family: String,
}

/// The headline quantities of a run.
pub fn headlines(r: &Run) -> Vec<Headline> {
    let h = |name: String, value: f64, family: &str| Headline {
        name,
        value,
        family: family.to_string(),
    };
    let mut out = Vec::new();
    match r {
        Run::Beam(b) => {
            for (k, p) in b.setup.probes.iter().enumerate() {
                let (lo, hi) = b
                    .rows
                    .iter()
                    .map(|row| row.probes[k].w)
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), w| {
                        (l.min(w), u.max(w))
                    });
                out.push(h(format!("{}.w_min", p.name), lo, "w"));
                out.push(h(format!("{}.w_max", p.name), hi, "w"));
            }
        }
        Run::Rolling(rr) => {
            let d = rr.last.disk;
            out.push(h("disk.x_end".into(), d.x, "position"));
            out.push(h("disk.y_end".into(), d.y, "position"));
            let (lo, hi) = rr
                .rows
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), row| {
                    (l.min(row.disk.rn), u.max(row.disk.rn))
                });
            out.push(h("disk.rn_min".into(), lo, "rn"));
            out.push(h("disk.rn_max".into(), hi, "rn"));
        }
    }
    out.push(h("t_end".into(), r.header().t_end, "t"));
    out
}

/// max |a − b| / (largest |b| of the same family), over the headlines.
pub fn headline_error(a: &[Headline], reference: &[Headline]) -> f64 {
    let scale = |family: &str| {
        reference
            .iter()
            .filter(|h| h.family == family)
            .fold(0.0_f64, |m, h| m.max(h.value.abs()))
            .max(f64::MIN_POSITIVE)
    };
    a.iter()
        .zip(reference)
        .map(|(x, r)| (x.value - r.value).abs() / scale(&r.family))
        .fold(0.0, |m, e| if e.is_nan() { f64::NAN } else { m.max(e) })
}

/// The history a run is compared on: per output time, the probes' deflections (beam) or the
/// disk centre (rigid curve).
pub fn history(r: &Run) -> Vec<(f64, Vec<f64>)> {
    match r {
        Run::Beam(b) => b
            .rows
            .iter()
            .map(|row| (row.t, row.probes.iter().map(|p| p.w).collect()))
            .collect(),
        Run::Rolling(rr) => rr
            .rows
            .iter()
            .map(|row| (row.t, vec![row.disk.x, row.disk.y]))
            .collect(),
    }
}

/// max over the reference's output times of |a − b| at the same time, relative to the largest
/// |b|; a reference time the run did not reach (it ended before) counts as wholly wrong. Rows
/// are matched by time: a run also records the times of its scene's shapes.
pub fn history_error(a: &[(f64, Vec<f64>)], reference: &[(f64, Vec<f64>)]) -> f64 {
    let scale = reference
        .iter()
        .flat_map(|(_, v)| v.iter())
        .fold(0.0_f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let same_time = |x: f64, y: f64| (x - y).abs() <= 1e-9 * (1.0 + y.abs());
    let mut rows = a.iter().peekable();
    let mut worst = 0.0_f64;
    for (t, r) in reference {
        while rows
            .next_if(|(ta, _)| *ta < *t && !same_time(*ta, *t))
            .is_some()
        {}
        match rows.peek() {
            Some((ta, x)) if same_time(*ta, *t) => {
                worst = x
                    .iter()
                    .zip(r)
                    .map(|(p, q)| (p - q).abs())
                    .fold(worst, f64::max);
            }
            _ => return 1.0,
        }
    }
    worst / scale
}

/// The scene with its beam meshed into `elements` of degree `order` and modelled as `model`.
fn with_mesh(
    scene: &Scene,
    elements: Option<usize>,
    order: Option<usize>,
    model: Option<BeamModel>,
) -> Scene {
    let mut s = scene.clone();
    if let Model::Beam(b) = &mut s.model {
        if let Some(n) = elements {
            b.beam.elements = n;
        }
        if let Some(p) = order {
            b.beam.order = p;
        }
        if let Some(m) = model {
            b.beam.model = m;
        }
    }
    s
}

/// "exact", "linear", "modal:16".
pub fn model_label(model: BeamModel) -> String {
    match model {
        BeamModel::Modal { modes } => format!("modal:{modes}"),
        other => other.name().to_string(),
    }
}

/// A beam model as `--models` names it: exact, linear or modal:N.
pub fn parse_model(text: &str) -> Result<BeamModel, Error> {
    match text {
        "exact" => Ok(BeamModel::Exact),
        "linear" => Ok(BeamModel::Linear),
        _ => text
            .strip_prefix("modal:")
            .and_then(|n| n.parse::<usize>().ok())
            .filter(|n| (1..=crate::beam::modal::MAX_MODES).contains(n))
            .map(|modes| BeamModel::Modal { modes })
            .ok_or_else(|| {
                Error::Input(format!(
                    "--models {}: a beam model is exact, linear or modal:N with N from 1 to {}",
                    crate::error::quote(text),
                    crate::beam::modal::MAX_MODES
                ))
            }),
    }
}

/// atol is a thousandth of rtol, so that the tolerance a run is asked for is its rtol: the
/// states here are metres, radians and their rates, of order 10⁻² and up.
fn overrides(method: Method, rtol: f64, max_steps: usize) -> Overrides {
    Overrides {
        method: Some(method),
        rtol: Some(rtol),
        atol: Some(rtol * 1e-3),
        fixed_step: None,
        max_steps: Some(max_steps),
        ..Default::default()
    }
}

/// The same, recording the probes' windowed means.
fn with_means(over: Overrides) -> Overrides {
    Overrides {
        windowed_means: true,
        ..over
    }
}

/// The reference run and how settled it is.
pub struct Reference {
    pub method: Method,
    pub rtol: f64,
    pub elements: Option<usize>,
    /// The elements' degree, where the plan sweeps it (otherwise the scene's).
    pub order: Option<usize>,
    /// Largest relative headline change at the last tenfold cut of rtol.
    pub settled_to: f64,
    /// Largest relative headline difference from the same run on a mesh twice as fine: the
    /// mesh's own error, which no cut of rtol shows (`None` on a rigid curve, and in a
    /// reference stored before it was measured).
    pub mesh_gap: Option<f64>,
    pub headlines: Vec<Headline>,
    pub history: Vec<(f64, Vec<f64>)>,
    pub wall_s: f64,
    /// The command that computes it again.
    pub made_by: String,
    /// The probes' windowed means, where a reference for them was made.
    pub means: Option<MeansReference>,
}

/// The reference for the probes' Hann-windowed means (`BeamRun::windowed_means`): a headline
/// the fast modes' phase leaves alone, so it converges where the extremes cannot (REPORT.md,
/// "A windowed mean reaches 10⁻⁶ on the sudden loads"). It has its own run, since the means
/// need a fourth-order method, not the extremes' reference's tenfold cuts of rtol.
#[derive(Clone, Debug)]
pub struct MeansReference {
    pub method: Method,
    pub rtol: f64,
    pub elements: Option<usize>,
    /// The elements' degree, where it is not the scene's.
    pub order: Option<usize>,
    pub values: Vec<f64>,
    /// The largest |w| of that run's probes: what an error in the means is relative to.
    pub scale: f64,
    /// The larger of how far the means move at a tenfold cut of rtol and on a mesh half as
    /// fine.
    pub resolves: f64,
    pub wall_s: f64,
    pub made_by: String,
}

/// max |a − b| / scale over the windows; a run that did not cover the reference's windows
/// counts as wholly wrong.
pub fn mean_error(a: &[f64], reference: &MeansReference) -> f64 {
    if a.len() != reference.values.len() {
        return 1.0;
    }
    a.iter()
        .zip(&reference.values)
        .map(|(x, r)| (x - r).abs() / reference.scale)
        .fold(0.0, |m, e| if e.is_nan() { f64::NAN } else { m.max(e) })
}

/// The windowed means of a beam run (none on a rigid curve).
pub fn windowed_means(r: &Run) -> Option<&[f64]> {
    match r {
        Run::Beam(b) => Some(&b.windowed_means),
        Run::Rolling(_) => None,
    }
}

/// The means' reference for a beam scene: [`Plan::means_method`] a decade below the tightest
/// rtol tried ([`Plan::means_rtol`]) on twice the finest mesh tried, of the highest degree
/// tried ([`Plan::means_mesh`]), checked at a tenfold rtol and on a mesh half as fine.
pub fn means_reference(scene: &Scene, plan: &Plan, made_by: &str) -> Result<MeansReference, Error> {
    let Some(beam) = scene.beam() else {
        return Err(Error::Input(format!(
            "{}: windowed means are a beam's headline; the scene has no beam",
            scene.name
        )));
    };
    let (elements, order) = plan.means_mesh();
    let elements = elements.unwrap_or(2 * beam.beam.elements);
    let method = plan.means_method();
    let run_on = |elements: usize, rtol: f64| {
        let s = with_mesh(scene, Some(elements), order, None);
        run::run(&s, &with_means(overrides(method, rtol, usize::MAX)), false)
    };
    let rtol = plan.means_rtol();
    let fine = run_on(elements, rtol)?;
    let looser = run_on(elements, 10.0 * rtol)?;
    let coarser = run_on(elements.div_ceil(2), rtol)?;
    let means = |r: &Run| windowed_means(r).unwrap_or_default().to_vec();
    let scale = headlines(&fine)
        .iter()
        .filter(|h| h.family == "w")
        .fold(0.0_f64, |m, h| m.max(h.value.abs()))
        .max(f64::MIN_POSITIVE);
    let mut reference = MeansReference {
        method,
        rtol,
        elements: Some(elements),
        order,
        values: means(&fine),
        scale,
        resolves: 0.0,
        wall_s: [&fine, &looser, &coarser]
            .iter()
            .map(|r| r.header().stats.wall_s)
            .sum(),
        made_by: made_by.to_string(),
    };
    reference.resolves =
        mean_error(&means(&looser), &reference).max(mean_error(&means(&coarser), &reference));
    Ok(reference)
}

impl Reference {
    /// The smallest error the reference can score a run to: how far it is settled in time,
    /// or in its mesh where that was measured.
    pub fn resolves(&self) -> f64 {
        self.settled_to.max(self.mesh_gap.unwrap_or(0.0))
    }
}

/// The method a reference is computed with: the most accurate for the kind of scene.
pub fn reference_method(scene: &Scene) -> Method {
    match &scene.model {
        Model::Rolling(_) => Method::Dopri5,
        Model::Beam(_) => Method::GenAlpha,
    }
}

/// Compute the reference; `made_by` is the command that does it again.
pub fn reference(scene: &Scene, plan: &Plan, made_by: &str) -> Result<Reference, Error> {
    let method = reference_method(scene);
    let elements = match &scene.model {
        Model::Rolling(_) => None,
        Model::Beam(_) => Some(2 * plan.meshes.iter().copied().max().unwrap_or(1)),
    };
    let order = plan.reference_order();
    let fine = with_mesh(scene, elements, order, None);
    let mut rtol = plan.reference_rtol();
    let run_at = |rtol: f64| run::run(&fine, &overrides(method, rtol, usize::MAX), false);
    let mut last = run_at(rtol)?;
    let mut wall = last.header().stats.wall_s;
    let mut settled_to = f64::INFINITY;
    for _ in 0..REFERENCE_CUTS {
        let next = run_at(rtol / 10.0)?;
        wall += next.header().stats.wall_s;
        settled_to = headline_error(&headlines(&last), &headlines(&next));
        rtol /= 10.0;
        last = next;
        if settled_to <= REFERENCE_SETTLED {
            break;
        }
    }
    // The cuts of rtol say nothing of the mesh; one run on a mesh twice as fine does. On the
    // undamped studies it is the larger of the two (docs/numerics.md, "The work–precision grids").
    let mesh_gap = match elements {
        Some(n) => {
            let finer = with_mesh(scene, Some(2 * n), order, None);
            let check = run::run(&finer, &overrides(method, rtol, usize::MAX), false)?;
            wall += check.header().stats.wall_s;
            Some(headline_error(&headlines(&last), &headlines(&check)))
        }
        None => None,
    };
    Ok(Reference {
        method,
        rtol,
        elements,
        order,
        settled_to,
        mesh_gap,
        headlines: headlines(&last),
        history: history(&last),
        wall_s: wall,
        made_by: made_by.to_string(),
        means: None,
    })
}

/// The reference for `scene`, read from `file`: the stored one where it serves (see
/// `reference.rs`), otherwise computed, and stored when `store` is set (`--reference`). The
/// line says which, and why.
pub fn reference_for(
    scene: &Scene,
    file: &Path,
    plan: &Plan,
    store: bool,
    made_by: &str,
) -> Result<(Reference, String), Error> {
    let path = super::reference::stored_path(file, &scene.name);
    let hash = super::reference::scene_hash(file)?;
    let why = if store {
        "asked to compute it again".to_string()
    } else {
        let scene_order = scene.beam().map(|b| b.beam.order);
        match super::reference::load(&path, &hash, plan, reference_method(scene), scene_order) {
            super::reference::Stored::Usable(r) => {
                let line = format!("stored reference {} ({hash})", path.display());
                return Ok((*r, line));
            }
            super::reference::Stored::Missing => {
                format!("no stored reference at {}", path.display())
            }
            super::reference::Stored::Stale(why) => {
                format!("the stored reference does not serve: {why}")
            }
        }
    };
    say!("{}: computing the reference ({why})…", scene.name);
    let mut r = reference(scene, plan, made_by)?;
    let line = if store {
        r.means = super::reference::stored_means(&path, &hash);
        super::reference::store(&r, &scene.name, &hash, &path)?;
        format!("computed and stored the reference in {}", path.display())
    } else {
        format!("computed the reference ({why}; `{made_by}` stores one)")
    };
    Ok((r, line))
}

/// One run of the grid and what it measured.
#[derive(Clone, Debug)]
pub struct Trial {
    pub point: GridPoint,
    pub outcome: Result<Measured, String>,
    /// Wall time from the run's start until its outcome was known: what a run that stopped
    /// on its step budget cost (a finished run's own time is [`Measured::wall_s`]).
    pub spent_s: f64,
}

#[derive(Clone, Debug)]
pub struct Measured {
    pub headline_error: f64,
    /// Against the reference's windowed means, where it has them.
    pub mean_error: Option<f64>,
    pub history_error: f64,
    pub wall_s: f64,
    pub steps: usize,
    pub rejected: usize,
    pub rhs_evals: usize,
}

/// One point of a work–precision grid; `None` keeps the scene's own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridPoint {
    pub method: Method,
    pub rtol: f64,
    pub elements: Option<usize>,
    pub order: Option<usize>,
    pub model: Option<BeamModel>,
}

/// Every point of the plan's grid, then the points past it, in the order its diagram and
/// tables list them.
pub fn grid(plan: &Plan) -> Vec<GridPoint> {
    fn each<T: Copy>(values: &[T]) -> Vec<Option<T>> {
        if values.is_empty() {
            vec![None]
        } else {
            values.iter().map(|&v| Some(v)).collect()
        }
    }
    let mut grid = Vec::new();
    for &method in &plan.methods {
        for model in each(&plan.models) {
            for order in each(&plan.orders) {
                for elements in each(&plan.meshes) {
                    for &rtol in &plan.rtols {
                        grid.push(GridPoint {
                            method,
                            rtol,
                            elements,
                            order,
                            model,
                        });
                    }
                }
            }
        }
    }
    grid.extend(plan.points.iter().copied());
    grid
}

/// Every run of the plan's grid, on every core.
pub fn trials(
    scene: &Scene,
    plan: &Plan,
    reference: &Reference,
    show_progress: bool,
) -> Vec<Trial> {
    super::parallel::map(&grid(plan), show_progress, |&point| {
        trial(scene, plan, reference, point)
    })
}

/// One run of the grid, scored against the reference.
pub fn trial(scene: &Scene, plan: &Plan, reference: &Reference, point: GridPoint) -> Trial {
    let scene = with_mesh(scene, point.elements, point.order, point.model);
    let (max_steps, whole_budget) = plan.budget(&point);
    let mut over = Overrides {
        whole_budget,
        ..overrides(point.method, point.rtol, max_steps)
    };
    if reference.means.is_some() {
        over = with_means(over);
    }
    let started = std::time::Instant::now();
    let outcome = run::run(&scene, &over, false)
        .and_then(|r| {
            let wall_s = mean_wall(&scene, &over, r.header().stats.wall_s)?;
            Ok(Measured {
                headline_error: headline_error(&headlines(&r), &reference.headlines),
                mean_error: reference
                    .means
                    .as_ref()
                    .zip(windowed_means(&r))
                    .map(|(m, values)| mean_error(values, m)),
                history_error: history_error(&history(&r), &reference.history),
                wall_s,
                steps: r.header().stats.steps,
                rejected: r.header().stats.rejected,
                rhs_evals: r.header().stats.rhs_evals,
            })
        })
        .map_err(|e| e.to_string());
    Trial {
        point,
        outcome,
        spent_s: started.elapsed().as_secs_f64(),
    }
}

/// A run shorter than [`TIMING_FLOOR`] is below the clock's resolution and the noise of a
/// shared machine: it is repeated until the repeats add up to that, and their mean is its time.
fn mean_wall(scene: &Scene, over: &Overrides, first: f64) -> Result<f64, Error> {
    let (mut total, mut count) = (first, 1);
    while total < TIMING_FLOOR && count < 1000 {
        total += run::run(scene, over, false)?.header().stats.wall_s;
        count += 1;
    }
    Ok(total / count as f64)
}

/// What a diagram scores a run by.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Score {
    /// The headlines: the probes' extremes on a beam, the disk's end and contact on a curve.
    Headlines,
    /// The probes' windowed means, where the reference has them.
    Means,
}

impl Score {
    pub fn of(self, m: &Measured) -> Option<f64> {
        match self {
            Score::Headlines => Some(m.headline_error),
            Score::Means => m.mean_error,
        }
    }
}

/// The fastest trial whose headline error is within `target`.
pub fn cheapest(trials: &[Trial], target: f64) -> Option<&Trial> {
    cheapest_in(trials, target, Score::Headlines)
}

/// The fastest trial whose error in `score` is within `target`.
pub fn cheapest_in(trials: &[Trial], target: f64, score: Score) -> Option<&Trial> {
    trials
        .iter()
        .filter(|t| {
            t.outcome
                .as_ref()
                .is_ok_and(|m| score.of(m).is_some_and(|e| e <= target))
        })
        .min_by(|a, b| {
            let wall = |t: &Trial| t.outcome.as_ref().map_or(f64::INFINITY, |m| m.wall_s);
            wall(a).total_cmp(&wall(b))
        })
}

impl Trial {
    /// "genalpha, rtol 1e-4, 10 elements, degree 8, modal:16".
    pub fn settings(&self) -> String {
        let p = &self.point;
        let mesh = p
            .elements
            .map_or(String::new(), |n| format!(", {n} elements"));
        let order = p.order.map_or(String::new(), |k| format!(", degree {k}"));
        let model = p
            .model
            .map_or(String::new(), |m| format!(", {}", model_label(m)));
        format!("{}, rtol {:e}{mesh}{order}{model}", p.method.name(), p.rtol)
    }
}

/// tradeoff.csv and tradeoff.svg in `dir`; the closing lines for the terminal.
pub fn write_tradeoff(
    scene: &Scene,
    reference: &Reference,
    trials: &[Trial],
    dir: &Path,
) -> Result<Vec<String>, Error> {
    std::fs::create_dir_all(dir).map_err(|e| io_error(dir, e))?;
    let mut csv = String::from(
        "method,rtol,elements,order,model,status,headline_error,history_error,wall_s,steps,rejected,rhs_evals,mean_error\n",
    );
    for t in trials {
        let p = &t.point;
        let mesh = p.elements.map_or(String::new(), |n| n.to_string());
        let order = p.order.map_or(String::new(), |k| k.to_string());
        let model = p.model.map_or(String::new(), model_label);
        let _ = match &t.outcome {
            Ok(m) => writeln!(
                csv,
                "{},{:e},{mesh},{order},{model},ok,{:e},{:e},{},{},{},{},{}",
                p.method.name(),
                p.rtol,
                m.headline_error,
                m.history_error,
                m.wall_s,
                m.steps,
                m.rejected,
                m.rhs_evals,
                m.mean_error.map_or(String::new(), |e| format!("{e:e}"))
            ),
            Err(e) => writeln!(
                csv,
                "{},{:e},{mesh},{order},{model},\"failed: {}\",,,{},,,,",
                p.method.name(),
                p.rtol,
                e.replace('"', "'"),
                t.spent_s
            ),
        };
    }
    write(&dir.join("tradeoff.csv"), &csv)?;
    diagram(scene, trials, Score::Headlines, &dir.join("tradeoff.svg"))?;
    let mesh = match (reference.elements, reference.mesh_gap) {
        (None, _) => String::new(),
        (Some(_), Some(gap)) => format!(", and lie {gap:.1e} from a mesh twice as fine"),
        (Some(_), None) => {
            "; its mesh was not checked against a finer one (stored before rollbeam did so; --reference does)".to_string()
        }
    };
    let mut lines = vec![format!(
        "reference: {}, rtol {:.0e}{}{} ({:.2} s): headlines settled to {:.1e} at the last tenfold cut of rtol{mesh}",
        reference.method.name(),
        reference.rtol,
        reference
            .elements
            .map_or(String::new(), |n| format!(", {n} elements")),
        reference
            .order
            .map_or(String::new(), |k| format!(", degree {k}")),
        reference.wall_s,
        reference.settled_to,
    )];
    lines.extend(cheapest_lines(
        trials,
        Score::Headlines,
        reference.resolves(),
        "",
    ));
    if let Some(means) = &reference.means {
        lines.push(format!(
            "windowed means' reference: {}, rtol {:.0e}{}{} ({:.2} s): resolves {:.1e} (a tenfold cut of rtol, and a mesh half as fine)",
            means.method.name(),
            means.rtol,
            means
                .elements
                .map_or(String::new(), |n| format!(", {n} elements")),
            means
                .order
                .map_or(String::new(), |k| format!(", degree {k}")),
            means.wall_s,
            means.resolves,
        ));
        lines.extend(cheapest_lines(
            trials,
            Score::Means,
            means.resolves,
            "in the windowed means ",
        ));
        diagram(scene, trials, Score::Means, &dir.join("tradeoff-means.svg"))?;
    } else {
        // A means diagram from an earlier run would otherwise pass for this one's.
        let _ = std::fs::remove_file(dir.join("tradeoff-means.svg"));
    }
    let mut summary = String::new();
    for l in &lines {
        let _ = writeln!(summary, "{l}");
    }
    write(&dir.join("tradeoff.txt"), &summary)?;
    Ok(lines)
}

/// The cheapest setting for each of [`TARGETS`] in `score`, a line each.
fn cheapest_lines(trials: &[Trial], score: Score, resolves: f64, what: &str) -> Vec<String> {
    TARGETS
        .iter()
        .map(|&target| match cheapest_in(trials, target, score) {
            _ if target < resolves => {
                format!("{what}{target:.0e}: below what the reference resolves ({resolves:.1e})")
            }
            Some(t) => {
                let m = t.outcome.as_ref().expect("cheapest is a finished run");
                format!(
                    "{what}{target:.0e}: {} — error {:.1e}, {:.2e} s, {} steps",
                    t.settings(),
                    score.of(m).expect("cheapest has the score"),
                    m.wall_s,
                    m.steps
                )
            }
            None => format!("{what}{target:.0e}: no setting tried reaches it"),
        })
        .collect()
}

/// Error in `score` against the work, log–log, a line per method, mesh, degree and model. The
/// work is the right-hand sides evaluated, which a rerun repeats exactly, so the committed
/// diagrams change only where the physics or the method does; `tradeoff.csv` and
/// `tradeoff.txt` keep the wall times.
fn diagram(scene: &Scene, trials: &[Trial], score: Score, path: &Path) -> Result<(), Error> {
    let err =
        |e: &dyn std::fmt::Display| Error::Output(format!("cannot draw {}: {e}", path.display()));
    let mut lines: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for t in trials {
        let Ok(m) = &t.outcome else { continue };
        let Some(error) = score.of(m) else { continue };
        let p = &t.point;
        let mut name = match (p.elements, p.order) {
            (Some(n), Some(k)) => format!("{} ({n} el. p{k})", p.method.name()),
            (Some(n), None) => format!("{} ({n} el.)", p.method.name()),
            (None, _) => p.method.name().to_string(),
        };
        if let Some(m) = p.model {
            name = format!("{name} {}", model_label(m));
        }
        let point = ((m.rhs_evals as f64).max(1.0), error.max(1e-12));
        match lines.iter_mut().find(|(n, _)| *n == name) {
            Some((_, pts)) => pts.push(point),
            None => lines.push((name, vec![point])),
        }
    }
    let all = lines.iter().flat_map(|(_, p)| p.iter());
    let (x0, x1, y0, y1) = all.fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
    );
    if !x0.is_finite() {
        return Ok(());
    }
    // A legend of many lines (D44's 37) would run off the foot of the figure and hide the
    // costliest runs in the upper right: the figure grows with it, and the time axis runs on
    // for two fifths of its decades again, to the legend's right of the data. Past the
    // palette's colours the lines take another marker, so that each stays told apart.
    let many = lines.len() > 12;
    let height = if many {
        150 + 16 * lines.len() as u32
    } else {
        600
    };
    let x_end = if many {
        x1 * 1.5 * (x1 * 1.5 / (x0 / 1.5)).powf(0.4)
    } else {
        x1 * 1.5
    };
    crate::output::plots::svg(path, (900, height.max(600)), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                match score {
                    Score::Headlines => format!("{}: work–precision", scene.name),
                    Score::Means => format!("{}: work–precision in the windowed means", scene.name),
                },
                ("sans-serif", 22),
            )
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(
                (x0 / 1.5..x_end).log_scale(),
                // From just below a whole decade: plotters labels a log axis from the first
                // decade inside its range upwards, so errors below that would go unlabelled.
                (0.99 * 10f64.powf((y0 / 3.0).log10().floor())..y1 * 3.0).log_scale(),
            )
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("right-hand sides evaluated (work)")
            .y_desc(match score {
                Score::Headlines => "headline error (relative)",
                Score::Means => "error in the windowed means (relative)",
            })
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(|e| err(&e))?;
        for (i, (name, pts)) in lines.iter().enumerate() {
            let color = PALETTE[i % PALETTE.len()];
            let style = if i < PALETTE.len() {
                color.stroke_width(2)
            } else {
                color.stroke_width(1)
            };
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), style))
                .map_err(|e| err(&e))?
                .label(name.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
            match i / PALETTE.len() {
                0 => chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled()))),
                1 => {
                    chart.draw_series(pts.iter().map(|&p| Cross::new(p, 4, color.stroke_width(2))))
                }
                2 => chart.draw_series(
                    pts.iter()
                        .map(|&p| TriangleMarker::new(p, 4, color.filled())),
                ),
                _ => chart.draw_series(
                    pts.iter()
                        .map(|&p| Circle::new(p, 4, color.stroke_width(1))),
                ),
            }
            .map_err(|e| err(&e))?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(|e| err(&e))?;
        Ok(())
    })
}

/// What a work–precision run may be told, beside the scene: empty lists keep the defaults.
#[derive(Clone, Debug, Default)]
pub struct TradeoffOptions {
    pub methods: Vec<String>,
    pub rtols: Vec<f64>,
    pub elements: Vec<usize>,
    pub orders: Vec<usize>,
    pub models: Vec<String>,
    pub max_steps: Option<usize>,
    /// Settings past the grid, METHOD:RTOL:ELEMENTS:DEGREE each.
    pub points: Vec<String>,
    /// Compute the reference again and store it beside the scene file.
    pub recompute: bool,
    /// Make the windowed means' reference and store it with the scene's reference.
    pub recompute_means: bool,
}

impl TradeoffOptions {
    /// The scene's default plan with the options applied, each checked.
    pub fn plan(&self, scene: &Scene) -> Result<Plan, Error> {
        let mut plan = Plan::default_for(scene);
        if !self.methods.is_empty() {
            plan.methods = self
                .methods
                .iter()
                .map(|m| parse_method(m, scene))
                .collect::<Result<_, _>>()?;
        }
        if !self.rtols.is_empty() {
            for &r in &self.rtols {
                rtol_flag(Some(r), "--rtols")?;
            }
            plan.rtols = self.rtols.clone();
        }
        if !self.elements.is_empty() {
            if scene.beam().is_none() {
                return Err(Error::Input(
                    "--elements meshes a beam; this scene has a rigid curve".into(),
                ));
            }
            if let Some(&bad) = self.elements.iter().find(|n| !ELEMENTS_TRIED.contains(n)) {
                return Err(Error::Input(format!(
                    "--elements {bad}: {}",
                    elements_tried()
                )));
            }
            plan.meshes = self.elements.clone();
        }
        if !self.orders.is_empty() {
            if scene.beam().is_none() {
                return Err(Error::Input(
                    "--orders sets the degree of a beam's elements; this scene has a rigid curve"
                        .into(),
                ));
            }
            if let Some(&bad) = self.orders.iter().find(|k| !DEGREES.contains(k)) {
                return Err(Error::Input(format!("--orders {bad}: {}", degrees())));
            }
            plan.orders = self.orders.clone();
        }
        if !self.models.is_empty() {
            if scene.beam().is_none() {
                return Err(Error::Input(
                    "--models models a beam; this scene has a rigid curve".into(),
                ));
            }
            plan.models = self
                .models
                .iter()
                .map(|m| parse_model(m))
                .collect::<Result<_, _>>()?;
        }
        if let Some(m) = self.max_steps {
            if m == 0 {
                return Err(Error::Input("--max-steps must be at least 1".into()));
            }
            plan.max_steps = m;
        }
        plan.points = self
            .points
            .iter()
            .map(|p| parse_point(p, scene))
            .collect::<Result<_, _>>()?;
        let runs = [
            plan.methods.len(),
            plan.rtols.len(),
            plan.meshes.len().max(1),
            plan.orders.len().max(1),
            plan.models.len().max(1),
        ]
        .iter()
        .try_fold(1_usize, |n, &k| n.checked_mul(k))
        .and_then(|n| n.checked_add(plan.points.len()))
        .filter(|&n| n <= MAX_RUNS);
        if runs.is_none() {
            return Err(Error::Input(format!(
                "the options make more than {MAX_RUNS} runs (methods × rtols × elements × orders × models, and the points); try fewer"
            )));
        }
        Ok(plan)
    }
}

/// Most runs one work–precision diagram is made of: each is a whole run of the scene.
const MAX_RUNS: usize = 10_000;

/// The element counts a run of `tradeoff` may be given (`--elements`, `--point`).
const ELEMENTS_TRIED: std::ops::RangeInclusive<usize> = 1..=1000;
/// The elements' degrees (`--orders`, `--point`).
const DEGREES: std::ops::RangeInclusive<usize> = 1..=MAX_ORDER;

fn elements_tried() -> String {
    format!(
        "an element count is from {} to {}",
        ELEMENTS_TRIED.start(),
        ELEMENTS_TRIED.end()
    )
}

fn degrees() -> String {
    format!(
        "an element's degree is from {} to {}",
        DEGREES.start(),
        DEGREES.end()
    )
}

/// A `--point`: METHOD:RTOL:ELEMENTS:DEGREE, each part checked as its own flag is.
fn parse_point(text: &str, scene: &Scene) -> Result<GridPoint, Error> {
    let bad = |why: String| Error::Input(format!("--point {}: {why}", quote(text)));
    if scene.beam().is_none() {
        return Err(bad(
            "a point past the grid sets a beam's mesh; this scene has a rigid curve".into(),
        ));
    }
    let parts: Vec<&str> = text.split(':').collect();
    let [method, rtol, elements, order] = parts[..] else {
        return Err(bad(
            "write it METHOD:RTOL:ELEMENTS:DEGREE, e.g. esdirk4:1e-4:20:6".into(),
        ));
    };
    let method = parse_method(method, scene)?;
    let rtol: f64 = rtol
        .parse()
        .map_err(|_| bad(format!("the rtol {} is not a number", quote(rtol))))?;
    rtol_flag(Some(rtol), "--point's rtol")?;
    let elements = match elements.parse::<usize>() {
        Ok(n) if ELEMENTS_TRIED.contains(&n) => n,
        _ => return Err(bad(elements_tried())),
    };
    let order = match order.parse::<usize>() {
        Ok(k) if DEGREES.contains(&k) => k,
        _ => return Err(bad(degrees())),
    };
    Ok(GridPoint {
        method,
        rtol,
        elements: Some(elements),
        order: Some(order),
        model: None,
    })
}

/// Work–precision of a scene into `dir`: the reference (stored beside `file` where one
/// serves; computed otherwise), every trial, the files and the lines to print.
pub fn run_tradeoff(
    scene: &Scene,
    file: Option<&Path>,
    options: &TradeoffOptions,
    dir: &Path,
    made_by: &str,
    show_progress: bool,
) -> Result<(Vec<Trial>, Vec<String>), Error> {
    let plan = options.plan(scene)?;
    let (mut reference, origin) = match file {
        Some(file) => reference_for(scene, file, &plan, options.recompute, made_by)?,
        None => (
            reference(scene, &plan, made_by)?,
            "computed the reference (a scene without a file has no stored one)".to_string(),
        ),
    };
    let mut lines = vec![origin];
    if options.recompute_means {
        let Some(file) = file else {
            return Err(Error::Input(
                "windowed means' references are stored beside a scene file; this scene has none"
                    .into(),
            ));
        };
        say!("{}: computing the windowed means' reference…", scene.name);
        // `made_by` is the command that makes the headlines' reference; the means' is the
        // same command asking for them instead.
        let means_by = made_by.replacen(" --reference", " --reference-means", 1);
        let means = means_reference(scene, &plan, &means_by)?;
        let path = super::reference::stored_path(file, &scene.name);
        super::reference::store_means(&means, &super::reference::scene_hash(file)?, &path)?;
        lines.push(format!(
            "computed and stored the windowed means' reference in {}",
            path.display()
        ));
        reference.means = Some(means);
    }
    let trials = trials(scene, &plan, &reference, show_progress);
    lines.extend(write_tradeoff(scene, &reference, &trials, dir)?);
    Ok((trials, lines))
}

//! The speed–accuracy trade of a scene, measured (`rollbeam tradeoff SCENE.yaml`).
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
//!
//! Here: the options a run is told and [`run_tradeoff`], which names those steps. `plan`: the
//! grid; `reference` and `store`: the reference computed or read back; `metrics`: the error
//! measures; `trials`: the grid's runs and the cheapest; `report`: the tables and diagrams.

use std::fmt::Write as _;
use std::path::Path;

use plotters::prelude::*;

use crate::beam::{BeamModel, MAX_ORDER};
use crate::error::{quote, Error};
use crate::ode::Method;
use crate::output::plots::PALETTE;
use crate::output::{io_error, write};
use crate::run::{self, Overrides, Run};
use crate::say;
use crate::scene::{Model, Scene};
use crate::workflows::settings::{parse_method, rtol_flag};

mod metrics;
mod plan;
mod reference;
mod report;
pub mod store;
mod trials;

pub use metrics::*;
pub use plan::*;
pub use reference::*;
pub use report::*;
pub use store::reference_for;
pub use trials::*;

/// The accuracies the command names the cheapest settings for.
pub const TARGETS: [f64; 3] = [1e-2, 1e-4, 1e-6];

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
                .map(|m| parse_method(m, scene, "--methods"))
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
    let method = parse_method(method, scene, "--point's method")?;
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
        let path = store::stored_path(file, &scene.name);
        store::store_means(&means, &store::scene_hash(file)?, &path)?;
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

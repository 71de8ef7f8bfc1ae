//! The grid's runs on every core, each measured (error, wall time, steps, evaluations), and
//! the cheapest that reach an accuracy.

use super::*;

/// Runs shorter than this (s) are timed as the mean of repeats that add up to it.
pub(super) const TIMING_FLOOR: f64 = 0.05;

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
    pub(super) fn each<T: Copy>(values: &[T]) -> Vec<Option<T>> {
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
    crate::workflows::parallel::map(&grid(plan), show_progress, |&point| {
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
pub(super) fn mean_wall(scene: &Scene, over: &Overrides, first: f64) -> Result<f64, Error> {
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

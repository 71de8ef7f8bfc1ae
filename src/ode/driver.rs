//! The one stepping driver: output times, breakpoints, event location and step-size control,
//! the same for every [`Stepper`].

use std::cell::RefCell;
use std::time::Instant;

use super::dopri5::Dopri5;
use super::esdirk::Esdirk4;
use super::exact_modal::ExactModal;
use super::genalpha::GenAlphaStepper;
use super::stage_solver::Dirk;
use super::trbdf2::TrBdf2;
use super::{
    Attempt, Ctx, Dense, Dynamics, EventHit, EventSpec, Method, Observer, Options, Outcome,
    Problem, SolveError, Stats, Stepper, EVENT_TIME_TOL, SAFETY,
};

fn make_stepper(opts: &Options, n: usize) -> Box<dyn Stepper> {
    match opts.method {
        Method::Dopri5 => Box::new(Dopri5::new(n)),
        Method::TrBdf2 => Box::new(Dirk::new(TrBdf2::new(n), n)),
        Method::Esdirk4 => Box::new(Dirk::new(Esdirk4::new(n), n)),
        Method::GenAlpha => Box::new(GenAlphaStepper::new(opts.rho_inf, n)),
        Method::ExactModal => Box::new(ExactModal::new(n)),
    }
}

/// Integrate from (t0, y0) to t_end, reporting at every time of `outputs` that the run reaches
/// (sorted, within [t0, t_end]) and after every step.
pub fn solve<E: Copy + std::fmt::Debug>(
    p: &dyn Problem<Event = E>,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    outputs: &[f64],
    opts: &Options,
    observer: &mut dyn Observer,
) -> Result<Outcome<E>, SolveError> {
    let clock = Instant::now();
    let mut d = Driver::new(p, t0, y0, t_end, outputs, opts);
    let stopped_by = d.run(observer)?;
    d.ctx.stats.wall_s = clock.elapsed().as_secs_f64();
    Ok(Outcome {
        t: d.t,
        y: d.y,
        stats: d.ctx.stats,
        stopped_by,
        events: d.events,
    })
}

/// One run of the driver: where it is, what it has reported, and what it watches.
struct Driver<'a, E> {
    p: &'a dyn Problem<Event = E>,
    opts: &'a Options,
    outputs: &'a [f64],
    t_end: f64,
    ctx: Ctx,
    stepper: Box<dyn Stepper>,
    t: f64,
    y: Vec<f64>,
    /// The first output time not yet reported.
    next_out: usize,
    /// Non-terminal events met so far.
    events: Vec<EventHit<E>>,
    /// The event functions at (t, y).
    g: Vec<f64>,
    breaks: Vec<f64>,
    /// Steps shorter than this are round-off.
    h_min: f64,
    /// The longest step the controller proposes: [`NEWTON_CAP`] of the last step on which
    /// Newton failed, loosened by [`NEWTON_CAP_EASING`] at every accepted step.
    newton_cap: f64,
    /// Where the current pace window started: (steps, t).
    pace_from: (usize, f64),
    /// Whether the last pace window projected past the budget's margin.
    pace_over: bool,
    y_tmp: Vec<f64>,
}

/// How an attempted step went.
enum Trial {
    Accepted {
        err: f64,
    },
    /// Rejected: try again with this step.
    Rejected {
        h: f64,
        on_error: bool,
    },
}

/// Accepted steps over which the pace of a run is measured for its step budget.
const PACE_WINDOW: usize = 2000;
/// How far past the budget a projection must go, in two windows running, before a run gives
/// up early. A run's pace varies along it: on a sudden load the first steps are the densest,
/// and on B1 the first 2000 projected 2.5 to 6 times the steps taken (generalized-α at rtol
/// 10⁻⁴: 47 000 projected, 18 640 taken; ESDIRK4 at 10⁻³: 21 000 and 3459). A time scale a
/// scene made tiny projects thousands of times past. A larger margin would spend whole
/// budgets on runs that do exceed them (ESDIRK4 at 10⁻⁴: 130 000 projected, 47 360 taken).
const PACE_MARGIN: usize = 4;

/// The most stretches a step's events are looked at in ([`Problem::event_pace`]): the pace
/// serves steps a few times longer than it, and a step far longer is no reason to sample its
/// events without end.
const MAX_EVENT_PIECES: f64 = 1024.0;

/// The step after one on which Newton failed, as a fraction of it.
const NEWTON_CUT: f64 = 0.5;
/// The controller's steps stay below this fraction of the last step on which Newton failed:
/// where the error allows far longer steps than Newton converges on (a disk rolling on a
/// beam, whose convective terms the tangent leaves out), growing straight back fails again.
/// Without the cap ESDIRK4 on D44 at rtol 10⁻⁴ failed Newton on 2499 of its 9651 steps
/// (docs/numerics.md, "Steps Newton cannot take").
const NEWTON_CAP: f64 = 0.9;
/// How fast the cap eases at each accepted step: where Newton converges again on longer
/// steps (the disk has moved on), the steps grow back within a few dozen.
const NEWTON_CAP_EASING: f64 = 1.02;

impl<'a, E: Copy + std::fmt::Debug> Driver<'a, E> {
    fn new(
        p: &'a dyn Problem<Event = E>,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        outputs: &'a [f64],
        opts: &'a Options,
    ) -> Self {
        let n = p.dim();
        Driver {
            p,
            opts,
            outputs,
            t_end,
            ctx: Ctx {
                rtol: opts.rtol,
                atol: opts.atol,
                stats: Stats::default(),
                mass_lu: None,
                split_lu: None,
                groups: p.norm_groups(),
                weights: p.norm_weights(),
                rows: p.norm_rows(),
            },
            stepper: make_stepper(opts, n),
            t: t0,
            y: y0.to_vec(),
            next_out: outputs.partition_point(|&o| o < t0),
            events: Vec::new(),
            g: (0..p.events().len()).map(|i| p.event(i, t0, y0)).collect(),
            breaks: breakpoints_within(
                match opts.method {
                    Method::ExactModal => [p.breakpoints(), p.kinks()].concat(),
                    _ => p.breakpoints(),
                },
                t0,
                t_end,
            ),
            h_min: 1e-14 * t0.abs().max(t_end.abs()).max(1.0),
            newton_cap: f64::INFINITY,
            pace_from: (0, t0),
            pace_over: false,
            y_tmp: vec![0.0; n],
        }
    }

    /// The end of the stretch between breakpoints that t lies in: the breakpoints are sorted,
    /// and a train sets one at every axle's crossing of every node.
    fn segment_end(&self, t: f64) -> f64 {
        let next = self.breaks.partition_point(|&b| b <= t);
        self.breaks.get(next).copied().unwrap_or(self.t_end)
    }

    fn run(&mut self, observer: &mut dyn Observer) -> Result<Option<EventHit<E>>, SolveError> {
        let dynamics: &dyn Dynamics = self.p;
        let specs = self.p.events();
        let t0 = self.t;
        while self.next_out < self.outputs.len() && self.outputs[self.next_out] <= t0 {
            observer.output(t0, &self.y);
            self.next_out += 1;
        }
        if let Some(i) = (0..specs.len()).find(|&i| specs[i].terminal && self.g[i] < 0.0) {
            return Ok(Some(EventHit {
                reason: specs[i].reason,
                t: t0,
            }));
        }
        self.p.enter_segment(t0, self.segment_end(t0));
        self.stepper.start(dynamics, t0, &self.y, &mut self.ctx)?;
        let mut h = match self.opts.fixed_step {
            Some(h) => h,
            None => self
                .stepper
                .initial_step(dynamics, t0, &self.y, self.t_end, &mut self.ctx)?,
        };
        let mut just_rejected = false;
        while self.t < self.t_end {
            self.check_budget()?;
            if self.opts.fixed_step.is_none() {
                h = h.min(self.p.max_step(self.t, &self.y));
            }
            // Steps end exactly on the next breakpoint (or the end), and restart there.
            let target = self.segment_end(self.t + self.h_min);
            let last = self.t + h >= target - self.h_min;
            let h_try = if last { target - self.t } else { h };
            let err = match self.attempt(h_try)? {
                Trial::Accepted { err } => err,
                Trial::Rejected { h: next, on_error } => {
                    // Snapped to the breakpoint, a step the controller shortens by less than the
                    // run's time resolution snaps to it again: the same step, rejected forever.
                    if last && self.t + next >= target - self.h_min {
                        return Err(SolveError::BelowResolution {
                            t: self.t,
                            h: target - self.t,
                            floor: self.h_min,
                        });
                    }
                    h = next;
                    just_rejected |= on_error;
                    continue;
                }
            };
            let t_new = if last { target } else { self.t + h_try };
            if let Some(hit) = self.accept(t_new, observer) {
                return Ok(Some(hit));
            }
            if last && target < self.t_end {
                self.p.enter_segment(self.t, self.segment_end(self.t));
                self.stepper
                    .start(dynamics, self.t, &self.y, &mut self.ctx)?;
            }
            observer.step(self.t, &self.y);
            if self.opts.fixed_step.is_none() {
                h = self.next_step(h_try, err, just_rejected);
                just_rejected = false;
            }
        }
        Ok(None)
    }

    /// The step budget: spent, or sure to be spent at the pace of the last two
    /// [`PACE_WINDOW`]s of steps (each projected [`PACE_MARGIN`] times past it), so that a run
    /// whose time scale a scene made tiny stops in a fraction of its budget, not after all of
    /// it. One window is not enough to judge: a load that comes on at the start makes the first
    /// steps the densest by far (the zip-line's first 2000 projected 16–27 times the steps its
    /// runs took), while a tiny time scale projects thousands of times past window after window.
    fn check_budget(&mut self) -> Result<(), SolveError> {
        let steps = self.ctx.stats.steps;
        let (from_steps, from_t) = self.pace_from;
        let mut projected = steps;
        let mut hopeless = false;
        if steps >= from_steps + PACE_WINDOW {
            let pace = (self.t - from_t) / (steps - from_steps) as f64;
            projected = steps.saturating_add(((self.t_end - self.t) / pace).min(1e18) as usize);
            self.pace_from = (steps, self.t);
            let over = projected > self.opts.max_steps.saturating_mul(PACE_MARGIN);
            hopeless = over && self.pace_over && !self.opts.whole_budget;
            self.pace_over = over;
        }
        if steps >= self.opts.max_steps || hopeless {
            return Err(SolveError::TooManySteps {
                t: self.t,
                steps,
                projected,
                budget: self.opts.max_steps,
            });
        }
        Ok(())
    }

    /// Attempt a step of h_try from (t, y), and judge it.
    fn attempt(&mut self, h_try: f64) -> Result<Trial, SolveError> {
        let (t, fixed) = (self.t, self.opts.fixed_step.is_some());
        let attempt = self
            .stepper
            .attempt(self.p, t, &self.y, h_try, &mut self.ctx)?;
        let err = match attempt {
            Attempt::Done { err } => err,
            Attempt::NewtonFailed => {
                if fixed {
                    return Err(SolveError::NewtonFailed { t });
                }
                self.ctx.stats.rejected += 1;
                self.newton_cap = NEWTON_CAP * h_try;
                let h = h_try * NEWTON_CUT;
                if h < self.h_min {
                    return Err(SolveError::NewtonFailed { t });
                }
                return Ok(Trial::Rejected { h, on_error: false });
            }
        };
        if !err.is_finite() && fixed {
            return Err(SolveError::NonFinite { t });
        }
        if !fixed && !(err <= 1.0) {
            self.ctx.stats.rejected += 1;
            let q = self.stepper.error_order() as f64;
            let factor = if err.is_finite() {
                (SAFETY * err.powf(-1.0 / (q + 1.0))).clamp(0.2, 1.0)
            } else {
                0.2
            };
            let h = h_try * factor;
            if h < self.h_min {
                return Err(SolveError::StepSizeUnderflow {
                    t,
                    h,
                    floor: self.h_min,
                });
            }
            return Ok(Trial::Rejected { h, on_error: true });
        }
        if self.stepper.y_new().iter().any(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite { t: t + h_try });
        }
        Ok(Trial::Accepted { err })
    }

    /// Accept the step to t_new: report the outputs it passes, and stop at the earliest
    /// terminal event in it (sign change from ≥ 0 to < 0, located on the dense output).
    fn accept(&mut self, t_new: f64, observer: &mut dyn Observer) -> Option<EventHit<E>> {
        let (p, specs) = (self.p, self.p.events());
        let stepper = &mut self.stepper;
        stepper.accept(t_new);
        self.ctx.stats.steps += 1;
        let g_new: Vec<f64> = (0..specs.len())
            .map(|i| p.event(i, t_new, stepper.y_new()))
            .collect();
        let y_tmp = &mut self.y_tmp;
        // Where the events' functions may fall below zero and rise again within the step (a
        // wheel's contact force over a crest the steps, following the motion, do not see), they
        // are looked at every `event_pace` inside it, and the first stretch with a crossing is
        // searched.
        let pace = if specs.is_empty() {
            f64::INFINITY
        } else {
            p.event_pace(self.t, &self.y)
        };
        // A pace that is not a positive number leaves the step's ends alone to look at.
        let pieces = if pace > 0.0 {
            ((t_new - self.t) / pace).ceil().min(MAX_EVENT_PIECES) as usize
        } else {
            1
        }
        .max(1);
        let mut g_start = std::mem::take(&mut self.g);
        let mut first = None;
        for k in 1..=pieces {
            let ta = self.t + (t_new - self.t) * (k - 1) as f64 / pieces as f64;
            let (tb, g_end) = if k == pieces {
                (t_new, g_new.clone())
            } else {
                let tb = self.t + (t_new - self.t) * k as f64 / pieces as f64;
                stepper.interpolate(tb, y_tmp);
                (
                    tb,
                    (0..specs.len()).map(|i| p.event(i, tb, y_tmp)).collect(),
                )
            };
            first = crossings(
                specs,
                &g_start,
                &g_end,
                ta,
                tb,
                &mut self.events,
                |i, tt| {
                    stepper.interpolate(tt, y_tmp);
                    p.event(i, tt, y_tmp)
                },
            );
            if first.is_some() {
                break;
            }
            g_start = g_end;
        }
        // The observer follows the solution to the last time known before a terminal event:
        // where the event's function jumps rather than passes through zero, the state past
        // the crossing breaks the law the problem holds until the event is handled, and what
        // is observed there is no state the system reaches.
        let t_stop = first.map_or(t_new, |(_, _, te)| te);
        let t_seen = first.map_or(t_new, |(_, before, _)| before);
        let dense = StepperDense {
            stepper: stepper.as_ref(),
            ends: (self.t, t_new),
            problem: stepper
                .rate_from_the_problem()
                .then(|| (self.p as &dyn Dynamics, RefCell::new(&mut self.ctx))),
        };
        observer.span(self.t, t_seen, &dense);
        while self.next_out < self.outputs.len() && self.outputs[self.next_out] <= t_stop {
            let to = self.outputs[self.next_out];
            stepper.interpolate(to, y_tmp);
            observer.output(to, y_tmp);
            self.next_out += 1;
        }
        if let Some((i, _, te)) = first {
            stepper.interpolate(te, y_tmp);
            observer.step(te, y_tmp);
            self.t = te;
            self.y.copy_from_slice(y_tmp);
            p.accepted(te, &self.y);
            return Some(EventHit {
                reason: specs[i].reason,
                t: te,
            });
        }
        self.t = t_new;
        self.y.copy_from_slice(stepper.y_new());
        self.g = g_new;
        p.accepted(t_new, &self.y);
        None
    }

    /// The next step after one of h_try accepted with error err; no growth straight after a
    /// rejection (Hairer & Wanner II.4), nor past the cap Newton's last failure set.
    fn next_step(&mut self, h_try: f64, err: f64, just_rejected: bool) -> f64 {
        let q = self.stepper.error_order() as f64;
        let grow = if just_rejected {
            1.0
        } else {
            self.stepper.max_growth()
        };
        let factor = (SAFETY * err.max(1e-10).powf(-1.0 / (q + 1.0))).clamp(0.2, grow);
        let cap = self.newton_cap.max(h_try);
        self.newton_cap *= NEWTON_CAP_EASING;
        self.stepper.keep_step(h_try, (h_try * factor).min(cap))
    }
}

/// The dense output of the stepper's last accepted step, which spans `ends`; with the problem
/// where y' inside is read from it ([`Stepper::rate_from_the_problem`]).
struct StepperDense<'a> {
    stepper: &'a dyn Stepper,
    ends: (f64, f64),
    problem: Option<(&'a dyn Dynamics, RefCell<&'a mut Ctx>)>,
}

impl Dense for StepperDense<'_> {
    fn at(&self, t: f64) -> Vec<f64> {
        let mut y = vec![0.0; self.stepper.y_new().len()];
        self.stepper.interpolate(t, &mut y);
        y
    }

    fn rate(&self, t: f64) -> Option<Vec<f64>> {
        let inside = t != self.ends.0 && t != self.ends.1;
        let from_problem = match &self.problem {
            Some((p, ctx)) if inside => ctx.borrow_mut().rate(*p, t, &self.at(t)),
            _ => None,
        };
        Some(from_problem.unwrap_or_else(|| {
            let mut yp = vec![0.0; self.stepper.y_new().len()];
            self.stepper.interpolate_rate(t, &mut yp);
            yp
        }))
    }

    fn power_integrals(&self, ta: f64, tb: f64) -> Option<super::PowerIntegrals> {
        self.stepper.power_integrals(ta, tb)
    }

    fn forms(&self, rows: &[super::FormRow]) -> Option<super::StepForms> {
        self.stepper.forms(rows)
    }
}

/// The breakpoints strictly inside (t0, t_end), ascending.
fn breakpoints_within(mut breaks: Vec<f64>, t0: f64, t_end: f64) -> Vec<f64> {
    breaks.retain(|&b| b > t0 && b < t_end);
    breaks.sort_by(f64::total_cmp);
    // Two loads that switch at one time (an axle entering is also its first node crossing)
    // make one breakpoint, not a step of round-off between them.
    breaks.dedup_by(|b, a| same_breakpoint(*a, *b));
    breaks
}

/// Whether two breakpoints are one: a step ends on the first of several that lie within a
/// round-off of each other, so whoever looks for a step end among them compares by this.
pub fn same_breakpoint(a: f64, b: f64) -> bool {
    (b - a).abs() <= 1e-12 * a.abs().max(1.0)
}

/// The events of one step [t0, t1] whose g passes from ≥ 0 (g0) to < 0 (g1), each located on
/// `g_at(index, t)`: non-terminal ones are recorded in `events`, and the earliest terminal one
/// is returned with the last time known before its crossing and the first known past it.
fn crossings<E: Copy>(
    specs: &[EventSpec<E>],
    g0: &[f64],
    g1: &[f64],
    t0: f64,
    t1: f64,
    events: &mut Vec<EventHit<E>>,
    mut g_at: impl FnMut(usize, f64) -> f64,
) -> Option<(usize, f64, f64)> {
    let mut first: Option<(usize, f64, f64)> = None;
    for i in 0..specs.len() {
        if !(g0[i] >= 0.0 && g1[i] < 0.0) {
            continue;
        }
        let (before, te) = locate(|tt| g_at(i, tt), t0, g0[i], t1, g1[i]);
        if specs[i].terminal {
            if first.is_none_or(|(_, _, tf)| te < tf) {
                first = Some((i, before, te));
            }
        } else {
            events.push(EventHit {
                reason: specs[i].reason,
                t: te,
            });
        }
    }
    first
}

/// Illinois (modified regula falsi) on g over [a, b] with g(a) ≥ 0 > g(b).
fn locate(
    mut g: impl FnMut(f64) -> f64,
    mut a: f64,
    mut ga: f64,
    mut b: f64,
    mut gb: f64,
) -> (f64, f64) {
    if ga == 0.0 {
        return (a, a);
    }
    let mut side = 0;
    for _ in 0..200 {
        if b - a <= EVENT_TIME_TOL {
            break;
        }
        let mut c = b - gb * (b - a) / (gb - ga);
        if !(c > a && c < b) {
            c = 0.5 * (a + b);
        }
        let gc = g(c);
        if gc >= 0.0 {
            a = c;
            ga = gc;
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        } else {
            b = c;
            gb = gc;
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        }
    }
    // The last time known before the crossing, and the first known past it: the event has
    // happened by then.
    (a, b)
}

/// Hairer–Wanner's starting step from the size of y, y' and an estimate of y''.
pub(super) fn initial_step(
    p: &dyn Dynamics,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    order: u32,
    ctx: &mut Ctx,
) -> Result<f64, SolveError> {
    let n = y0.len();
    let mut f0 = vec![0.0; n];
    ctx.derivative(p, t0, y0, &mut f0)?;
    let zero = vec![0.0; n];
    let d0 = ctx.norm(y0, y0, &zero);
    let d1 = ctx.norm(&f0, y0, &zero);
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    let y1: Vec<f64> = y0.iter().zip(&f0).map(|(y, f)| y + h0 * f).collect();
    let mut f1 = vec![0.0; n];
    ctx.derivative(p, t0 + h0, &y1, &mut f1)?;
    let df: Vec<f64> = f1.iter().zip(&f0).map(|(a, b)| a - b).collect();
    let d2 = ctx.norm(&df, y0, &zero) / h0;
    let h1 = if d1.max(d2) <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d1.max(d2)).powf(1.0 / (order as f64 + 1.0))
    };
    Ok((100.0 * h0).min(h1).min(t_end - t0))
}

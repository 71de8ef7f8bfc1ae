//! The one stepping driver: output times, breakpoints, event location and step-size control,
//! the same for every [`Stepper`].

use std::time::Instant;

use super::dopri5::Dopri5;
use super::esdirk::Esdirk4;
use super::genalpha::GenAlphaStepper;
use super::stage_solver::Dirk;
use super::trbdf2::TrBdf2;
use super::{
    Attempt, Ctx, Dynamics, EventHit, EventSpec, Method, Observer, Options, Outcome, Problem,
    SolveError, Stats, Stepper, EVENT_TIME_TOL,
};

fn make_stepper(opts: &Options, n: usize) -> Box<dyn Stepper> {
    match opts.method {
        Method::Dopri5 => Box::new(Dopri5::new(n)),
        Method::TrBdf2 => Box::new(Dirk::new(TrBdf2::new(n), n)),
        Method::Esdirk4 => Box::new(Dirk::new(Esdirk4::new(n), n)),
        Method::GenAlpha => Box::new(GenAlphaStepper::new(opts.rho_inf, n)),
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
    let dynamics: &dyn Dynamics = p;
    let clock = Instant::now();
    let n = p.dim();
    let mut ctx = Ctx {
        rtol: opts.rtol,
        atol: opts.atol,
        stats: Stats::default(),
        mass_lu: None,
        groups: p.norm_groups(),
    };
    let mut stepper = make_stepper(opts, n);
    let specs = p.events();
    let mut t = t0;
    let mut y = y0.to_vec();
    let mut next_out = outputs.partition_point(|&o| o < t0);
    let mut events = Vec::new();
    let finish = |t: f64, y: Vec<f64>, mut ctx: Ctx, stopped_by, events| {
        ctx.stats.wall_s = clock.elapsed().as_secs_f64();
        Ok(Outcome {
            t,
            y,
            stats: ctx.stats,
            stopped_by,
            events,
        })
    };

    let mut g: Vec<f64> = (0..specs.len()).map(|i| p.event(i, t, &y)).collect();
    while next_out < outputs.len() && outputs[next_out] <= t0 {
        observer.output(t0, &y);
        next_out += 1;
    }
    if let Some(i) = (0..specs.len()).find(|&i| specs[i].terminal && g[i] < 0.0) {
        let hit = EventHit {
            reason: specs[i].reason,
            t,
        };
        return finish(t, y, ctx, Some(hit), events);
    }

    let breaks = breakpoints_within(p.breakpoints(), t0, t_end);
    let segment_end = |t: f64| breaks.iter().copied().find(|&b| b > t).unwrap_or(t_end);
    p.enter_segment(t0, segment_end(t0));
    stepper.start(dynamics, t0, y0, &mut ctx)?;
    let mut h = match opts.fixed_step {
        Some(h) => h,
        None => stepper.initial_step(dynamics, t0, y0, t_end, &mut ctx)?,
    };
    let h_min = 1e-14 * t0.abs().max(t_end.abs()).max(1.0);
    let mut y_tmp = vec![0.0; n];
    let mut just_rejected = false;

    while t < t_end {
        if ctx.stats.steps >= opts.max_steps {
            return Err(SolveError::TooManySteps {
                t,
                steps: ctx.stats.steps,
            });
        }
        if opts.fixed_step.is_none() {
            h = h.min(p.max_step(t, &y));
        }
        // Steps end exactly on the next breakpoint (or the end), and restart there.
        let target = breaks
            .iter()
            .copied()
            .find(|&b| b > t + h_min)
            .unwrap_or(t_end);
        let last = t + h >= target - h_min;
        let h_try = if last { target - t } else { h };
        let attempt = stepper.attempt(dynamics, t, &y, h_try, &mut ctx)?;
        let err = match attempt {
            Attempt::Done { err } => err,
            Attempt::NewtonFailed => {
                if opts.fixed_step.is_some() {
                    return Err(SolveError::NewtonFailed { t });
                }
                ctx.stats.rejected += 1;
                h = h_try * 0.25;
                if h < h_min {
                    return Err(SolveError::NewtonFailed { t });
                }
                continue;
            }
        };
        if !err.is_finite() && opts.fixed_step.is_some() {
            return Err(SolveError::NonFinite { t });
        }
        let q = stepper.error_order() as f64;
        if opts.fixed_step.is_none() && !(err <= 1.0) {
            ctx.stats.rejected += 1;
            just_rejected = true;
            let factor = if err.is_finite() {
                (0.9 * err.powf(-1.0 / (q + 1.0))).clamp(0.2, 1.0)
            } else {
                0.2
            };
            h = h_try * factor;
            if h < h_min {
                return Err(SolveError::StepSizeUnderflow { t, h });
            }
            continue;
        }
        if stepper.y_new().iter().any(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite { t: t + h_try });
        }
        let t_new = if last { target } else { t + h_try };
        stepper.accept(t_new);
        ctx.stats.steps += 1;

        // Earliest sign change from ≥ 0 to < 0 in this step, located on the dense output.
        let g_new: Vec<f64> = (0..specs.len())
            .map(|i| p.event(i, t_new, stepper.y_new()))
            .collect();
        let first = crossings(specs, &g, &g_new, t, t_new, &mut events, |i, tt| {
            stepper.interpolate(tt, &mut y_tmp);
            p.event(i, tt, &y_tmp)
        });
        let t_stop = first.map_or(t_new, |(_, te)| te);
        while next_out < outputs.len() && outputs[next_out] <= t_stop {
            stepper.interpolate(outputs[next_out], &mut y_tmp);
            observer.output(outputs[next_out], &y_tmp);
            next_out += 1;
        }
        if let Some((i, te)) = first {
            stepper.interpolate(te, &mut y_tmp);
            observer.step(te, &y_tmp);
            let hit = EventHit {
                reason: specs[i].reason,
                t: te,
            };
            return finish(te, y_tmp, ctx, Some(hit), events);
        }
        t = t_new;
        y.copy_from_slice(stepper.y_new());
        if last && target < t_end {
            p.enter_segment(t, segment_end(t));
            stepper.start(dynamics, t, &y, &mut ctx)?;
        }
        g = g_new;
        observer.step(t, &y);
        if opts.fixed_step.is_none() {
            // No growth straight after a rejection (Hairer & Wanner II.4).
            let grow = if just_rejected {
                1.0
            } else {
                stepper.max_growth()
            };
            let factor = (0.9 * err.max(1e-10).powf(-1.0 / (q + 1.0))).clamp(0.2, grow);
            h = stepper.keep_step(h_try, h_try * factor);
            just_rejected = false;
        }
    }
    finish(t, y, ctx, None, events)
}

/// The breakpoints strictly inside (t0, t_end), ascending.
fn breakpoints_within(mut breaks: Vec<f64>, t0: f64, t_end: f64) -> Vec<f64> {
    breaks.retain(|&b| b > t0 && b < t_end);
    breaks.sort_by(f64::total_cmp);
    breaks
}

/// The events of one step [t0, t1] whose g passes from ≥ 0 (g0) to < 0 (g1), each located on
/// `g_at(index, t)`: non-terminal ones are recorded in `events`, and the earliest terminal one
/// is returned.
fn crossings<E: Copy>(
    specs: &[EventSpec<E>],
    g0: &[f64],
    g1: &[f64],
    t0: f64,
    t1: f64,
    events: &mut Vec<EventHit<E>>,
    mut g_at: impl FnMut(usize, f64) -> f64,
) -> Option<(usize, f64)> {
    let mut first: Option<(usize, f64)> = None;
    for i in 0..specs.len() {
        if !(g0[i] >= 0.0 && g1[i] < 0.0) {
            continue;
        }
        let te = locate(|tt| g_at(i, tt), t0, g0[i], t1, g1[i]);
        if specs[i].terminal {
            if first.is_none_or(|(_, tf)| te < tf) {
                first = Some((i, te));
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
fn locate(mut g: impl FnMut(f64) -> f64, mut a: f64, mut ga: f64, mut b: f64, mut gb: f64) -> f64 {
    if ga == 0.0 {
        return a;
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
    // The first time known to be past the crossing: the event has happened by then.
    b
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

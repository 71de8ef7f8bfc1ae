//! A run of a disk on a rigid curve, driven through the disk's life at its track
//! (`disk::life`): it rolls (integrated) until the normal force falls to zero, then lifts;
//! where the scene lets it fly, the flight in closed form and the landing that ends it
//! (`rolling/flight.rs`) hand it back to rolling, or the run stops.

use super::extremes::{Range, Turning, Watch};
use super::{EnergyCheck, FlightRecord, Overrides, Progress, RunHeader, Stop, MAX_FLIGHTS};
use crate::disk::flight::{self as free, Flight};
use crate::disk::life::{self, Next};
use crate::disk::{ContactLoss, DiskObservation, StopReason};
use crate::error::Error;
use crate::ode::{self, Observer};
use crate::rolling::flight::{self, FlightEnd};
use crate::rolling::minimal::Minimal;
use crate::rolling::thesis::Thesis;
use crate::rolling::{Rolling, RollingModel};
use crate::scene::{Formulation, RollingScene, Scene};

#[derive(Clone, Copy, Debug)]
pub struct Row {
    pub t: f64,
    pub disk: DiskObservation,
    /// Distance from the centre to the track minus the radius: 0 while the disk rolls.
    pub gap: f64,
    /// Kinetic energy the landings so far have taken (J).
    pub impact: f64,
}

impl Row {
    /// The energy that stays constant: the disk's, plus what the landings took.
    pub fn energy(&self) -> f64 {
        self.disk.kinetic + self.disk.potential + self.impact
    }
}

pub struct RollingRun {
    pub header: RunHeader,
    pub setup: RollingScene,
    pub rows: Vec<Row>,
    pub last: Row,
    pub flights: Vec<FlightRecord>,
    /// The extremes of rn, rt and the friction rolling needs, located on the solution.
    pub contact: [Range; 3],
}

pub fn model(setup: &RollingScene) -> Box<dyn RollingModel> {
    match setup.formulation {
        Formulation::Minimal => Box::new(Minimal {
            rolling: setup.rolling.clone(),
        }),
        Formulation::Thesis => Box::new(Thesis {
            rolling: setup.rolling.clone(),
        }),
    }
}

fn energy_of(d: &DiskObservation, impact: f64) -> (f64, f64) {
    (
        d.kinetic + d.potential + impact,
        d.kinetic.abs() + d.potential.abs() + impact,
    )
}

/// The run's observer: rows at the output times and the energy check at every step, with
/// what the landings took added, whether the disk rolls or flies.
struct Recorder<'a> {
    model: &'a dyn RollingModel,
    rows: Vec<Row>,
    energy: EnergyCheck,
    progress: Option<Progress>,
    impact: f64,
    /// The contact force and the friction it needs ([`contact_quantities`]), watched for
    /// their extremes on the solution.
    watch: Watch,
    /// Those quantities at the end of the last step watched.
    last: Option<(f64, Vec<f64>)>,
    /// Where the track's curvature has a kink ([`crate::curve::Curve::curvature_kinks`]).
    kinks: &'a [f64],
}

/// What the summary reports the extremes of: rn, rt and the friction coefficient rolling
/// needs (NaN where the disk does not press on the track).
fn contact_quantities(d: &DiskObservation) -> Vec<f64> {
    vec![d.rn, d.rt, d.mu_needed().unwrap_or(f64::NAN)]
}

impl<'a> Recorder<'a> {
    fn new(
        model: &'a dyn RollingModel,
        kinks: &'a [f64],
        first: &DiskObservation,
        outputs: usize,
        scene: &Scene,
        show_progress: bool,
    ) -> Self {
        let (total, scale) = energy_of(first, 0.0);
        Recorder {
            model,
            rows: Vec::with_capacity(outputs + 1),
            energy: EnergyCheck::new(total, scale),
            progress: if show_progress {
                Progress::new(scene.duration)
            } else {
                None
            },
            impact: 0.0,
            watch: Watch::new(3, Turning::OnTheSolution),
            last: None,
            kinks,
        }
    }

    fn record(&mut self, row: Row) {
        let (total, scale) = energy_of(&row.disk, row.impact);
        self.energy.record(total, scale);
        self.watch
            .record_point(row.t, &contact_quantities(&row.disk));
        self.rows.push(row);
    }
}

impl Observer for Recorder<'_> {
    fn output(&mut self, t: f64, y: &[f64]) {
        let disk = self.model.observe(t, y);
        let impact = self.impact;
        self.record(Row {
            t,
            disk,
            gap: 0.0,
            impact,
        });
    }

    fn span(&mut self, t0: f64, t1: f64, dense: &dyn ode::Dense) {
        if !(t1 > t0) {
            return;
        }
        let model = self.model;
        let at = |t: f64| contact_quantities(&model.observe(t, &dense.at(t)));
        let mut start = match self.last.take() {
            Some((t, v)) if t == t0 => v,
            _ => at(t0),
        };
        // The contact force has a kink where the contact point crosses a kink of the
        // curvature; a parabola fitted across it finds no turning point there, so the step is
        // watched in pieces that end at each crossing.
        let s_at = |t: f64| model.observe(t, &dense.at(t)).s;
        let mut a = t0;
        for b in kink_crossings(self.kinks, t0, t1, s_at)
            .into_iter()
            .chain([t1])
        {
            let m = 0.5 * (a + b);
            let (middle, end) = (at(m), at(b));
            self.watch
                .record_step([a, m, b], [&start, &middle, &end], at);
            (a, start) = (b, end);
        }
        self.last = Some((t1, start));
    }

    fn step(&mut self, t: f64, y: &[f64]) {
        let disk = self.model.observe(t, y);
        let (total, scale) = energy_of(&disk, self.impact);
        self.energy.record(total, scale);
        if let Some(p) = &mut self.progress {
            p.update(t);
        }
    }
}

/// The times inside (t0, t1) where the contact parameter `s_at` crosses one of `kinks`
/// (ascending), each to 1e-12 of the step by bisection; a knot crossed twice within one step
/// is not seen, which needs the disk to turn back within a step.
fn kink_crossings(kinks: &[f64], t0: f64, t1: f64, s_at: impl Fn(f64) -> f64) -> Vec<f64> {
    if kinks.is_empty() {
        return Vec::new();
    }
    let (s0, s1) = (s_at(t0), s_at(t1));
    let (lo, hi) = (s0.min(s1), s0.max(s1));
    let from = kinks.partition_point(|&k| k <= lo);
    let to = kinks.partition_point(|&k| k < hi);
    let mut times: Vec<f64> = kinks[from..to]
        .iter()
        .map(|&knot| {
            let on_start_side = |t: f64| (s_at(t) < knot) == (s0 < knot);
            let (mut a, mut b) = (t0, t1);
            while b - a > 1e-12 * (t1 - t0) {
                let m = 0.5 * (a + b);
                // On a short step late in a run 1e-12 of the step is below the times'
                // spacing: a and b end up neighbours, whose midpoint is one of them.
                if m <= a || m >= b {
                    break;
                }
                if on_start_side(m) {
                    a = m;
                } else {
                    b = m;
                }
            }
            0.5 * (a + b)
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times
}

/// A bounce lower than this share of the radius is not flown: the gap is resolved to about
/// 1e-10 of the radius, so such a flight could not be told from rolling. The bounces left
/// (heights e² times smaller each) are summed in closed form instead, as on a flat track under
/// the normal gravity there: they last τ / (1 − e) in all, τ = 2 vₙ / gₙ the first's flight
/// time, the disk sliding along at its speed in the meantime, and the normal speed they carry
/// is what they take.
const RESOLVED_BOUNCE: f64 = 1e-8;

/// Where the run ends: at t, for `stop`, the disk last seen as `last`.
struct Ended {
    t: f64,
    stop: Stop,
    last: Row,
}

/// A disk leaving the curve on `flight`, from `from`: the track's nearest point, the disk's
/// rotation relative to it, and the tangent's angle there.
struct Launch {
    flight: Flight,
    from: (f64, f64, f64),
}

/// A flight back on the curve at t, touching at s, the disk as it came down (`before`)
/// spinning at `omega`.
struct Touch {
    t: f64,
    s: f64,
    before: Row,
    omega: f64,
}

pub fn run(
    scene: &Scene,
    setup: &RollingScene,
    over: &Overrides,
    show_progress: bool,
) -> Result<RollingRun, Error> {
    let clock = std::time::Instant::now();
    let model = model(setup);
    let y0 = model.initial_state();
    let opts = over.options(scene);
    let outputs = super::output_times(scene);
    let first = model.observe(0.0, &y0);
    let mut curve = Curve {
        scene,
        setup,
        model: model.as_ref(),
        opts: &opts,
        outputs: &outputs,
        rec: Recorder::new(
            model.as_ref(),
            setup.rolling.curve.curvature_kinks(),
            &first,
            outputs.len(),
            scene,
            show_progress,
        ),
        stats: ode::Stats::default(),
        flights: Vec::new(),
    };
    // A disk launched faster than the track can hold it (the normal force negative from the
    // start) leaves the track at once.
    let start = if first.rn < 0.0 {
        let start = Row {
            t: 0.0,
            disk: first,
            gap: 0.0,
            impact: 0.0,
        };
        curve.rec.record(start);
        curve.lifts(start)
    } else {
        Next::Rolls((0.0, y0.clone()))
    };
    let Ended {
        t: t_end,
        stop,
        last,
    } = life::live(&mut curve, start)?;
    let Curve {
        mut rec,
        mut stats,
        flights,
        ..
    } = curve;
    if let Some(p) = &rec.progress {
        p.finish();
    }
    if rec.rows.last().is_none_or(|r| r.t < t_end) {
        rec.record(last);
    }
    stats.wall_s = clock.elapsed().as_secs_f64();
    Ok(RollingRun {
        header: RunHeader {
            scene: scene.clone(),
            method: opts.method,
            rtol: opts.rtol,
            atol: opts.atol,
            unknowns: y0.len(),
            stop,
            t_end,
            stats,
            energy: rec.energy,
        },
        setup: setup.clone(),
        rows: rec.rows,
        last,
        flights,
        contact: [
            rec.watch.ranges[0],
            rec.watch.ranges[1],
            rec.watch.ranges[2],
        ],
    })
}

/// The rigid curve as a disk's life meets it: what its phases need of the run, and what
/// they record.
struct Curve<'a> {
    scene: &'a Scene,
    setup: &'a RollingScene,
    model: &'a dyn RollingModel,
    opts: &'a ode::Options,
    outputs: &'a [f64],
    rec: Recorder<'a>,
    stats: ode::Stats,
    flights: Vec<FlightRecord>,
}

impl Curve<'_> {
    /// The disk loses contact at `lift` (the row where the normal force fell to zero): it
    /// flies where the scene lets it, and the run stops there otherwise.
    fn lifts(&self, lift: Row) -> Next<Self> {
        let r = &self.setup.rolling;
        if !matches!(r.contact_loss, ContactLoss::Fly { .. }) {
            return Next::Ends(Ended {
                t: lift.t,
                stop: Stop::Event(StopReason::ContactLost),
                last: lift,
            });
        }
        let d = lift.disk;
        Next::Flies(Launch {
            flight: Flight {
                t0: lift.t,
                centre: [d.x, d.y],
                velocity: [d.vx, d.vy],
                omega: d.omega,
                gravity: r.gravity,
            },
            from: (d.s, d.phi, tangent_angle(r, d.s)),
        })
    }

    fn restitution(&self) -> f64 {
        match self.setup.rolling.contact_loss {
            ContactLoss::Fly { restitution } => restitution,
            ContactLoss::Stop => 0.0,
        }
    }
}

impl life::Track for Curve<'_> {
    type Rolling = (f64, Vec<f64>);
    type Launch = Launch;
    type Touch = Touch;
    type End = Ended;

    /// Roll from (t, y) until the run's end, a stopping event, or the normal force falling
    /// to zero (the disk lifts).
    fn roll(&mut self, (t, y): (f64, Vec<f64>)) -> Result<Next<Self>, Error> {
        // Rows at the output times after this phase's start (and at t = 0 for the first).
        let ahead: Vec<f64> = self
            .outputs
            .iter()
            .copied()
            .filter(|&o| o > t || (t == 0.0 && o == 0.0))
            .collect();
        let scene = self.scene;
        let out = ode::solve(
            self.model,
            t,
            &y,
            scene.duration,
            &ahead,
            self.opts,
            &mut self.rec,
        )
        .map_err(|e| Error::Solver(format!("scene {}: the solver failed: {e}", scene.name)))?;
        self.stats.add(&out.stats);
        let last = Row {
            t: out.t,
            disk: self.model.observe(out.t, &out.y),
            gap: 0.0,
            impact: self.rec.impact,
        };
        let stop = match out.stopped_by {
            None => Stop::End,
            Some(hit) if hit.reason == StopReason::ContactLost => return Ok(self.lifts(last)),
            Some(hit) => Stop::Event(hit.reason),
        };
        Ok(Next::Ends(Ended {
            t: out.t,
            stop,
            last,
        }))
    }

    /// One flight, recorded in `flights` with its rows at the output times, until it lands,
    /// leaves the track or the run ends.
    fn fly(&mut self, launch: Launch) -> Result<Next<Self>, Error> {
        let (scene, r) = (self.scene, &self.setup.rolling);
        let Launch { flight, from } = launch;
        if self.flights.len() >= MAX_FLIGHTS {
            return Err(Error::Solver(format!(
                "scene {}: the disk lifted off {MAX_FLIGHTS} times by t = {:.6} s; it cannot stay on this track at this speed, and the run stops rather than count more flights",
                scene.name, flight.t0
            )));
        }
        let (end, max_gap) = flight::land(r, &flight, from.0, scene.duration);
        self.flights.push(FlightRecord {
            disk: 0,
            lift_off_t: flight.t0,
            lift_off_s: from.0,
            land_t: None,
            land_s: None,
            max_gap,
            energy_lost: None,
        });
        let t_stop = match end {
            FlightEnd::Lands { t, .. } | FlightEnd::LeavesTrack { t, .. } => t,
            FlightEnd::Airborne => scene.duration,
        };
        let rec = &mut self.rec;
        let observe =
            |t: f64, s_guess: f64, impact: f64| flying(r, &flight, from, t, s_guess, impact);
        let mut s_guess = from.0;
        for &o in self
            .outputs
            .iter()
            .filter(|&&o| o > flight.t0 && o <= t_stop)
        {
            let row = observe(o, s_guess, rec.impact);
            s_guess = row.disk.s;
            rec.record(row);
        }
        Ok(match end {
            FlightEnd::Airborne => Next::Ends(Ended {
                t: t_stop,
                stop: Stop::End,
                last: observe(t_stop, s_guess, rec.impact),
            }),
            FlightEnd::LeavesTrack { t, .. } => Next::Ends(Ended {
                t,
                stop: Stop::Event(StopReason::LeftTrack),
                last: observe(t, s_guess, rec.impact),
            }),
            FlightEnd::Lands { t, s } => Next::Touches(Touch {
                t,
                s,
                before: observe(t, s, rec.impact),
                omega: flight.omega,
            }),
        })
    }

    /// The impact where a flight meets the curve: a bounce high enough to resolve flies; a
    /// lower one settles in closed form; then the disk rolls on, unless the track falls away
    /// faster than it can follow there, in which case it lifts off at once.
    fn land(&mut self, touch: Touch) -> Result<Next<Self>, Error> {
        let r = &self.setup.rolling;
        let restitution = self.restitution();
        let Touch {
            t,
            s,
            before,
            omega,
        } = touch;
        let p = r.curve.at(s);
        let impact = impact_at(
            r,
            &mut self.rec,
            &mut self.flights,
            (t, s),
            &before,
            omega,
            restitution,
        );
        let Some(hit) = impact else {
            return Ok(Next::Ends(Ended {
                t,
                stop: Stop::Event(StopReason::Slip),
                last: before,
            }));
        };
        // What of gravity presses the disk onto the track there.
        let gravity_n = r.gravity * p.normal()[1];
        let height = if gravity_n > 0.0 {
            hit.vn * hit.vn / (2.0 * gravity_n)
        } else {
            f64::INFINITY
        };
        let t_dir = p.tangent();
        let vt = hit.velocity[0] * t_dir[0] + hit.velocity[1] * t_dir[1];
        let from = (s, before.disk.phi, tangent_angle(r, s));
        if hit.vn > 0.0 && height >= RESOLVED_BOUNCE * r.disk.radius {
            return Ok(Next::Flies(Launch {
                flight: Flight {
                    t0: t,
                    centre: [before.disk.x, before.disk.y],
                    velocity: hit.velocity,
                    omega: hit.omega,
                    gravity: r.gravity,
                },
                from,
            }));
        }
        let (mut t, mut s, mut phi) = (t, s, before.disk.phi);
        if hit.vn > 0.0 && restitution < 1.0 {
            let low = LowBounces {
                t,
                s,
                vt,
                vn: hit.vn,
                omega: hit.omega,
                height,
                gravity_n,
                restitution,
            };
            match self.settle(&before, from, &low) {
                Settles::At(end) => (t, s, phi) = (end.t, end.disk.s, end.disk.phi),
                Settles::AfterTheEnd(last) => {
                    return Ok(Next::Ends(Ended {
                        t: self.scene.duration,
                        stop: Stop::End,
                        last,
                    }))
                }
            }
        }
        let y = self.model.state_at(s, vt, phi);
        let rolling = self.model.observe(t, &y);
        if rolling.rn > 0.0 {
            return Ok(Next::Rolls((t, y)));
        }
        Ok(Next::Flies(Launch {
            flight: Flight {
                t0: t,
                centre: [rolling.x, rolling.y],
                velocity: [rolling.vx, rolling.vy],
                omega: rolling.omega,
                gravity: r.gravity,
            },
            from: (s, phi, tangent_angle(r, s)),
        }))
    }
}

/// The impact where the last flight meets the curve at (t, s), `before` the disk just before
/// it: booked on the flight's record and in the energy the landings took; none where friction
/// cannot hold the tangential impulse, which stops the run.
fn impact_at(
    r: &Rolling,
    rec: &mut Recorder,
    flights: &mut [FlightRecord],
    (t, s): (f64, f64),
    before: &Row,
    omega: f64,
    restitution: f64,
) -> Option<free::Impact> {
    let p = r.curve.at(s);
    let hit = free::impact(
        &r.disk,
        [p.tangent(), p.normal()],
        [before.disk.vx, before.disk.vy],
        omega,
        restitution,
    );
    let record = flights.last_mut().expect("pushed by the flight");
    record.land_t = Some(t);
    record.land_s = Some(s);
    if r.mu.is_some_and(|mu| hit.jt.abs() > mu * hit.jn) {
        return None;
    }
    record.energy_lost = Some(hit.energy_lost);
    rec.impact += hit.energy_lost;
    Some(hit)
}

/// A landing at (t, s) that throws the disk off again lower than [`RESOLVED_BOUNCE`]: its
/// speed along the track and away from it, its spin, how high it would rise, what of gravity
/// presses it on, and the restitution.
struct LowBounces {
    t: f64,
    s: f64,
    vt: f64,
    vn: f64,
    omega: f64,
    height: f64,
    gravity_n: f64,
    restitution: f64,
}

/// Where low bounces leave the disk: settled, or still bouncing at the run's end.
enum Settles {
    At(Row),
    AfterTheEnd(Row),
}

impl Curve<'_> {
    /// The bounces too low to fly, summed: the disk glides on at its tangential speed until
    /// they have died out, 2 vₙ / (g (1 − e)) later, having lost its normal kinetic energy;
    /// recorded as one flight. The disk where it settles, or where the run ends before it does.
    fn settle(&mut self, before: &Row, from: (f64, f64, f64), b: &LowBounces) -> Settles {
        let (scene, r, rec) = (self.scene, &self.setup.rolling, &mut self.rec);
        let settled = b.t + 2.0 * b.vn / b.gravity_n / (1.0 - b.restitution);
        let t_dir = r.curve.at(b.s).tangent();
        let glide = Flight {
            t0: b.t,
            centre: [before.disk.x, before.disk.y],
            velocity: [b.vt * t_dir[0], b.vt * t_dir[1]],
            omega: b.omega,
            gravity: 0.0,
        };
        let lost = 0.5 * r.disk.mass * b.vn * b.vn;
        let mut s_guess = b.s;
        for &o in self.outputs.iter().filter(|&&o| o > b.t && o <= settled) {
            let row = flying(r, &glide, from, o, s_guess, rec.impact + lost);
            s_guess = row.disk.s;
            rec.record(row);
        }
        rec.impact += lost;
        let end = flying(
            r,
            &glide,
            from,
            settled.min(scene.duration),
            s_guess,
            rec.impact,
        );
        self.flights.push(FlightRecord {
            disk: 0,
            lift_off_t: b.t,
            lift_off_s: b.s,
            land_t: (settled <= scene.duration).then_some(settled),
            land_s: (settled <= scene.duration).then_some(end.disk.s),
            max_gap: b.height,
            energy_lost: Some(lost),
        });
        if settled > scene.duration {
            return Settles::AfterTheEnd(end);
        }
        Settles::At(end)
    }
}

fn tangent_angle(r: &Rolling, s: f64) -> f64 {
    let t = r.curve.at(s).tangent();
    t[1].atan2(t[0])
}

/// The row of a flying disk at `t`: no contact force, the gap to the nearest track point, and
/// the rotation relative to that point's tangent, continued from the lift-off at `from`
/// (s, φ, tangent angle).
fn flying(
    r: &Rolling,
    flight: &Flight,
    from: (f64, f64, f64),
    t: f64,
    s_guess: f64,
    impact: f64,
) -> Row {
    let c = flight.centre(t);
    let v = flight.velocity(t);
    let near = flight::gap(r, c, s_guess);
    let turned = tangent_angle(r, near.s) - from.2;
    let turned = turned.sin().atan2(turned.cos());
    let m = r.disk.mass;
    let kinetic = 0.5 * m * (v[0] * v[0] + v[1] * v[1])
        + 0.5 * r.disk.inertia() * flight.omega * flight.omega;
    Row {
        t,
        disk: DiskObservation {
            s: near.s,
            x: c[0],
            y: c[1],
            vx: v[0],
            vy: v[1],
            omega: flight.omega,
            phi: from.1 + flight.omega * (t - flight.t0) - turned,
            rt: 0.0,
            rn: 0.0,
            kinetic,
            potential: m * r.gravity * c[1],
        },
        gap: near.gap.max(0.0),
        impact,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A knot crossed within a step of 10⁻⁴ s at t = 1.6 s (the jump scene at Ω₀ = −40 1/s
    /// took such a step over its crest's knot): 10⁻¹² of the step is below the spacing of
    /// doubles there, and a bisection to it never ended. The crossing is found to the
    /// neighbouring doubles instead.
    #[test]
    fn a_knot_crossed_late_in_a_short_step_is_found_to_the_last_digit() {
        let (t0, t1, knot) = (1.626_713_844_415_042, 1.626_842_271_154_175, 0.25);
        let crossing = t0 + 0.3 * (t1 - t0);
        let s_at = |t: f64| knot + (t - crossing);
        let times = kink_crossings(&[knot], t0, t1, s_at);
        assert_eq!(times.len(), 1);
        assert!((times[0] - crossing).abs() <= 4.0 * f64::EPSILON * crossing);
    }
}

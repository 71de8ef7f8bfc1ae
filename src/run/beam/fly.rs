//! The disks' flights over the beam, as the beam's part of a disk's life (`disk::life`): a
//! lift-off, what rides on under the disk while it flies in closed form (the beam alone, or
//! the beam with the other disks rolling on it), and the landing (with its bounces) or its
//! leaving the beam. One disk flies at a time: another lifting off meanwhile stops the run.

use super::*;
use crate::coupling::landing::Bounce;
use flight::{BesideEvent, BesideFlight};

/// A disk leaving the beam: where and how it flies, over the state of what rides on.
pub(super) struct Launch {
    pub(super) t: f64,
    /// What rides on while it flies, (z, ż): the beam's unknowns alone, or with the contact
    /// coordinates of the disks rolling beside it (its own at rest).
    pub(super) q: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) flight: Flight,
    pub(super) s: f64,
    /// Which disk flies, and the (kinetic, potential) energy the budget holds for it while
    /// it flies.
    pub(super) disk: usize,
    pub(super) carried: (f64, f64),
}

/// Disk k lifts off at (t, y) of the coupled phase: it takes its energy with it into the
/// air, where the budget holds it constant. Where other disks roll on, it leaves their
/// equations and they ride on.
pub(super) fn lift_off(c: &DiskOnBeam, rec: &mut Recorder, t: f64, y: &[f64], k: usize) -> Launch {
    let n = c.loaded.dim();
    let (z, zd) = rec.phase.split(y);
    let d = c.observe_all(t, z, zd)[k].expect("the disk lifting off is on the beam");
    let beside = (0..c.count()).any(|j| j != k && !c.has_left(j));
    // The contact force falls to zero and stays there, a kink no parabola through samples
    // either side of it follows.
    rec.restart();
    let (q, v) = if beside {
        rec.ledger.one_disk_leaves(&rec.phase, t, y, k);
        let mut zd = zd.to_vec();
        c.leave(k, &mut zd);
        (z.to_vec(), zd)
    } else {
        rec.ledger.disk_leaves(&rec.phase, t, y);
        (z[..n].to_vec(), zd[..n].to_vec())
    };
    Launch {
        t,
        q,
        v,
        flight: Flight {
            t0: t,
            centre: [d.x, d.y],
            velocity: [d.vx, d.vy],
            omega: d.omega,
            gravity: c.spec_of(k).gravity,
        },
        s: d.s,
        disk: k,
        carried: (d.kinetic, d.potential),
    }
}

/// A bounce lower than this share of the radius is not flown: it ends as a plastic landing
/// (see the rigid curve's `RESOLVED_BOUNCE`).
pub(super) const RESOLVED_BOUNCE: f64 = 1e-8;

/// A disk touching the beam at t, what rides on in (q, v) (as in [`Launch`]), after `flight`
/// launched at `launched`; `s` the beam's nearest point to where it flew.
pub(super) struct Touch {
    launched: f64,
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    flight: Flight,
    s: f64,
    disk: usize,
    carried: (f64, f64),
}

/// How one stretch of a flight beside rolling disks ended.
enum Beside<N> {
    /// The flight goes on from this state: a disk beside it left the beam.
    Goes((f64, Vec<f64>, Vec<f64>)),
    /// What follows: the riding is over, or the flying disk touches down or leaves.
    Then(N),
}

impl<'a> OnTheBeam<'a, '_> {
    /// One flight from `launch`: what rides on integrated under the disk in the air until it
    /// touches the beam, passes an end, or the run ends; recorded in `flights`.
    pub(super) fn fly_once(&mut self, launch: Launch) -> Result<Next<Self>, Error> {
        let (scene, c) = (self.scene, self.c);
        if self.flights.len() >= MAX_FLIGHTS {
            return Err(Error::Solver(format!(
                "scene {}: {} lifted off the beam {MAX_FLIGHTS} times by t = {:.6} s; the run stops rather than count more flights",
                scene.name,
                if c.count() > 1 { "the disks" } else { "the disk" },
                launch.t
            )));
        }
        let disk = FlyingDisk {
            coupled: c,
            k: launch.disk,
            flight: launch.flight,
            s: std::cell::Cell::new(launch.s),
        };
        self.flights.push(FlightRecord {
            disk: launch.disk,
            lift_off_t: launch.t,
            lift_off_s: launch.s,
            land_t: None,
            land_s: None,
            max_gap: 0.0,
            energy_lost: None,
        });
        self.rec.watches.gap = Watch::new(1, Turning::OnTheSolution);
        if launch.q.len() > self.loaded.dim() {
            self.fly_beside(launch, disk)
        } else {
            self.fly_alone(launch, disk)
        }
    }

    /// The flight over the beam alone.
    fn fly_alone(&mut self, launch: Launch, disk: FlyingDisk<'a>) -> Result<Next<Self>, Error> {
        let (scene, c, loaded) = (self.scene, self.c, self.loaded);
        let ahead = self.ahead(launch.t);
        let rec = &mut *self.rec;
        rec.phase.free();
        rec.phase.flying = Some(disk.clone());
        rec.train_goes_on(launch.t, &[&launch.q[..], &launch.v[..]].concat());
        let beneath = BeneathFlight { loaded, disk };
        let out = integrate(
            &beneath,
            launch.t,
            &launch.q,
            &launch.v,
            scene.duration,
            &ahead,
            self.opts,
            rec,
        )
        .map_err(|e| solver_error(scene, self.opts.method, e))?;
        self.stats.add(&out.stats);
        self.note_gap();
        let k = launch.disk;
        let Some(hit) = out.stopped_by else {
            return Ok(self.stopped(out.t, out.y, Stop::End, Some(k)));
        };
        let (q, v) = out.y.split_at(loaded.dim());
        if hit.reason == FlightEvent::PassesEnd {
            self.rec.phase.flying = None;
            self.left[k] = Some(out.t);
            return Ok(self.left_beam(out.t, q.to_vec(), v.to_vec()));
        }
        let flight = beneath.disk.flight;
        let s = c.gap(k, q, flight.centre(out.t), beneath.disk.s.get()).s;
        Ok(Next::Touches(Touch {
            launched: launch.t,
            t: out.t,
            q: q.to_vec(),
            v: v.to_vec(),
            flight,
            s,
            disk: k,
            carried: launch.carried,
        }))
    }

    /// The flight beside disks rolling on the beam: their coupled phase, watched for the
    /// flying disk as well, stretch by stretch until it touches down or leaves, or one of
    /// them stops the run (another lifting off among them: one flies at a time).
    fn fly_beside(&mut self, launch: Launch, disk: FlyingDisk<'a>) -> Result<Next<Self>, Error> {
        let c = self.c;
        self.rec.phase.flying = Some(disk.clone());
        let y: Vec<f64> = launch.q.iter().chain(&launch.v).copied().collect();
        self.rec.ledger.restart(&self.rec.phase, launch.t, &y);
        let problem = BesideFlight::new(c, disk);
        let mut from = (launch.t, launch.q.clone(), launch.v.clone());
        loop {
            match self.beside_stretch(&problem, &launch, from)? {
                Beside::Goes(state) => from = state,
                Beside::Then(next) => return Ok(next),
            }
        }
    }

    /// One stretch of a flight beside rolling disks, from `from` to the next event or a
    /// prescribed disk's exit.
    fn beside_stretch(
        &mut self,
        problem: &BesideFlight<'a>,
        launch: &Launch,
        (t0, z0, zd0): (f64, Vec<f64>, Vec<f64>),
    ) -> Result<Beside<Next<Self>>, Error> {
        let (scene, c) = (self.scene, self.c);
        let k = launch.disk;
        let until = c
            .next_exit()
            .map_or(scene.duration, |(te, _)| te.min(scene.duration));
        let ahead = self.ahead(t0);
        let out = integrate(problem, t0, &z0, &zd0, until, &ahead, self.opts, self.rec)
            .map_err(|e| solver_error(scene, self.opts.method, e))?;
        self.stats.add(&out.stats);
        self.note_gap();
        let (t, y) = (out.t, out.y);
        let reason = match out.stopped_by {
            None if t < scene.duration => {
                let j = leaving(c, t);
                self.left[j] = Some(t);
                return Ok(Beside::Goes(one_leaves(c, j, self.rec, t, y)));
            }
            None => return Ok(Beside::Then(self.stopped(t, y, Stop::End, Some(k)))),
            Some(hit) => hit.reason,
        };
        match reason {
            BesideEvent::Rolling(DiskEvent::Disk {
                disk: j,
                reason: StopReason::LeftTrack,
            }) => {
                self.left[j] = Some(t);
                Ok(Beside::Goes(one_leaves(c, j, self.rec, t, y)))
            }
            BesideEvent::Rolling(DiskEvent::Disk { disk, reason }) => Ok(Beside::Then(
                self.stopped(t, y, Stop::Event(reason), Some(disk)),
            )),
            BesideEvent::Rolling(DiskEvent::Wheel(_)) => {
                unreachable!("a disk beside vehicles stops where it would fly")
            }
            BesideEvent::Flight(FlightEvent::PassesEnd) => {
                self.rec.phase.flying = None;
                self.left[k] = Some(t);
                let (z, zd) = self.rec.phase.split(&y);
                let (z, zd) = (z.to_vec(), zd.to_vec());
                if c.all_left() {
                    // The others left the beam while it flew: the beam vibrates alone.
                    self.rec.ledger.disk_leaves(&self.rec.phase, t, &y);
                    let n = self.loaded.dim();
                    return Ok(Beside::Then(self.left_beam(
                        t,
                        z[..n].to_vec(),
                        zd[..n].to_vec(),
                    )));
                }
                self.rec.ledger.restart(&self.rec.phase, t, &y);
                Ok(Beside::Then(Next::Rolls(Some((t, z, zd)))))
            }
            BesideEvent::Flight(FlightEvent::Lands) => {
                let (z, zd) = self.rec.phase.split(&y);
                let n = self.loaded.dim();
                let flight = problem.disk.flight;
                let s = c.gap(k, &z[..n], flight.centre(t), problem.disk.s.get()).s;
                Ok(Beside::Then(Next::Touches(Touch {
                    launched: launch.t,
                    t,
                    q: z.to_vec(),
                    v: zd.to_vec(),
                    flight,
                    s,
                    disk: k,
                    carried: launch.carried,
                })))
            }
        }
    }

    /// The output times after t.
    fn ahead(&self, t: f64) -> Vec<f64> {
        self.outputs.iter().copied().filter(|&o| o > t).collect()
    }

    /// The flight's largest gap so far, into its record.
    fn note_gap(&mut self) {
        let record = self.flights.last_mut().expect("pushed by the flight");
        record.max_gap = record
            .max_gap
            .max(self.rec.watches.gap.ranges[0].max.max(0.0));
    }

    /// A disk touches the beam (`touch`): it lands plastically, or bounces off where the
    /// restitution throws it high enough to resolve; then it rolls on, slips, or lifts off
    /// again.
    pub(super) fn touch_down(&mut self, touch: Touch) -> Result<Next<Self>, Error> {
        let (scene, c) = (self.scene, self.c);
        let Touch {
            launched,
            t,
            q,
            v,
            flight,
            s,
            disk: k,
            carried,
        } = touch;
        let restitution = match c.spec_of(k).contact_loss {
            ContactLoss::Fly { restitution } => restitution,
            ContactLoss::Stop => 0.0,
        };
        let beside = q.len() > self.loaded.dim();
        c.rejoin(k);
        let before = flight.velocity(t);
        let unsolved = || {
            Error::Solver(format!(
                "scene {}: the disk's landing on the beam at t = {t:.6} s could not be solved (the coupled mass matrix is singular there)",
                scene.name
            ))
        };
        let landing = c
            .land(k, t, (&q, &v), s, before, flight.omega)
            .ok_or_else(unsolved)?;
        let record = self.flights.last_mut().expect("pushed by the flight");
        record.land_t = Some(t);
        record.land_s = Some(s);
        // The landing's impulse jumps the state, and the contact force from zero: no parabola
        // through samples either side of it (joined across it, a 3 t disk hopping on D44's
        // section read its least contact force as −158.8 N).
        self.rec.restart();
        let bounce = if restitution > 0.0 {
            c.bounce(
                k,
                t,
                (&q, &v),
                s,
                before,
                flight.omega,
                restitution,
                &landing,
                self.rec.phase.mass_lu,
            )
        } else {
            None
        };
        let gravity_n = c.spec_of(k).gravity * c.contact_frame(k, t, &landing.z, &landing.zd)[1][1];
        if let Some(b) = bounce.filter(|b| {
            gravity_n <= 0.0
                || b.leaving * b.leaving / (2.0 * gravity_n)
                    >= RESOLVED_BOUNCE * c.spec_of(k).disk.radius
        }) {
            record.energy_lost = Some(b.energy_lost);
            return Ok(self.bounce_off((t, s, k, carried), q, &landing, before, b));
        }
        record.energy_lost = Some(landing.energy_lost);
        self.rec
            .ledger
            .disk_lands(landing.energy_lost, landing.axle_work, carried);
        self.rec.phase.couple(c);
        let after = c.observe_all(t, &landing.z, &landing.zd)[k].expect("landed on the beam");
        let y: Vec<f64> = landing.z.iter().chain(&landing.zd).copied().collect();
        if beside {
            self.rec.ledger.restart(&self.rec.phase, t, &y);
        } else {
            self.rec.train_goes_on(t, &y);
        }
        if slips(c, k, &landing, t, before, [after.vx, after.vy]) {
            return Ok(self.stopped(t, y, Stop::Event(StopReason::Slip), Some(k)));
        }
        // The disk rolls on from the landing, unless the beam falls away faster than it can
        // follow there, in which case it lifts off at once; but a disk that touches again the
        // instant it left, and then would have to be pulled to stay on, can neither roll nor
        // fly there, and the run stops at that contact loss.
        if after.rn > 0.0 {
            return Ok(Next::Rolls(Some((t, landing.z, landing.zd))));
        }
        if t <= launched + 1e-12 * (1.0 + t.abs()) {
            return Ok(self.stopped(t, y, Stop::Event(StopReason::ContactLost), Some(k)));
        }
        Ok(Next::Flies(lift_off(c, self.rec, t, &y, k)))
    }

    /// Disk k bouncing off the beam where it landed at (t, s) from `before` (its centre
    /// velocity), what rides on at `rest`, having carried `carried` into the air: it flies
    /// again, unless friction cannot hold the impulse.
    fn bounce_off(
        &mut self,
        (t, s, k, carried): (f64, f64, usize, (f64, f64)),
        rest: Vec<f64>,
        landing: &Landing,
        before: [f64; 2],
        b: Bounce,
    ) -> Next<Self> {
        let c = self.c;
        let after = c.observe_all(t, &landing.z, &landing.zd)[k].expect("landed on the beam");
        if slips(c, k, landing, t, before, b.velocity) {
            self.rec
                .ledger
                .disk_lands(landing.energy_lost, landing.axle_work, carried);
            self.rec.phase.couple(c);
            let y = landing.z.iter().chain(&landing.zd).copied().collect();
            return self.stopped(t, y, Stop::Event(StopReason::Slip), Some(k));
        }
        let spec = c.spec_of(k);
        let m = spec.disk.mass;
        let kinetic = 0.5 * m * (b.velocity[0].powi(2) + b.velocity[1].powi(2))
            + 0.5 * spec.disk.inertia() * b.omega * b.omega;
        let flies_with = (kinetic, after.potential);
        self.rec
            .ledger
            .disk_bounces(b.energy_lost, b.axle_work, carried, flies_with);
        let mut v = b.beam;
        let q = if rest.len() > self.loaded.dim() {
            c.leave(k, &mut v);
            landing.z.clone()
        } else {
            rest
        };
        Next::Flies(Launch {
            t,
            q,
            v,
            flight: Flight {
                t0: t,
                centre: [after.x, after.y],
                velocity: b.velocity,
                omega: b.omega,
                gravity: spec.gravity,
            },
            s,
            disk: k,
            carried: flies_with,
        })
    }
}

/// Whether the impulse that took disk k from `before` to `after` (centre velocities,
/// global) needs more friction than the scene's `mu`: |Jₜ| > mu Jₙ in the track's frame.
pub(super) fn slips(
    c: &DiskOnBeam,
    k: usize,
    landing: &Landing,
    t: f64,
    before: [f64; 2],
    after: [f64; 2],
) -> bool {
    let Some(mu) = c.spec_of(k).mu else {
        return false;
    };
    let [tg, nm] = c.contact_frame(k, t, &landing.z, &landing.zd);
    let m = c.spec_of(k).disk.mass;
    let dv = [after[0] - before[0], after[1] - before[1]];
    let jt = m * (dv[0] * tg[0] + dv[1] * tg[1]);
    let jn = m * (dv[0] * nm[0] + dv[1] * nm[1]);
    jt.abs() > mu * jn
}

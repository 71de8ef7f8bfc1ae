//! The disk's flights over the beam, as the beam's part of the disk's life (`disk::life`): its
//! lift-off, the beam alone under it while it flies in closed form, and the landing (with its
//! bounces) or its leaving the beam.

use super::*;
use crate::coupling::landing::Bounce;

/// A disk leaving the beam: where and how it flies, over the beam's state then.
pub(super) struct Launch {
    pub(super) t: f64,
    pub(super) q: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) flight: Flight,
    pub(super) s: f64,
}

/// The disk lifts off at (t, y) of the coupled phase: it takes its energy with it into the
/// air, where the budget holds it constant.
pub(super) fn lift_off(c: &DiskOnBeam, rec: &mut Recorder, t: f64, y: &[f64]) -> Launch {
    let n = c.loaded.dim();
    let (z, zd) = rec.phase.split(y);
    let d = c.observe(t, z, zd);
    let launch = Launch {
        t,
        q: z[..n].to_vec(),
        v: zd[..n].to_vec(),
        flight: Flight {
            t0: t,
            centre: [d.x, d.y],
            velocity: [d.vx, d.vy],
            omega: d.omega,
            gravity: c.spec().gravity,
        },
        s: d.s,
    };
    rec.ledger.disk_leaves(&rec.phase, t, y);
    launch
}

/// A bounce lower than this share of the radius is not flown: it ends as a plastic landing
/// (see the rigid curve's `RESOLVED_BOUNCE`).
pub(super) const RESOLVED_BOUNCE: f64 = 1e-8;

/// The disk touching the beam at t, the beam in (q, v), after `flight` launched at
/// `launched`; `s` the beam's nearest point to where it flew.
pub(super) struct Touch {
    launched: f64,
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    flight: Flight,
    s: f64,
}

impl<'a> OnTheBeam<'a, '_> {
    /// One flight from `launch`: the beam integrated alone under the disk in the air until it
    /// touches the beam, passes an end, or the run ends; recorded in `flights`.
    pub(super) fn fly_once(&mut self, launch: Launch) -> Result<Next<Self>, Error> {
        let (scene, c, loaded) = (self.scene, self.c, self.loaded);
        if self.flights.len() >= MAX_FLIGHTS {
            return Err(Error::Solver(format!(
                "scene {}: the disk lifted off the beam {MAX_FLIGHTS} times by t = {:.6} s; the run stops rather than count more flights",
                scene.name, launch.t
            )));
        }
        let disk = FlyingDisk {
            coupled: c,
            flight: launch.flight,
            s: std::cell::Cell::new(launch.s),
        };
        let rec = &mut *self.rec;
        rec.phase.free();
        rec.phase.flying = Some(disk.clone());
        rec.train_goes_on(launch.t, &[&launch.q[..], &launch.v[..]].concat());
        self.flights.push(FlightRecord {
            lift_off_t: launch.t,
            lift_off_s: launch.s,
            land_t: None,
            land_s: None,
            max_gap: 0.0,
            energy_lost: None,
        });
        rec.watches.gap = Watch::new(1, Turning::OnTheSolution);
        let beneath = BeneathFlight { loaded, disk };
        let ahead: Vec<f64> = self
            .outputs
            .iter()
            .copied()
            .filter(|&o| o > launch.t)
            .collect();
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
        .map_err(|e| solver_error(scene, e))?;
        self.stats.add(&out.stats);
        let record = self.flights.last_mut().expect("pushed above");
        record.max_gap = rec.watches.gap.ranges[0].max.max(0.0);
        let Some(hit) = out.stopped_by else {
            return Ok(self.stopped(out.t, out.y, Stop::End, Some(0)));
        };
        let (q, v) = out.y.split_at(loaded.dim());
        if hit.reason == FlightEvent::PassesEnd {
            rec.phase.flying = None;
            return Ok(self.left_beam(out.t, q.to_vec(), v.to_vec()));
        }
        let flight = beneath.disk.flight;
        let s = c.gap(q, flight.centre(out.t), beneath.disk.s.get()).s;
        Ok(Next::Touches(Touch {
            launched: launch.t,
            t: out.t,
            q: q.to_vec(),
            v: v.to_vec(),
            flight,
            s,
        }))
    }

    /// The disk touches the beam (`touch`): it lands plastically, or bounces off where the
    /// restitution throws it high enough to resolve; then it rolls on, slips, or lifts off
    /// again.
    pub(super) fn touch_down(&mut self, touch: Touch) -> Result<Next<Self>, Error> {
        let (scene, c) = (self.scene, self.c);
        let restitution = match c.spec().contact_loss {
            ContactLoss::Fly { restitution } => restitution,
            ContactLoss::Stop => 0.0,
        };
        let Touch {
            launched,
            t,
            q,
            v,
            flight,
            s,
        } = touch;
        let before = flight.velocity(t);
        let unsolved = || {
            Error::Solver(format!(
                "scene {}: the disk's landing on the beam at t = {t:.6} s could not be solved (the coupled mass matrix is singular there)",
                scene.name
            ))
        };
        let landing = c
            .land(t, &q, &v, s, before, flight.omega)
            .ok_or_else(unsolved)?;
        let record = self.flights.last_mut().expect("pushed by the flight");
        record.land_t = Some(t);
        record.land_s = Some(s);
        let bounce = if restitution > 0.0 {
            c.bounce(
                t,
                &q,
                &v,
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
        let gravity_n = c.spec().gravity * c.contact_frame(0, t, &landing.z, &landing.zd)[1][1];
        if let Some(b) = bounce.filter(|b| {
            gravity_n <= 0.0
                || b.leaving * b.leaving / (2.0 * gravity_n)
                    >= RESOLVED_BOUNCE * c.spec().disk.radius
        }) {
            record.energy_lost = Some(b.energy_lost);
            return Ok(self.bounce_off((t, s), q, &landing, before, b));
        }
        record.energy_lost = Some(landing.energy_lost);
        self.rec
            .ledger
            .disk_lands(landing.energy_lost, landing.axle_work);
        self.rec.phase.couple(c);
        let after = c.observe(t, &landing.z, &landing.zd);
        let y: Vec<f64> = landing.z.iter().chain(&landing.zd).copied().collect();
        self.rec.train_goes_on(t, &y);
        if slips(c, &landing, t, before, [after.vx, after.vy]) {
            return Ok(self.stopped(t, y, Stop::Event(StopReason::Slip), Some(0)));
        }
        // The disk rolls on from the landing, unless the beam falls away faster than it can
        // follow there, in which case it lifts off at once; but a disk that touches again the
        // instant it left, and then would have to be pulled to stay on, can neither roll nor
        // fly there, and the run stops at that contact loss.
        if after.rn > 0.0 {
            return Ok(Next::Rolls(Some((t, landing.z, landing.zd))));
        }
        if t <= launched + 1e-12 * (1.0 + t.abs()) {
            return Ok(self.stopped(t, y, Stop::Event(StopReason::ContactLost), Some(0)));
        }
        Ok(Next::Flies(lift_off(c, self.rec, t, &y)))
    }

    /// The disk bouncing off the beam where it landed at (t, s) from `before` (its centre
    /// velocity) with the beam at q: it flies again, unless friction cannot hold the impulse.
    fn bounce_off(
        &mut self,
        (t, s): (f64, f64),
        q: Vec<f64>,
        landing: &Landing,
        before: [f64; 2],
        b: Bounce,
    ) -> Next<Self> {
        let c = self.c;
        let after = c.observe(t, &landing.z, &landing.zd);
        if slips(c, landing, t, before, b.velocity) {
            self.rec
                .ledger
                .disk_lands(landing.energy_lost, landing.axle_work);
            self.rec.phase.couple(c);
            let y = landing.z.iter().chain(&landing.zd).copied().collect();
            return self.stopped(t, y, Stop::Event(StopReason::Slip), Some(0));
        }
        let m = c.spec().disk.mass;
        let kinetic = 0.5 * m * (b.velocity[0].powi(2) + b.velocity[1].powi(2))
            + 0.5 * c.spec().disk.inertia() * b.omega * b.omega;
        self.rec
            .ledger
            .disk_bounces(b.energy_lost, b.axle_work, (kinetic, after.potential));
        Next::Flies(Launch {
            t,
            q,
            v: b.beam,
            flight: Flight {
                t0: t,
                centre: [after.x, after.y],
                velocity: b.velocity,
                omega: b.omega,
                gravity: c.spec().gravity,
            },
            s,
        })
    }
}

/// Whether the impulse that took the disk from `before` to `after` (centre velocities,
/// global) needs more friction than the scene's `mu`: |Jₜ| > mu Jₙ in the track's frame.
pub(super) fn slips(
    c: &DiskOnBeam,
    landing: &Landing,
    t: f64,
    before: [f64; 2],
    after: [f64; 2],
) -> bool {
    let Some(mu) = c.spec().mu else {
        return false;
    };
    let [tg, nm] = c.contact_frame(0, t, &landing.z, &landing.zd);
    let m = c.spec().disk.mass;
    let dv = [after[0] - before[0], after[1] - before[1]];
    let jt = m * (dv[0] * tg[0] + dv[1] * tg[1]);
    let jn = m * (dv[0] * nm[0] + dv[1] * nm[1]);
    jt.abs() > mu * jn
}

//! The disk's flights over the beam: its lift-off, the beam alone under it while it flies in
//! closed form, and the landing (with its bounces) or its leaving the beam.

use super::*;
use crate::coupling::landing::Bounce;

/// How a flight over the beam ended.
pub(super) enum FlightEnd {
    /// The disk landed and rolls on from the coupled state (t, z, ż).
    Lands { t: f64, z: Vec<f64>, zd: Vec<f64> },
    /// The run ends in the air, or stops at the landing: y is the phase's state then.
    Stops { t: f64, y: Vec<f64>, stop: Stop },
    /// The disk flew beyond an end of the beam; the beam goes on alone from (q, v).
    Leaves { t: f64, q: Vec<f64>, v: Vec<f64> },
}

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

/// From a lift-off at (t, y) of the coupled phase: the beam integrated alone under the disk's
/// flight until the disk lands (or passes an end, or the run ends), the landing, and the
/// bounces after it.
#[allow(clippy::too_many_arguments)]
pub(super) fn fly<'a>(
    scene: &Scene,
    c: &'a DiskOnBeam<'a>,
    loaded: &'a LoadedBeam<'a>,
    t: f64,
    y: &[f64],
    outputs: &[f64],
    opts: &ode::Options,
    rec: &mut Recorder<'a>,
    stats: &mut Stats,
    flights: &mut Vec<FlightRecord>,
) -> Result<FlightEnd, Error> {
    let restitution = match c.spec().contact_loss {
        ContactLoss::Fly { restitution } => restitution,
        ContactLoss::Stop => 0.0,
    };
    let mut launch = lift_off(c, rec, t, y);
    loop {
        let touch = match fly_once(
            scene, c, loaded, &launch, outputs, opts, rec, stats, flights,
        )? {
            Aloft::Touches(touch) => touch,
            Aloft::Ends(end) => return Ok(end),
        };
        let record = flights.last_mut().expect("pushed by the flight");
        match touch_down(scene, c, restitution, launch.t, touch, rec, record)? {
            Next::FliesAgain(next) => launch = next,
            Next::Ends(end) => return Ok(end),
        }
    }
}

/// Where one flight over the beam got to.
enum Aloft {
    /// The disk touches the beam again.
    Touches(Touch),
    /// The run ended in the air, or the disk flew past an end.
    Ends(FlightEnd),
}

/// The disk touching the beam at t, the beam in (q, v), after `flight`; `s` the beam's
/// nearest point to where it flew.
struct Touch {
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    flight: Flight,
    s: f64,
}

/// What a touch of the beam leads to.
enum Next {
    /// The disk bounced off: another flight.
    FliesAgain(Launch),
    /// It rolls on, stops, or lifts off at once.
    Ends(FlightEnd),
}

/// One flight from `launch`: the beam integrated alone under the disk in the air until it
/// touches the beam, passes an end, or the run ends; recorded in `flights`.
#[allow(clippy::too_many_arguments)]
fn fly_once<'a>(
    scene: &Scene,
    c: &'a DiskOnBeam<'a>,
    loaded: &'a LoadedBeam<'a>,
    launch: &Launch,
    outputs: &[f64],
    opts: &ode::Options,
    rec: &mut Recorder<'a>,
    stats: &mut Stats,
    flights: &mut Vec<FlightRecord>,
) -> Result<Aloft, Error> {
    if flights.len() >= MAX_FLIGHTS {
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
    rec.phase.free();
    rec.phase.flying = Some(disk.clone());
    flights.push(FlightRecord {
        lift_off_t: launch.t,
        lift_off_s: launch.s,
        land_t: None,
        land_s: None,
        max_gap: 0.0,
        energy_lost: None,
    });
    rec.watches.gap = Watch::new(1, Turning::OnTheSolution);
    let beneath = BeneathFlight { loaded, disk };
    let ahead: Vec<f64> = outputs.iter().copied().filter(|&o| o > launch.t).collect();
    let out = integrate(
        &beneath,
        launch.t,
        &launch.q,
        &launch.v,
        scene.duration,
        &ahead,
        opts,
        rec,
    )
    .map_err(|e| solver_error(scene, e))?;
    stats.add(&out.stats);
    let record = flights.last_mut().expect("pushed above");
    record.max_gap = rec.watches.gap.ranges[0].max.max(0.0);
    let Some(hit) = out.stopped_by else {
        return Ok(Aloft::Ends(FlightEnd::Stops {
            t: out.t,
            y: out.y,
            stop: Stop::End,
        }));
    };
    let (q, v) = out.y.split_at(loaded.dim());
    if hit.reason == FlightEvent::PassesEnd {
        rec.phase.flying = None;
        return Ok(Aloft::Ends(FlightEnd::Leaves {
            t: out.t,
            q: q.to_vec(),
            v: v.to_vec(),
        }));
    }
    let flight = beneath.disk.flight;
    let s = c.gap(q, flight.centre(out.t), beneath.disk.s.get()).s;
    Ok(Aloft::Touches(Touch {
        t: out.t,
        q: q.to_vec(),
        v: v.to_vec(),
        flight,
        s,
    }))
}

/// The disk touches the beam (`touch`, after a flight launched at `launched`): it lands
/// plastically, or bounces off where the restitution throws it high enough to resolve; then
/// it rolls on, slips, or lifts off again. `record` is the flight's.
fn touch_down<'a>(
    scene: &Scene,
    c: &'a DiskOnBeam<'a>,
    restitution: f64,
    launched: f64,
    touch: Touch,
    rec: &mut Recorder<'a>,
    record: &mut FlightRecord,
) -> Result<Next, Error> {
    let Touch { t, q, v, flight, s } = touch;
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
            rec.phase.mass_lu,
        )
    } else {
        None
    };
    let gravity_n = c.spec().gravity * c.contact_frame(0, t, &landing.z, &landing.zd)[1][1];
    if let Some(b) = bounce.filter(|b| {
        gravity_n <= 0.0
            || b.leaving * b.leaving / (2.0 * gravity_n) >= RESOLVED_BOUNCE * c.spec().disk.radius
    }) {
        record.energy_lost = Some(b.energy_lost);
        return Ok(bounce_off(c, rec, (t, s), q, &landing, before, b));
    }
    record.energy_lost = Some(landing.energy_lost);
    rec.ledger.disk_lands(landing.energy_lost);
    rec.phase.couple(c);
    let after = c.observe(t, &landing.z, &landing.zd);
    let y: Vec<f64> = landing.z.iter().chain(&landing.zd).copied().collect();
    if slips(c, &landing, t, before, [after.vx, after.vy]) {
        return Ok(Next::Ends(FlightEnd::Stops {
            t,
            y,
            stop: Stop::Event(StopReason::Slip),
        }));
    }
    // The disk rolls on from the landing, unless the beam falls away faster than it can
    // follow there, in which case it lifts off at once; but a disk that touches again the
    // instant it left, and then would have to be pulled to stay on, can neither roll nor
    // fly there, and the run stops at that contact loss.
    if after.rn > 0.0 {
        return Ok(Next::Ends(FlightEnd::Lands {
            t,
            z: landing.z,
            zd: landing.zd,
        }));
    }
    if t <= launched + 1e-12 * (1.0 + t.abs()) {
        return Ok(Next::Ends(FlightEnd::Stops {
            t,
            y,
            stop: Stop::Event(StopReason::ContactLost),
        }));
    }
    Ok(Next::FliesAgain(lift_off(c, rec, t, &y)))
}

/// The disk bouncing off the beam where it landed at (t, s) from `before` (its centre
/// velocity) with the beam at q: it flies again, unless friction cannot hold the impulse.
fn bounce_off<'a>(
    c: &'a DiskOnBeam<'a>,
    rec: &mut Recorder<'a>,
    (t, s): (f64, f64),
    q: Vec<f64>,
    landing: &Landing,
    before: [f64; 2],
    b: Bounce,
) -> Next {
    let after = c.observe(t, &landing.z, &landing.zd);
    if slips(c, landing, t, before, b.velocity) {
        rec.ledger.disk_lands(landing.energy_lost);
        rec.phase.couple(c);
        return Next::Ends(FlightEnd::Stops {
            t,
            y: landing.z.iter().chain(&landing.zd).copied().collect(),
            stop: Stop::Event(StopReason::Slip),
        });
    }
    let m = c.spec().disk.mass;
    let kinetic = 0.5 * m * (b.velocity[0].powi(2) + b.velocity[1].powi(2))
        + 0.5 * c.spec().disk.inertia() * b.omega * b.omega;
    rec.ledger
        .disk_bounces(b.energy_lost, (kinetic, after.potential));
    Next::FliesAgain(Launch {
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

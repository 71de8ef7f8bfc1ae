//! The vehicles' part of a beam run: their model on the beam, the drive over the whole run
//! (each wheel's lift-offs and landings), and each vehicle's report from what was watched.

use super::*;

/// What a vehicle did over the run: its bodies' vertical accelerations and its wheels'
/// contact forces from the time it came onto the deck, located on the solution.
#[derive(Clone, Debug)]
pub struct VehicleReport {
    pub name: String,
    /// Per body: its name, the range of its vertical acceleration, and its root mean square.
    pub bodies: Vec<(String, Range, f64)>,
    /// Per axle: its name and the range of its wheel's contact force.
    pub axles: Vec<(String, Range)>,
    /// When its last wheel left the deck, if it did in the run.
    pub left_t: Option<f64>,
    /// When it stopped, braking, if it did.
    pub stopped_t: Option<f64>,
    /// The axle whose wheel lost contact and stopped the run.
    pub lost_contact: Option<String>,
    /// Per axle, its disk wheel's flights.
    pub flights: Vec<Vec<AxleFlight>>,
}

/// One flight of a vehicle's disk wheel (`summary.yaml`, `vehicles.<name>.axles.<axle>.flights`):
/// when and where (the wheel's centre along the beam) it lifted off and landed, and the energy
/// the plastic landing took (J); a flight the run ends in has no landing.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct AxleFlight {
    pub lift_off_t: f64,
    pub lift_off_x: f64,
    pub land_t: Option<f64>,
    pub land_x: Option<f64>,
    pub energy_lost: Option<f64>,
}

/// One flight of a vehicle's disk wheel (index among all the wheels), from lift-off to
/// landing.
#[derive(Clone, Copy, Debug)]
pub(super) struct WheelFlight {
    wheel: usize,
    lift_off_t: f64,
    land_t: Option<f64>,
    /// What the landing took (J).
    energy_lost: Option<f64>,
}

/// Crests a disk wheel may meet at one instant (three crests level at once, and round-off)
/// before the run stops rather than turn between them.
const MAX_MEETINGS_AT_ONCE: usize = 8;

impl WheelFlight {
    /// Wheel k lifting off at t.
    fn off(wheel: usize, t: f64) -> Self {
        WheelFlight {
            wheel,
            lift_off_t: t,
            land_t: None,
            energy_lost: None,
        }
    }
}

/// The vehicles on the beam, where the scene has them.
pub(super) fn vehicles_on<'a>(
    scene: &Scene,
    setup: &'a BeamScene,
    loaded: &'a LoadedBeam<'a>,
    first: usize,
) -> Result<Option<VehiclesOnBeam<'a>>, Error> {
    if setup.vehicles.is_empty() {
        return Ok(None);
    }
    let patch = crate::coupling::patch::dispersed_half_width(setup.beam.depth);
    VehiclesOnBeam::new(loaded, &setup.vehicles, &setup.profile, patch, first)
        .map(Some)
        .ok_or_else(|| {
            Error::Solver(format!(
                "scene {}: the mass matrix of the beam and the vehicles' bodies is singular",
                scene.name
            ))
        })
}

/// Integrate the vehicles on the beam over the whole run: on the deck, and on the rigid
/// approaches before and after it, until the end or a wheel that cannot fly loses contact. A
/// disk wheel with an unsprung mass flies where its contact force falls to zero and lands,
/// plastically, where it touches the track again; the run goes on from each.
pub(super) fn drive<'a>(
    scene: &Scene,
    v: &'a VehiclesOnBeam<'a>,
    y0: &[f64],
    outputs: &[f64],
    opts: &ode::Options,
    rec: &mut Recorder<'a>,
    stats: &mut Stats,
) -> Result<Ridden, Error> {
    let n = v.dim();
    let (mut t, mut y) = (0.0, y0.to_vec());
    let mut wheels = Wheels::start(scene, v, t, &mut y, rec)?;
    let (stop, lost_contact) = loop {
        let ahead: Vec<f64> = outputs
            .iter()
            .copied()
            .filter(|&o| t == 0.0 || o > t)
            .collect();
        let out = integrate(v, t, &y[..n], &y[n..], scene.duration, &ahead, opts, rec)
            .map_err(|e| solver_error(scene, opts.method, e))?;
        stats.add(&out.stats);
        (t, y) = (out.t, out.y);
        let Some(hit) = out.stopped_by else {
            break (Stop::End, None);
        };
        if let Some(lost) = wheels.meet(scene, v, hit.reason, t, &mut y, rec)? {
            break (Stop::Event(StopReason::ContactLost), Some(lost));
        }
    };
    record_once(rec, t, &y);
    Ok(Ridden {
        stop,
        left_track_t: None,
        disks_left: Vec::new(),
        flights: Vec::new(),
        then: Then::Ended { t, y },
        lost_contact,
        stopped_disk: None,
        wheel_flights: wheels.flights,
    })
}

/// The vehicles' wheels over a run: their flights, and the crests they meet.
pub(super) struct Wheels {
    pub(super) flights: Vec<WheelFlight>,
    /// When a wheel last met a crest, and how many it has met since at that instant.
    meeting: Option<f64>,
    stalled: usize,
}

impl Wheels {
    /// The wheels at the run's start (t, y): the crests they rest on held from the first
    /// step on, as from every accepted one (searched afresh at each stage, a contact could
    /// pass to a crest rising ahead without the impact the crest event finds), and a wheel
    /// that cannot hold the track it starts on (a crest sharper than it follows at its speed)
    /// in the air from the first row on, as at any lift-off.
    pub(super) fn start(
        scene: &Scene,
        v: &VehiclesOnBeam,
        t: f64,
        y: &mut [f64],
        rec: &mut Recorder,
    ) -> Result<Self, Error> {
        let mut wheels = Wheels {
            flights: Vec::new(),
            meeting: None,
            stalled: 0,
        };
        v.remember_crests(t, &y[..v.dim()]);
        for k in 0..v.wheels() {
            if v.can_fly(k) && pulls(v, k, t, y) {
                v.lift(k, t, y);
                take_off(scene, &mut wheels.flights, k, t)?;
                rec.ledger.restart(&rec.phase, t, y);
            }
        }
        Ok(wheels)
    }

    /// The vehicles' event `k` met at t in the state y: a crest met, a flying wheel landing,
    /// or a wheel lifting off, after which the run goes on from y; the vehicle and axle of a
    /// wheel that cannot fly and lost contact, where the run stops.
    pub(super) fn meet(
        &mut self,
        scene: &Scene,
        v: &VehiclesOnBeam,
        k: usize,
        t: f64,
        y: &mut [f64],
        rec: &mut Recorder,
    ) -> Result<Option<(usize, String)>, Error> {
        if let Some(k) = v.crest_event(k) {
            self.stalled = if self.meeting == Some(t) {
                self.stalled + 1
            } else {
                0
            };
            self.meeting = Some(t);
            if self.stalled > MAX_MEETINGS_AT_ONCE {
                let (i, axle) = v.wheel(k);
                return Err(Error::Solver(format!(
                    "scene {}: vehicle {}'s disk wheel {axle} met crest after crest at t = {t:.9} s without moving on: the road's crests there lie level within round-off",
                    scene.name, v.vehicles[i].name
                )));
            }
            meet_crest(scene, v, k, t, y, rec, &mut self.flights)?;
            return Ok(None);
        }
        if !v.can_fly(k) {
            return Ok(Some(v.wheel(k)));
        }
        if v.flies(k) {
            record_once(rec, t, y);
            rec.restart();
            land(v, k, t, y, rec, &mut self.flights);
        } else {
            // The row at the lift-off is the wheel's first in the air: its contact force may
            // drop to zero at once (a disk wheel at a crest), and on the track past that
            // instant the wheel would pull on the deck.
            v.lift(k, t, y);
            record_once(rec, t, y);
            rec.restart();
            take_off(scene, &mut self.flights, k, t)?;
        }
        rec.ledger.restart(&rec.phase, t, y);
        Ok(None)
    }
}

/// The row at t, unless the history already ends there.
fn record_once(rec: &mut Recorder, t: f64, y: &[f64]) {
    if rec.history.rows.last().is_none_or(|r| r.t < t) {
        rec.output(t, y);
    }
}

/// Flying wheel k lands at t ([`VehiclesOnBeam::land`]): the ledger books what the landing
/// took, and its flight ends, unless the body pulls the axle up at once and it flies on at the
/// track's speed.
fn land(
    v: &VehiclesOnBeam,
    k: usize,
    t: f64,
    y: &mut [f64],
    rec: &mut Recorder,
    flights: &mut [WheelFlight],
) {
    let (lost, work) = v.land(k, t, y);
    rec.ledger.wheel_lands(lost, work);
    let flies_on = pulls(v, k, t, y);
    if flies_on {
        v.lift(k, t, y);
    }
    if let Some(f) = flights.iter_mut().rev().find(|f| f.wheel == k) {
        f.land_t = (!flies_on).then_some(t);
        f.energy_lost = Some(f.energy_lost.unwrap_or(0.0) + lost);
    }
}

/// Wheel k meets the crest ahead at t ([`VehiclesOnBeam::meet_crest`]), and flies on from it
/// where its body pulls its axle up.
fn meet_crest<'a>(
    scene: &Scene,
    v: &VehiclesOnBeam,
    k: usize,
    t: f64,
    y: &mut [f64],
    rec: &mut Recorder<'a>,
    flights: &mut Vec<WheelFlight>,
) -> Result<(), Error> {
    rec.restart();
    let (lost, work) = v.meet_crest(k, t, y);
    rec.ledger.wheel_lands(lost, work);
    if v.can_fly(k) && pulls(v, k, t, y) {
        v.lift(k, t, y);
        take_off(scene, flights, k, t)?;
    }
    rec.ledger.restart(&rec.phase, t, y);
    Ok(())
}

/// Book wheel k's lift-off at t, within the run's budget of flights: however a wheel leaves
/// the track (its force falling to zero, or a crest it meets throwing it), each flight counts.
fn take_off(scene: &Scene, flights: &mut Vec<WheelFlight>, k: usize, t: f64) -> Result<(), Error> {
    if flights.len() >= MAX_FLIGHTS {
        return Err(Error::Solver(format!(
            "scene {}: the vehicles' wheels lifted off {MAX_FLIGHTS} times by t = {t:.6} s; the run stops rather than count more flights",
            scene.name
        )));
    }
    flights.push(WheelFlight::off(k, t));
    Ok(())
}

/// Whether wheel k, on the track at (t, y), pulls on it.
fn pulls(v: &VehiclesOnBeam, k: usize, t: f64, y: &[f64]) -> bool {
    let (z, zd) = y.split_at(v.dim());
    v.contact_forces(t, z, zd, &v.acceleration_the_wheels_feel(t, z, zd))[k] < 0.0
}

/// Each vehicle's report from the ranges watched (per vehicle, its bodies' accelerations then
/// its wheels' contact forces) and the bodies' root mean squares.
pub(super) fn vehicle_reports(
    setup: &BeamScene,
    ranges: &[Range],
    rms: &[Option<f64>],
    lost: Option<(usize, String)>,
    wheel_flights: &[WheelFlight],
    t_end: f64,
    length: f64,
) -> Vec<VehicleReport> {
    let patch = crate::coupling::patch::dispersed_half_width(setup.beam.depth);
    let (mut r, mut b) = (ranges.iter(), rms.iter());
    let mut first_wheel = 0;
    setup
        .vehicles
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let last = v.axles.last().map_or(0.0, |a| a.x);
            let wheels = first_wheel..first_wheel + v.axles.len();
            first_wheel = wheels.end;
            let mut flights = vec![Vec::new(); v.axles.len()];
            for f in wheel_flights.iter().filter(|f| wheels.contains(&f.wheel)) {
                let a = f.wheel - wheels.start;
                let at = |t: f64| v.travel(t).0 - v.axles[a].x;
                flights[a].push(AxleFlight {
                    lift_off_t: f.lift_off_t,
                    lift_off_x: at(f.lift_off_t),
                    land_t: f.land_t,
                    land_x: f.land_t.map(at),
                    energy_lost: f.energy_lost,
                });
            }
            VehicleReport {
                flights,
                name: v.name.clone(),
                bodies: v
                    .bodies
                    .iter()
                    .map(|body| {
                        let range = r.next().copied().unwrap_or(Range::EMPTY);
                        // Over a vanishing time the root mean square tends to the magnitude
                        // at that instant, the largest the run saw.
                        let rms = b
                            .next()
                            .copied()
                            .flatten()
                            .unwrap_or_else(|| range.largest_magnitude().0);
                        (body.name.clone(), range, rms)
                    })
                    .collect(),
                axles: v
                    .axles
                    .iter()
                    .map(|a| (a.name.clone(), r.next().copied().unwrap_or(Range::EMPTY)))
                    .collect(),
                left_t: v.time_at(length + last + patch).filter(|&t| t <= t_end),
                stopped_t: v.stops_at().filter(|&t| t <= t_end),
                lost_contact: lost
                    .as_ref()
                    .filter(|(k, _)| *k == i)
                    .map(|(_, axle)| axle.clone()),
            }
        })
        .collect()
}

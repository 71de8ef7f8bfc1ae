//! The disks' ride on the beam, as their life at the track (`disk::life`) meets it: rolling
//! until one leaves the beam, stops, or lifts off (its flight and landing are `fly.rs`), with
//! the wheels' events of vehicles riding beside them met on the way.

use super::*;

/// Integrate while a disk is on the beam: rolling, and flying and landing where a disk
/// loses contact and flies, until the last leaves the beam, one stops, or the run ends.
#[allow(clippy::too_many_arguments)]
pub(super) fn ride<'a>(
    scene: &Scene,
    setup: &BeamScene,
    loaded: &'a LoadedBeam<'a>,
    c: &'a DiskOnBeam<'a>,
    literal: bool,
    start: &[f64],
    outputs: &[f64],
    opts: &mut ode::Options,
    rec: &mut Recorder<'a>,
    stats: &mut Stats,
) -> Result<Ridden, Error> {
    let wheels = match c.vehicles_beside() {
        Some(v) => {
            let mut y0 = initial_state(loaded, Some(c), Some(v), start);
            let wheels = Wheels::start(scene, v, 0.0, &mut y0, rec)?;
            // A wheel set in the air at the start leaves the run's start state changed.
            let lifted = !wheels.flights.is_empty();
            Some((wheels, lifted.then_some(y0)))
        }
        None => None,
    };
    let (wheels, from) = match wheels {
        Some((w, Some(y0))) => {
            let (z0, zd0) = y0.split_at(c.dim());
            (Some(w), Some((0.0, z0.to_vec(), zd0.to_vec())))
        }
        Some((w, None)) => (Some(w), None),
        None => (None, None),
    };
    let mut on = OnTheBeam {
        scene,
        setup,
        loaded,
        c,
        literal,
        start,
        outputs,
        opts,
        rec,
        stats,
        flights: Vec::new(),
        left: vec![None; c.count()],
        wheels,
    };
    life::live(&mut on, Next::Rolls(from))
}

/// The beam as a disk's life meets it (`disk::life`): what the riders' phases need of the
/// run, and what they keep. Its flights and landings are `fly.rs`.
pub(super) struct OnTheBeam<'a, 'r> {
    pub(super) scene: &'r Scene,
    pub(super) setup: &'r BeamScene,
    pub(super) loaded: &'a LoadedBeam<'a>,
    pub(super) c: &'a DiskOnBeam<'a>,
    pub(super) literal: bool,
    pub(super) start: &'r [f64],
    pub(super) outputs: &'r [f64],
    pub(super) opts: &'r mut ode::Options,
    pub(super) rec: &'r mut Recorder<'a>,
    pub(super) stats: &'r mut Stats,
    pub(super) flights: Vec<FlightRecord>,
    /// When each disk left the beam.
    pub(super) left: Vec<Option<f64>>,
    /// The wheels of vehicles beside the disks.
    pub(super) wheels: Option<Wheels>,
}

impl<'a> OnTheBeam<'a, '_> {
    /// Disk k flies where its scene lets it, beside disks that can ride on through its
    /// landing (`DiskOnBeam::rides_beside_a_flight`); beside others, or beside vehicles, a
    /// lift-off stops the run.
    pub(super) fn flies(&self, k: usize) -> bool {
        let c = self.c;
        c.vehicles_beside().is_none()
            && matches!(c.spec_of(k).contact_loss, ContactLoss::Fly { .. })
            && (0..c.count()).all(|j| j == k || c.has_left(j) || c.rides_beside_a_flight(j))
    }

    /// The run stops at t in the state y of the coupled phase, for `stop`, where `disk`'s
    /// event stopped it.
    pub(super) fn stopped(
        &mut self,
        t: f64,
        y: Vec<f64>,
        stop: Stop,
        disk: Option<usize>,
    ) -> Next<Self> {
        // The run stops between output times: its last row is the stop itself.
        if self.rec.history.rows.last().is_none_or(|r| r.t < t) {
            self.rec.output(t, &y);
        }
        Next::Ends(Ridden {
            stop,
            left_track_t: None,
            disks_left: self.left.clone(),
            flights: std::mem::take(&mut self.flights),
            then: Then::Ended { t, y },
            lost_contact: None,
            stopped_disk: disk.filter(|_| stop != Stop::End),
            wheel_flights: self.wheel_flights(),
        })
    }

    /// The flights of the wheels of vehicles beside the disks.
    pub(super) fn wheel_flights(&mut self) -> Vec<WheelFlight> {
        self.wheels
            .as_mut()
            .map_or_else(Vec::new, |w| std::mem::take(&mut w.flights))
    }

    /// The last disk has left the beam at t, the beam in (q, v): from then on the residual
    /// vibration is watched.
    pub(super) fn left_beam(&mut self, t: f64, q: Vec<f64>, v: Vec<f64>) -> Next<Self> {
        for l in self.left.iter_mut().filter(|l| l.is_none()) {
            *l = Some(t);
        }
        self.rec.last_load_leaves(t);
        self.rec.restart();
        Next::Ends(Ridden {
            stop: Stop::End,
            left_track_t: Some(t),
            disks_left: self.left.clone(),
            flights: std::mem::take(&mut self.flights),
            then: Then::Alone { t, q, v },
            lost_contact: None,
            stopped_disk: None,
            wheel_flights: self.wheel_flights(),
        })
    }
}

impl<'a> life::Track for OnTheBeam<'a, '_> {
    type Rolling = Option<(f64, Vec<f64>, Vec<f64>)>;
    type Launch = Launch;
    type Touch = Touch;
    type End = Ridden;

    /// The disks roll from `from` (the run's start where `None`) until one leaves the beam,
    /// stops, or lifts off, or the run ends.
    fn roll(&mut self, from: Self::Rolling) -> Result<Next<Self>, Error> {
        let end = integrate_coupled(
            self.scene,
            self.c,
            self.literal,
            self.start,
            from,
            self.outputs,
            self.opts,
            self.rec,
            self.stats,
        )?;
        Ok(match end {
            CoupledEnd::Stopped {
                t,
                y,
                stop: Stop::Event(StopReason::ContactLost),
                disk: Some(k),
            } if self.flies(k) => {
                // The damping the plan chose is for loads that move: once the disk has
                // left the beam, what it lands with or leaves behind vibrates freely.
                if self.setup.rho_inf_chosen.is_some() {
                    self.opts.rho_inf = 1.0;
                }
                Next::Flies(lift_off(self.c, self.rec, t, &y, k))
            }
            CoupledEnd::Stopped { t, y, stop, disk } => self.stopped(t, y, stop, disk),
            CoupledEnd::Wheel { t, mut y, wheel } => {
                let v = self
                    .c
                    .vehicles_beside()
                    .expect("a wheel's event is of vehicles beside");
                let wheels = self.wheels.as_mut().expect("the wheels of vehicles beside");
                match wheels.meet(self.scene, v, wheel, t, &mut y, self.rec)? {
                    Some(lost) => {
                        let mut end =
                            self.stopped(t, y, Stop::Event(StopReason::ContactLost), None);
                        if let Next::Ends(r) = &mut end {
                            r.lost_contact = Some(lost);
                        }
                        end
                    }
                    None => {
                        let (z, zd) = y.split_at(self.c.dim());
                        Next::Rolls(Some((t, z.to_vec(), zd.to_vec())))
                    }
                }
            }
            CoupledEnd::Left { t, y, disk } => {
                let c = self.c;
                let k = disk.unwrap_or_else(|| leaving(c, t));
                let on = (0..c.count()).filter(|&j| !c.has_left(j)).count();
                // Beside vehicles the run goes on with the disk out of the equations.
                if on > 1 || c.vehicles_beside().is_some() {
                    self.left[k] = Some(t);
                    return Ok(Next::Rolls(Some(one_leaves(c, k, self.rec, t, y))));
                }
                self.rec.ledger.disk_leaves(&self.rec.phase, t, &y);
                let n = self.loaded.dim();
                let (z, zd) = self.rec.phase.split(&y);
                let (q, v) = (z[..n].to_vec(), zd[..n].to_vec());
                self.left_beam(t, q, v)
            }
        })
    }

    fn fly(&mut self, launch: Launch) -> Result<Next<Self>, Error> {
        self.fly_once(launch)
    }

    fn land(&mut self, touch: Touch) -> Result<Next<Self>, Error> {
        self.touch_down(touch)
    }
}

/// The prescribed load that left the beam at t, its exit time, where no disk's event stopped
/// the integration.
pub(super) fn leaving(c: &DiskOnBeam, t: f64) -> usize {
    match c.next_exit() {
        Some((te, k)) if (te - t).abs() <= 1e-12 * te.max(1.0) => k,
        _ => unreachable!("the coupled phase stops early only at an event or a load's exit"),
    }
}

/// Disk k leaves the beam at t, in the state y, while others ride on: the state they go on
/// from, with its contact coordinate at rest.
pub(super) fn one_leaves(
    c: &DiskOnBeam,
    k: usize,
    rec: &mut Recorder,
    t: f64,
    y: Vec<f64>,
) -> (f64, Vec<f64>, Vec<f64>) {
    rec.ledger.one_disk_leaves(&rec.phase, t, &y, k);
    rec.restart();
    let (z, zd) = rec.phase.split(&y);
    let (z, mut zd) = (z.to_vec(), zd.to_vec());
    c.leave(k, &mut zd);
    let y: Vec<f64> = z.iter().chain(&zd).copied().collect();
    rec.ledger.restart(&rec.phase, t, &y);
    (t, z, zd)
}

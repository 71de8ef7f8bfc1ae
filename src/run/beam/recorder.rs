//! The run's observers in one: what the sensors record at output times, the extremes watched
//! over every step, the energy ledger, and the progress bar.

use super::ledger::LOBATTO;
use super::modal_probes::ModalProbes;
use super::*;
use crate::ode::same_breakpoint;

/// Samples of the energy ledger while an axle or a wheel passes the beam's shortest wave.
const SAMPLES_PER_PASSAGE: f64 = 8.0;

/// Samples a piece of the ledger's Gauss–Lobatto rule spans at most.
const LOBATTO_REACH: f64 = 8.0;

/// What the ledger's rule may err by on each moving mode's share of its powers, of the
/// beam's energy. The modes a fast axle sets ringing move faster than a sample: at this
/// tolerance a lone axle at 1000 m/s over the HSLM bridge, integrated exactly, balances
/// within 3e-5.
const QUADRATURE_TOLERANCE: f64 = 1e-5;

/// Samples of the extremes' watch a period of the acceleration's cutoff, where the steps are
/// shorter (see `Recorder::watch`).
pub(super) const SAMPLES_PER_CUTOFF_PERIOD: f64 = 32.0;

/// Samples of the watch, where the steps are shorter, to the time a disk takes to cross its
/// contact patch's half-width.
pub(super) const SAMPLES_PER_PATCH: f64 = 20.0;

/// Samples a pair of a long step's sub-steps spans: an eighth of the cutoff's period, over
/// which the parabola through its three points turns at most once where the filtered signal
/// does. Over the HSLM sweep the largest accelerations come within 8·10⁻⁶ of those watched at
/// every sample, and within 4.2·10⁻⁴ at pairs twice as long.
const SAMPLES_A_PAIR: f64 = 4.0;

/// The most pairs of samples one long step is watched in (a bound on a step far longer than
/// the cutoff's period, which is then watched at this many points).
const MAX_STEP_PAIRS: f64 = 2048.0;

/// What the watches see of the run at one time: each probe's (u, w, φ, a); each disk's (rn,
/// rt, μ needed, w under it), NaN once it has left, then the flying disk's gap, while a disk
/// is on or over the beam; and when asked, the envelope's stations' (u, w, φ, a) and the
/// stretch of the axis.
pub(super) struct Snapshot {
    pub(super) probes: Vec<f64>,
    pub(super) disk: Option<Vec<f64>>,
    pub(super) along: Vec<f64>,
    /// Per vehicle, its bodies' vertical accelerations then its wheels' contact forces; NaN
    /// before it comes onto the deck.
    pub(super) vehicles: Vec<f64>,
}

impl Snapshot {
    /// Each probe's w.
    pub(super) fn deflections(&self) -> Vec<f64> {
        self.probes.iter().skip(1).step_by(4).copied().collect()
    }
}

/// What the watches take at the end of every step a disk rides: the probes' (u, w, φ, a) and
/// the disks' values as a [`Snapshot`] holds them.
pub(super) struct Trailed {
    t: f64,
    probes: Vec<f64>,
    disk: Vec<f64>,
}

/// A snapshot's disk values split into the disks' (rn, rt, μ needed, w under it) and the gap.
fn and_gap(disk: &[f64]) -> (&[f64], &[f64]) {
    disk.split_at(disk.len() - 1)
}

/// The quantities watched for their extremes (`extremes.rs`); `along` takes the parabola's
/// turning values, as it holds every station of the envelope.
pub(super) struct Watches {
    pub(super) probes: Watch,
    pub(super) after_exit: Watch,
    pub(super) disk: Watch,
    /// The gap of the current flight.
    pub(super) gap: Watch,
    pub(super) along: Watch,
    pub(super) vehicles: Watch,
}

impl Watches {
    pub(super) fn new(probes: usize, stations: usize, vehicles: usize, disks: usize) -> Self {
        Watches {
            vehicles: Watch::new(vehicles, Turning::OnTheSolution),
            probes: Watch::new(4 * probes, Turning::OnTheSolution),
            after_exit: Watch::new(probes, Turning::OnTheSolution),
            disk: Watch::new(4 * disks, Turning::OnTheSolution),
            gap: Watch::new(1, Turning::OnTheSolution),
            // No stations, no stretch through them.
            along: Watch::new(
                if stations == 0 { 0 } else { 4 * stations + 1 },
                Turning::OnTheParabola,
            ),
        }
    }
}

/// The run's observer: at every output time the phase gives the disk and the reactions, the
/// ledger the energies, and the sensors record them; at every step the ledger books the work.
pub(super) struct Recorder<'a> {
    pub(super) phase: Phase<'a>,
    pub(super) ledger: Ledger<'a>,
    /// The beam's axis at the envelope's sample points.
    pub(super) stations: Stations,
    /// What of the acceleration is recorded.
    pub(super) filter: Option<AccelerationFilter>,
    /// On a modal beam, the probes read from the amplitudes.
    pub(super) modal_probes: Option<ModalProbes>,
    pub(super) history: History<'a>,
    pub(super) envelope: Envelope,
    pub(super) pictures: Pictures<'a>,
    pub(super) means: Option<WindowedMeans>,
    pub(super) watches: Watches,
    /// Whether the envelope along the beam is watched (not in a sweep's case).
    pub(super) watch_along: bool,
    /// The snapshot at the end of the last step watched.
    pub(super) last: Option<(f64, Snapshot)>,
    /// The snapshot before that: with the stations, the start of the last step watched.
    pub(super) before: Option<(f64, Snapshot)>,
    /// The least time between samples of steps far shorter than it (see `Recorder::watch`).
    pub(super) spacing: f64,
    /// The output times: the ledger's pieces end at each, so that the energy a row records
    /// is booked by their rule up to its time.
    pub(super) outputs: Vec<f64>,
    /// The probes and the disk at the last two step ends watched while a disk is on or over
    /// the beam: then every step is.
    pub(super) trail: Vec<Trailed>,
    /// The envelope's stations at the last two times they were sampled.
    pub(super) along_trail: Vec<(f64, Vec<f64>)>,
    /// When the last load left the beam: from then on the residual vibration is watched.
    pub(super) exit_t: Option<f64>,
    pub(super) progress: Option<Progress>,
    /// When each vehicle came onto the deck (`None`: it never does).
    pub(super) arrivals: Vec<Option<f64>>,
    /// Per body of every vehicle, ∫ a² dt and the time it covers since the vehicle arrived.
    pub(super) squares: Vec<(f64, f64)>,
    /// The times the loads turn at (an axle or a wheel entering or leaving the deck, crossing a
    /// node or a kink of the profile), ascending: what is sampled has a kink or a jump there,
    /// which a parabola through samples on both sides would overshoot.
    pub(super) kinks: Vec<f64>,
}

impl Recorder<'_> {
    /// What the watches see at (t, y); the stations only when `along` asks for them.
    pub(super) fn snapshot(
        &self,
        t: f64,
        y: &[f64],
        rate: Option<&[f64]>,
        along: bool,
    ) -> Snapshot {
        if let Some(probes) = self.probes_alone(t, y, rate, along) {
            return Snapshot {
                probes,
                disk: None,
                along: Vec::new(),
                vehicles: Vec::new(),
            };
        }
        let phase = &self.phase;
        let (disks, gap) = phase.disks(t, y);
        let q = phase.displaced(t, y, &disks, rate);
        // The beam alone takes its accelerations from the dense output, without a solve for
        // them. With the disk on, the observation has solved for them already, and the
        // contact force, which the beam's acceleration under the disk enters, is sensitive
        // to it: the dense output's derivative moved D44's lowest contact force by 2e-3 of
        // the disk's weight against the acceleration of the interpolated state.
        let a = match (phase.coupled, rate) {
            (None, Some(yp)) => phase.split(yp).1[..phase.loaded.dim()].to_vec(),
            _ => phase.acceleration(t, y),
        };
        let a = match &self.filter {
            Some(f) => f.filtered(phase.loaded, &a),
            None => phase.loaded.to_mesh(&a).into_owned(),
        };
        let beam = phase.beam;
        let probes = self
            .history
            .probes
            .iter()
            .flat_map(|p| {
                let d = beam.displacement_at(&q, p.x);
                [d.u, d.w, d.phi, beam.displacement_at(&a, p.x).w]
            })
            .collect();
        let disk = (!disks.is_empty()).then(|| {
            let mut values: Vec<f64> = disks
                .iter()
                .flat_map(|d| match d {
                    Some(d) => [
                        d.rn,
                        d.rt,
                        d.mu_needed().unwrap_or(f64::NAN),
                        beam.displacement_at(&q, d.s).w,
                    ],
                    None => [f64::NAN; 4],
                })
                .collect();
            values.push(gap);
            values
        });
        let along = if along && self.watch_along {
            let displaced = beam.displacements(&self.stations, &q);
            let accelerations = beam.deflections(&self.stations, &a);
            stations_watched(&self.envelope.x, &displaced, &accelerations)
        } else {
            Vec::new()
        };
        let vehicles = self.vehicle_values(t, phase.vehicles(t, y, rate).as_ref());
        Snapshot {
            probes,
            disk,
            along,
            vehicles,
        }
    }

    /// The probes' values at (t, y) read from a modal beam's amplitudes, where they are all a
    /// snapshot sees: the beam alone, its accelerations from the dense output, the stations
    /// not asked for.
    fn probes_alone(
        &self,
        t: f64,
        y: &[f64],
        rate: Option<&[f64]>,
        along: bool,
    ) -> Option<Vec<f64>> {
        let phase = &self.phase;
        let alone = phase.coupled.is_none() && phase.flying.is_none() && phase.vehicles.is_none();
        let (probes, yp) = self.modal_probes.as_ref().zip(rate)?;
        if !alone || (along && self.watch_along) {
            return None;
        }
        let n = phase.loaded.dim();
        let kept = self.filter.as_ref().map_or(n, |f| f.kept.min(n));
        let f = phase.correct.then(|| {
            let mut f = vec![0.0; phase.beam.dim()];
            phase.loaded.external(t, &mut f);
            f
        });
        Some(probes.read(&y[..n], &phase.split(yp).1[..n], kept, f.as_deref()))
    }

    /// What the watches see of the vehicles: per vehicle its bodies' accelerations then its
    /// wheels' contact forces, NaN before it arrives on the deck.
    pub(super) fn vehicle_values(&self, t: f64, obs: Option<&VehicleObservation>) -> Vec<f64> {
        let Some(obs) = obs else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for (i, (bodies, rn)) in obs.bodies.iter().zip(&obs.rn).enumerate() {
            let on = self.arrivals[i].is_some_and(|ta| t >= ta);
            let seen = |v: f64| if on { v } else { f64::NAN };
            out.extend(bodies.iter().map(|b| seen(b[2])));
            out.extend(rn.iter().map(|&r| seen(r)));
        }
        out
    }

    /// Where each body's acceleration is among the vehicles' values.
    fn body_slots(&self) -> Vec<usize> {
        let Some(v) = self.phase.vehicles else {
            return Vec::new();
        };
        let mut slots = Vec::new();
        let mut at = 0;
        for veh in v.vehicles {
            slots.extend(at..at + veh.bodies.len());
            at += veh.bodies.len() + veh.axles.len();
        }
        slots
    }

    /// Add ∫ a² dt over [t0, t1] for each body, from its values at the ends (the trapezoidal
    /// rule) or at the ends and the middle (Simpson's).
    fn add_squares(&mut self, t: (f64, f64), values: [&[f64]; 2], middle: Option<&[f64]>) {
        let h = t.1 - t.0;
        for (k, slot) in self.body_slots().into_iter().enumerate() {
            let (a0, a1) = (values[0][slot], values[1][slot]);
            let integral = match middle {
                Some(m) => h / 6.0 * (a0 * a0 + 4.0 * m[slot] * m[slot] + a1 * a1),
                None => 0.5 * h * (a0 * a0 + a1 * a1),
            };
            if integral.is_finite() {
                self.squares[k].0 += integral;
                self.squares[k].1 += h;
            }
        }
    }

    /// Take in the step [t0, t1] of the dense output `dense`: its start, middle and end, and
    /// the turning points between them that set an extreme.
    pub(super) fn watch(&mut self, t0: f64, t1: f64, dense: &dyn Dense, sample: f64) {
        if !(t1 > t0) {
            return;
        }
        // Steps far shorter than the fastest thing reported (a sudden load's, at the defaults)
        // are watched every `spacing` s only, the parabola through the last three samples
        // taken as it is: at 32 samples a period of the acceleration's cutoff it is within
        // 10⁻⁴ of that mode's amplitude, and on every step and middle the watching cost a
        // third of such a run. While an axle or a wheel crosses the beam the samples are also
        // [`SAMPLES_PER_PASSAGE`] to its passage of the shortest wave: the deck's acceleration
        // under a load is forced by it directly, and at 10⁶ m/s, where the wheel is on the
        // deck for 25 µs, samples at the cutoff's pace stepped over it (0.0037 m/s² for 3.4).
        // With a disk on or over the beam the samples are also [`SAMPLES_PER_PATCH`] to the
        // patch's crossing (the beam's accelerations carry the contact force), and the disk's
        // own values are taken at every step's end.
        let spacing = if self.spacing > 0.0 { sample } else { 0.0 };
        let riding = (self.phase.coupled).or(self.phase.flying.as_ref().map(|f| f.coupled));
        let spacing = riding.map_or(spacing, |c| {
            let crossing = (0..c.count())
                .filter(|&k| !c.has_left(k))
                .map(|k| c.spec_of(k).patch / c.spec_of(k).v0().abs())
                .fold(f64::INFINITY, f64::min);
            spacing.min(crossing / SAMPLES_PER_PATCH)
        });
        // A load that crosses faster than the cutoff's pace sets the samples
        // (`sample_spacing`): its directly forced acceleration and the truncated modes' static
        // response under it are pulses as short as its passage, which a long step's three
        // points do not resolve, so such a step is sampled on the grid too.
        let passing = riding.is_none() && spacing < self.spacing;
        if t1 - t0 < spacing || passing {
            self.sample_inside(t0, t1, dense, spacing, riding.is_some());
        } else {
            self.watch_in_pairs(t0, t1, dense, spacing);
        }
    }

    /// Sample the step [t0, t1] on the even grid of `spacing` that runs on from the last
    /// sample, with a disk `riding` on or over the beam taking in the step's end as well.
    fn sample_inside(&mut self, t0: f64, t1: f64, dense: &dyn Dense, spacing: f64, riding: bool) {
        // The contact force rings at the frequencies of the disk on the beam's local
        // stiffness, above any cutoff: sampled less often than every step, D44's largest
        // (the disk meeting the beam at rest) came out 11 % low. The deck's accelerations
        // carry it (every mode is forced by it directly), so the envelope's stations are
        // taken at every step too: D50's largest acceleration read 2.4·10⁻³ low.
        if riding {
            self.trail_rider(t1, dense);
        }
        // The samples keep an even spacing, taken inside the step where they fall: the
        // bodies' root mean square is the trapezoidal rule over them, which on an even
        // grid of a smooth signal is spectrally accurate, and on the uneven step ends
        // read the railcar's bogies 2·10⁻⁴ low even at rtol 10⁻¹⁰.
        let first = match &self.last {
            Some((t, _)) => (t + spacing).max(t0),
            None if t1 - t0 < spacing => t1,
            None => t0,
        };
        let mut times: Vec<f64> = (0..)
            .map(|k| first + k as f64 * spacing)
            .take_while(|&ts| ts <= t1)
            .collect();
        // A step that ends where the loads turn is sampled there too: what is watched may
        // turn sharply there.
        if times.last() != Some(&t1) && self.turns_at(t1) {
            times.push(t1);
        }
        for ts in times {
            let end = self.snapshot(ts, &dense.at(ts), self.rate(dense, ts).as_deref(), !riding);
            self.sampled(end, ts, riding);
        }
    }

    /// Watch the long step [t0, t1] in pairs of sub-steps no longer than [`SAMPLES_A_PAIR`]
    /// samples of `spacing`, and book its bodies' squares and the trails the next step reads.
    fn watch_in_pairs(&mut self, t0: f64, t1: f64, dense: &dyn Dense, spacing: f64) {
        let fresh = self.along_trail.is_empty();
        let last = self.last.take();
        let mut w = std::mem::replace(&mut self.watches, Watches::new(0, 0, 0, 0));
        let see = |t: f64, along: bool| {
            self.snapshot(t, &dense.at(t), self.rate(dense, t).as_deref(), along)
        };
        let (start, sampled_before) = match last {
            Some((t, s)) if t == t0 => (s, None),
            Some((t, s)) => (see(t0, fresh), Some((t, s))),
            None => (see(t0, fresh), None),
        };
        // A long step is watched in pairs of sub-steps no longer than a sample, each pair's
        // turning points refined on the solution: on three points alone a step the exact
        // integration takes between two node crossings (two thirds of the cutoff's period on
        // HSLM's bridge) read HSLM-A1's largest acceleration at 114 m/s 4.3·10⁻³ low, and the
        // envelope's stations on its ends alone overshot the deck's by 3·10⁻³.
        let pairs = if spacing > 0.0 {
            ((t1 - t0) / (SAMPLES_A_PAIR * spacing))
                .ceil()
                .clamp(1.0, MAX_STEP_PAIRS) as usize
        } else {
            1
        };
        let n = 2 * pairs;
        let times: Vec<f64> = (0..=n)
            .map(|k| {
                if k == n {
                    t1
                } else {
                    t0 + (t1 - t0) * k as f64 / n as f64
                }
            })
            .collect();
        let mut shots = vec![start];
        shots.extend(times[1..n].iter().map(|&tk| see(tk, true)));
        shots.push(see(t1, true));
        let after_exit = self.exit_t.is_some_and(|te| t0 >= te);
        for i in (0..n).step_by(2) {
            let steps = StepWatch {
                t: [times[i], times[i + 1], times[i + 2]],
                after_exit,
                flying: self.phase.flying.is_some(),
            };
            steps.record(&mut w, [&shots[i], &shots[i + 1], &shots[i + 2]], |tt| {
                see(tt, false)
            });
        }
        self.watches = w;
        if self.watch_along {
            if fresh {
                self.trail_along(t0, shots[0].along.clone());
            }
            for k in 1..=n {
                self.trail_along(times[k], shots[k].along.clone());
            }
        }
        if !shots[0].vehicles.is_empty() {
            // Short steps before this one left their last sample short of its start: the time
            // between belongs to the root mean square too (left out, the railcar's bogies
            // under ESDIRK4, whose steps alternate short and long, read 1·10⁻² low).
            if let Some((t, s)) = &sampled_before {
                self.add_squares((*t, t0), [&s.vehicles, &shots[0].vehicles], None);
            }
            for i in (0..n).step_by(2) {
                self.add_squares(
                    (times[i], times[i + 2]),
                    [&shots[i].vehicles, &shots[i + 2].vehicles],
                    Some(&shots[i + 1].vehicles),
                );
            }
        }
        let end = shots.pop().expect("the step's end");
        let before = shots.pop().expect("a sample before the end");
        self.trail = end
            .disk
            .clone()
            .map(|disk| Trailed {
                t: t1,
                probes: end.probes.clone(),
                disk,
            })
            .into_iter()
            .collect();
        self.before = Some((times[n - 1], before));
        self.last = Some((t1, end));
    }

    /// How a step's work and damping are booked: `None`, by the trapezoidal rule over the
    /// step, where it spans two samples or less (a sample: `spacing`, and an eighth of the
    /// time a fast axle or wheel takes to pass the beam's shortest wave, over which its power
    /// on the modes changes); otherwise the longest piece the Gauss–Lobatto rule ([`LOBATTO`])
    /// may book it in: [`LOBATTO_REACH`] samples, and on a modal beam short enough for every
    /// mode that moves (`LoadedBeam::quadrature_piece`).
    fn ledger_pieces(&self, t0: f64, t1: f64, dense: &dyn Dense, sample: f64) -> Option<f64> {
        let loaded = self.phase.loaded;
        if !(sample > 0.0) || t1 - t0 <= 2.0 * sample {
            return None;
        }
        let mut piece = LOBATTO_REACH * sample;
        let floor = loaded.quadrature_floor(QUADRATURE_TOLERANCE);
        if floor.is_some_and(|f| t1 - t0 > 2.0 * f) {
            let n = loaded.dim();
            for t in [t0, t1] {
                let y = dense.at(t);
                let (z, zd) = self.phase.split(&y);
                if let Some(p) = loaded.quadrature_piece(&z[..n], &zd[..n], QUADRATURE_TOLERANCE) {
                    piece = piece.min(p);
                }
            }
        }
        Some(piece)
    }

    /// The time between samples from t0 on: `spacing`, and an eighth of the time the fastest
    /// axle or wheel on the beam takes to pass its shortest wave, over which the loads' power
    /// and the deck's directly forced acceleration change. 0 where neither is set.
    fn sample_spacing(&self, t0: f64, dense: &dyn Dense) -> f64 {
        let shorter = |a: f64, b: f64| if a > 0.0 { a.min(b) } else { b };
        let wheels = self.phase.vehicles.and_then(|v| {
            let y = dense.at(t0);
            v.load_passage(t0, self.phase.split(&y).0)
        });
        self.phase
            .loaded
            .load_passage(t0)
            .into_iter()
            .chain(wheels)
            .map(|p| p / SAMPLES_PER_PASSAGE)
            .fold(self.spacing, shorter)
    }

    /// The dense output's y'(t) where a snapshot reads it: not with the disk on the beam,
    /// whose observation solves for the accelerations itself.
    fn rate(&self, dense: &dyn Dense, t: f64) -> Option<Vec<f64>> {
        self.phase
            .coupled
            .is_none()
            .then(|| dense.rate(t))
            .flatten()
    }

    /// Take in the envelope's stations at t: with the two samples before it, the parabola
    /// through the three.
    fn trail_along(&mut self, t: f64, along: Vec<f64>) {
        match &self.along_trail[..] {
            [(ta, a), (tb, b)] if self.smooth_between(*ta, t) => {
                self.watches
                    .along
                    .record_parabola([*ta, *tb, t], [a, b, &along]);
                self.along_trail.remove(0);
            }
            [_, _] => {
                self.watches.along.record_point(t, &along);
                self.along_trail.remove(0);
            }
            _ => self.watches.along.record_point(t, &along),
        }
        self.along_trail.push((t, along));
    }

    /// Whether the loads turn at t, as the driver ends a step there: on the breakpoint, or a
    /// round-off away where two breakpoints lie that close ([`same_breakpoint`]).
    fn turns_at(&self, t: f64) -> bool {
        let next = self.kinks.partition_point(|&k| k < t);
        [next.checked_sub(1), Some(next)]
            .into_iter()
            .flatten()
            .filter_map(|i| self.kinks.get(i))
            .any(|&k| same_breakpoint(k, t))
    }

    /// Whether the loads turn nowhere after ta up to tb ([`Recorder::kinks`]): a window that
    /// ends where they turn holds a sample taken there as well as the grid's last, which may
    /// lie a round-off before it, and the parabola through two such samples is ill-conditioned.
    fn smooth_between(&self, ta: f64, tb: f64) -> bool {
        let from = self.kinks.partition_point(|&k| k <= ta);
        self.kinks.get(from).is_none_or(|&k| k > tb)
    }

    /// Take in the probes, the envelope's stations and the disk at the end t of a short step:
    /// with the two step ends before it, the parabola through the three. The beam's
    /// accelerations carry the contact force, and with it its ringing.
    fn trail_rider(&mut self, t: f64, dense: &dyn Dense) {
        let now = self.snapshot(t, &dense.at(t), self.rate(dense, t).as_deref(), true);
        if self.watch_along {
            self.trail_along(t, now.along);
        }
        let Some(disk) = now.disk else {
            self.trail.clear();
            return;
        };
        let now = Trailed {
            t,
            probes: now.probes,
            disk,
        };
        let flying = self.phase.flying.is_some();
        let w = &mut self.watches;
        let (values, gap) = and_gap(&now.disk);
        match &self.trail[..] {
            [a, b] if a.disk.len() == now.disk.len() && b.disk.len() == now.disk.len() => {
                let times = [a.t, b.t, t];
                w.probes
                    .record_parabola(times, [&a.probes, &b.probes, &now.probes]);
                let [(va, ga), (vb, gb)] = [and_gap(&a.disk), and_gap(&b.disk)];
                w.disk.record_parabola(times, [va, vb, values]);
                if flying {
                    w.gap.record_parabola(times, [ga, gb, gap]);
                }
                self.trail.remove(0);
            }
            _ => {
                w.probes.record_point(t, &now.probes);
                w.disk.record_point(t, values);
                if flying {
                    w.gap.record_point(t, gap);
                }
            }
        }
        self.trail.push(now);
    }

    /// The run goes on from a state that jumped (a wheel landed, or its law changed as it
    /// lifted off): the steps before it are not joined to those after.
    pub(super) fn restart(&mut self) {
        self.last = None;
        self.before = None;
        self.trail.clear();
        self.along_trail.clear();
    }

    /// Take in a sample at t of the beam alone, on its own (a short step's end): with the
    /// two before it, the parabola through the three. The probes are left out where the
    /// rider's trail has taken them (`trailed`).
    pub(super) fn sampled(&mut self, end: Snapshot, t: f64, trailed: bool) {
        if let Some((tl, last)) = self.last.take() {
            if !end.vehicles.is_empty() {
                self.add_squares((tl, t), [&last.vehicles, &end.vehicles], None);
            }
            self.last = Some((tl, last));
        }
        let smooth = (self.before.as_ref()).is_some_and(|(ta, _)| self.smooth_between(*ta, t));
        let w = &mut self.watches;
        let after = self.exit_t.is_some_and(|te| t >= te);
        match (self.before.take(), self.last.take()) {
            (Some((ta, a)), Some((tb, b))) if smooth => {
                let times = [ta, tb, t];
                if !trailed {
                    w.probes
                        .record_parabola(times, [&a.probes, &b.probes, &end.probes]);
                }
                if !end.vehicles.is_empty() {
                    w.vehicles
                        .record_parabola(times, [&a.vehicles, &b.vehicles, &end.vehicles]);
                }
                if after && ta >= self.exit_t.unwrap_or(f64::INFINITY) {
                    w.after_exit.record_parabola(
                        times,
                        [&a.deflections(), &b.deflections(), &end.deflections()],
                    );
                }
                self.before = Some((tb, b));
            }
            (_, last) => {
                if !trailed {
                    w.probes.record_point(t, &end.probes);
                }
                w.vehicles.record_point(t, &end.vehicles);
                self.before = last;
            }
        }
        if after {
            w.after_exit.record_point(t, &end.deflections());
        }
        if self.watch_along && !trailed {
            self.trail_along(t, end.along.clone());
        }
        self.last = Some((t, end));
    }

    /// The extremes watched, and the envelope from the stations'.
    pub(super) fn extremes(&self) -> (Extremes, Envelope) {
        let w = &self.watches;
        let probes = w
            .probes
            .ranges
            .chunks(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect();
        let extremes = Extremes {
            probes,
            after_exit: self
                .exit_t
                .map(|_| w.after_exit.ranges.clone())
                .filter(|r| r.iter().all(Range::seen)),
            // Any value watched says the disk was on or over the beam.
            disks: w
                .disk
                .ranges
                .chunks(4)
                .map(|r| r.iter().any(Range::seen).then(|| [r[0], r[1], r[2], r[3]]))
                .collect(),
            vehicles: w.vehicles.ranges.clone(),
        };
        (extremes, self.envelope.from_stations(&w.along.ranges))
    }
}

/// The stations' (u, w, φ, a), then the stretch of the axis through them.
pub(super) fn stations_watched(
    x: &[f64],
    along: &[crate::beam::PointDisplacement],
    accelerations: &[f64],
) -> Vec<f64> {
    let mut out: Vec<f64> = along
        .iter()
        .zip(accelerations)
        .flat_map(|(d, a)| [d.u, d.w, d.phi, *a])
        .collect();
    out.push(sensors::stretch(x, along));
    out
}

impl Observer for Recorder<'_> {
    fn output(&mut self, t: f64, y: &[f64]) {
        let phase = &self.phase;
        let (disks, gap) = phase.disks(t, y);
        let energy = self.ledger.at_output(phase, t, y, &disks);
        let q = phase.displaced(t, y, &disks, None);
        let a = phase.acceleration(t, y);
        let reactions = phase.reactions(t, y, &q, &a, &disks);
        // The stations are read for the envelope and the pictures alone: a sweep's case, which
        // watches no envelope and draws nothing, skips them.
        let along = if self.watch_along || self.pictures.draws_at(t) {
            phase.beam.displacements(&self.stations, &q)
        } else {
            Vec::new()
        };
        let a = match &self.filter {
            Some(f) => f.filtered(phase.loaded, &a),
            None => phase.loaded.to_mesh(&a).into_owned(),
        };
        let vehicles = phase.vehicles(t, y, None);
        let watched = self.vehicle_values(t, vehicles.as_ref());
        self.watches.vehicles.record_point(t, &watched);
        let sample = Sample {
            vehicles,
            t,
            q: &q,
            a: &a,
            along: &along,
            disks,
            gap,
            energy,
            reactions,
        };
        self.history.record(&sample);
        self.pictures.record(&sample);
        let row = self.history.rows.last().expect("recorded above");
        let probes: Vec<f64> = row
            .probes
            .iter()
            .zip(&row.accelerations)
            .flat_map(|(d, a)| [d.u, d.w, d.phi, *a])
            .collect();
        self.watches.probes.record_point(t, &probes);
        if self.watch_along {
            let along_a = phase.beam.deflections(&self.stations, &a);
            self.watches
                .along
                .record_point(t, &stations_watched(&self.envelope.x, &along, &along_a));
        }
        if self.exit_t.is_some_and(|te| t >= te) {
            let w: Vec<f64> = row.probes.iter().map(|d| d.w).collect();
            self.watches.after_exit.record_point(t, &w);
        }
        if self.phase.flying.is_some() {
            self.watches.gap.record_point(t, &[gap]);
        }
        if !row.disks.is_empty() {
            let values: Vec<f64> = row
                .disks
                .iter()
                .zip(&row.w_under)
                .flat_map(|(d, w)| match d {
                    Some(d) => [d.rn, d.rt, d.mu_needed().unwrap_or(f64::NAN), *w],
                    None => [f64::NAN; 4],
                })
                .collect();
            self.watches.disk.record_point(t, &values);
        }
    }

    fn step(&mut self, t: f64, y: &[f64]) {
        self.ledger.at_step(&self.phase, t, y);
        if let Some(p) = &mut self.progress {
            p.update(t);
        }
    }

    fn span(&mut self, t0: f64, t1: f64, dense: &dyn Dense) {
        self.ledger.step_ends(&self.phase, t1, &dense.at(t1));
        // A long step books the work and the damping on the way (see `ledger_pieces`).
        let sample = self.sample_spacing(t0, dense);
        if let Some(piece) = self.ledger_pieces(t0, t1, dense, sample) {
            let from = self.outputs.partition_point(|&o| o <= t0);
            let to = self.outputs.partition_point(|&o| o < t1);
            let ends: Vec<f64> = self.outputs[from..to].iter().copied().chain([t1]).collect();
            let mut pieces = Vec::new();
            let mut a = t0;
            for b in ends {
                let count = ((b - a) / piece).ceil().max(1.0);
                let at = |i: f64| a + (b - a) * i / count;
                for i in 1..=count as usize {
                    let (start, t) = (at(i as f64 - 1.0), at(i as f64).min(b));
                    let times = LOBATTO.0.map(|x| start + (t - start) * x);
                    let states = times.map(|ti| dense.at(ti));
                    let inner = [0, 1, 2].map(|k| (times[k], &states[k][..]));
                    pieces.push(self.ledger.piece(&self.phase, inner, t, &dense.at(t)));
                }
                a = b;
            }
            self.ledger.book_in_pieces(pieces);
        }
        self.watch(t0, t1, dense, sample);
        let (phase, history) = (&self.phase, &self.history);
        let Some(means) = &mut self.means else {
            return;
        };
        means.record_span(t0, t1, |t| {
            let y = dense.at(t);
            let (disks, _) = phase.disks(t, &y);
            let q = phase.displaced(t, &y, &disks, None);
            history
                .probes
                .iter()
                .map(|p| history.beam.displacement_at(&q, p.x).w)
                .collect()
        });
    }
}

/// A long step's three samples (start, middle, end) and what the headline watches take from
/// them; each watch refines its turning points on the solution through `see`.
struct StepWatch {
    t: [f64; 3],
    /// The last load has left: the residual vibration is watched.
    after_exit: bool,
    /// A disk flies: its gap is watched.
    flying: bool,
}

impl StepWatch {
    fn record(&self, w: &mut Watches, s: [&Snapshot; 3], see: impl Fn(f64) -> Snapshot) {
        let t = self.t;
        let [s0, s1, s2] = s;
        w.probes
            .record_step(t, [&s0.probes, &s1.probes, &s2.probes], |tt| see(tt).probes);
        if !s0.vehicles.is_empty() {
            w.vehicles
                .record_step(t, [&s0.vehicles, &s1.vehicles, &s2.vehicles], |tt| {
                    see(tt).vehicles
                });
        }
        if self.after_exit {
            w.after_exit.record_step(
                t,
                [&s0.deflections(), &s1.deflections(), &s2.deflections()],
                |tt| see(tt).deflections(),
            );
        }
        match (&s0.disk, &s1.disk, &s2.disk) {
            (Some(d0), Some(d1), Some(d2)) if d0.len() == d2.len() && d1.len() == d2.len() => {
                let [(v0, g0), (v1, g1), (v2, g2)] = [and_gap(d0), and_gap(d1), and_gap(d2)];
                let disk_at = |tt: f64| {
                    see(tt)
                        .disk
                        .filter(|d| d.len() == d2.len())
                        .unwrap_or_else(|| vec![f64::NAN; d2.len()])
                };
                w.disk
                    .record_step(t, [v0, v1, v2], |tt| and_gap(&disk_at(tt)).0.to_vec());
                if self.flying {
                    w.gap
                        .record_step(t, [g0, g1, g2], |tt| and_gap(&disk_at(tt)).1.to_vec());
                }
            }
            disks => {
                for (tt, d) in t.iter().zip([disks.0, disks.1, disks.2]) {
                    if let Some(d) = d {
                        w.disk.record_point(*tt, and_gap(d).0);
                    }
                }
            }
        }
    }
}

/// Hands the recorder the reduced state (q, s; v, ṡ) of the literal thesis system.
pub(super) struct ThesisSystemObserver<'a, 'r> {
    pub(super) sys: &'a ThesisSystem<'a>,
    pub(super) rec: &'a mut Recorder<'r>,
}

impl Observer for ThesisSystemObserver<'_, '_> {
    fn output(&mut self, t: f64, y: &[f64]) {
        let r = self.sys.reduced(t, y);
        self.rec.output(t, &r);
    }
    fn step(&mut self, t: f64, y: &[f64]) {
        let r = self.sys.reduced(t, y);
        self.rec.step(t, &r);
    }
    fn span(&mut self, t0: f64, t1: f64, dense: &dyn Dense) {
        let sys = self.sys;
        self.rec.span(t0, t1, &|t| sys.reduced(t, &dense.at(t)));
    }
}

/// The observers of a run, from its start state `y0`.
pub(super) fn recorder<'a>(
    scene: &Scene,
    setup: &'a BeamScene,
    over: &Overrides,
    phase: Phase<'a>,
    filter: Option<AccelerationFilter>,
    y0: &[f64],
    outputs: &[f64],
    show_progress: bool,
) -> Recorder<'a> {
    let beam = phase.beam;
    let xs: Vec<f64> = (0..SAMPLES)
        .map(|k| beam.length * k as f64 / (SAMPLES - 1) as f64)
        .collect();
    let spacing = filter
        .as_ref()
        .map_or(0.0, |f| 1.0 / (SAMPLES_PER_CUTOFF_PERIOD * f.cutoff_hz));
    let exit_t = last_exit(setup, &phase, beam.length);
    let arrivals = phase.vehicles.map_or_else(Vec::new, |v| v.arrives());
    let mut kinks = phase
        .vehicles
        .map_or_else(|| phase.loaded.breakpoints(), |v| v.breakpoints());
    kinks.retain(|k| k.is_finite());
    kinks.sort_by(f64::total_cmp);
    kinks.dedup();
    let probe_xs: Vec<f64> = setup.probes.iter().map(|p| p.x).collect();
    Recorder {
        ledger: Ledger::new(&phase, &setup.loads, y0),
        modal_probes: ModalProbes::new(phase.loaded, &probe_xs),
        filter,
        stations: beam.stations(&xs),
        history: History {
            beam,
            probes: &setup.probes,
            rows: Vec::with_capacity(outputs.len()),
        },
        phase,
        envelope: Envelope::new(xs),
        pictures: Pictures {
            shape_times: &setup.shapes,
            frame_every: over.animate.then(|| scene.duration / (FRAMES - 1) as f64),
            shapes: Vec::new(),
            frames: Vec::new(),
            turned: setup.disks.iter().map(|d| (0.0, d.omega0, 0.0)).collect(),
            wheel_offsets: setup
                .vehicles
                .iter()
                .map(|v| v.axles.iter().map(|a| a.x).collect())
                .collect(),
        },
        means: over
            .windowed_means
            .then(|| WindowedMeans::new(scene.duration, setup.probes.len())),
        watches: Watches::new(
            setup.probes.len(),
            if over.no_envelope { 0 } else { SAMPLES },
            setup
                .vehicles
                .iter()
                .map(|v| v.bodies.len() + v.axles.len())
                .sum(),
            setup.disks.len(),
        ),
        watch_along: !over.no_envelope,
        last: None,
        before: None,
        trail: Vec::new(),
        along_trail: Vec::new(),
        spacing,
        outputs: outputs.to_vec(),
        exit_t,
        arrivals,
        kinks,
        squares: vec![(0.0, 0.0); setup.vehicles.iter().map(|v| v.bodies.len()).sum()],
        progress: if show_progress {
            Progress::new(scene.duration)
        } else {
            None
        },
    }
}

/// When the last load leaves the beam: a train's last axle, or the vehicles' last wheel
/// (`None` while a vehicle never leaves).
fn last_exit(setup: &BeamScene, phase: &Phase, length: f64) -> Option<f64> {
    let train = setup.train.as_ref().map(|tr| tr.gone(length));
    let vehicles = phase.vehicles.map(|v| v.gone());
    match (train, vehicles) {
        (_, Some(None)) => None,
        (Some(a), Some(Some(b))) => Some(a.max(b)),
        (a, Some(b)) => a.or(b),
        (a, None) => a,
    }
}

/// What the observers recorded, theirs no longer: the beam they borrowed goes into the result.
pub(super) struct Recorded {
    pub(super) rows: Vec<BeamRow>,
    pub(super) envelope: Envelope,
    pub(super) extremes: Extremes,
    pub(super) shapes: Vec<(f64, Vec<PointDisplacement>)>,
    pub(super) frames: Vec<Frame>,
    pub(super) windowed_means: Vec<f64>,
    pub(super) y_end: Vec<f64>,
    pub(super) acceleration: Option<CutoffReport>,
    pub(super) energy: crate::run::EnergyCheck,
    /// Per body of every vehicle, the root mean square of its acceleration since it arrived.
    pub(super) vehicle_rms: Vec<f64>,
}

impl Recorded {
    pub(super) fn from(rec: Recorder, y_end: &[f64]) -> Recorded {
        if let Some(p) = &rec.progress {
            p.finish();
        }
        let y_end = on_mesh(&rec.phase, y_end);
        let (extremes, envelope) = rec.extremes();
        Recorded {
            rows: rec.history.rows,
            envelope,
            extremes,
            shapes: rec.pictures.shapes,
            frames: rec.pictures.frames,
            windowed_means: rec.means.map_or_else(Vec::new, |m| m.means()),
            y_end,
            acceleration: rec.filter.as_ref().map(|f| f.report()),
            energy: rec.ledger.check,
            vehicle_rms: rec
                .squares
                .iter()
                .map(|&(sq, time)| {
                    if time > 0.0 {
                        (sq / time).sqrt()
                    } else {
                        f64::NAN
                    }
                })
                .collect(),
        }
    }
}

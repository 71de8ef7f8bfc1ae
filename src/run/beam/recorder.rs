//! The run's observers in one: what the sensors record at output times, the extremes watched
//! over every step (`watch.rs`), the energy ledger's pieces, and the progress bar.

use super::contact_mean::ContactMeans;
use super::ledger::{Piece, LOBATTO};
use super::modal_probes::{ModalProbes, StepCorrection};
use super::reactions::Reactions;
use super::*;
use crate::ode::{FormRow, StepForms};

/// Samples of the energy ledger while an axle or a wheel passes the beam's shortest wave.
const SAMPLES_PER_PASSAGE: f64 = 8.0;

/// Samples a piece of the ledger's Gauss–Lobatto rule spans at most.
const LOBATTO_REACH: f64 = 8.0;

/// What the ledger's rule may err by on each moving mode's share of its powers, of the
/// beam's energy. The modes a fast axle sets ringing move faster than a sample: at this
/// tolerance a lone axle at 1000 m/s over the HSLM bridge, integrated exactly, balances
/// within 3e-5.
const QUADRATURE_TOLERANCE: f64 = 1e-5;

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

    /// Each probe's w, φ and a: what a long step's watch checks its pace by. The axial u,
    /// about round-off on a beam under transverse loads, is left out of the check.
    pub(super) fn paced(&self) -> Vec<f64> {
        (self.probes.chunks(4))
            .flat_map(|p| p[1..].iter().copied())
            .collect()
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
    /// The support reactions, to the filter's cutoff.
    reactions: Reactions,
    /// On a modal beam, the probes read from the amplitudes.
    pub(super) modal_probes: Option<ModalProbes>,
    /// Their sums over the modes, which a step's closed forms are asked for.
    probe_rows: std::cell::OnceCell<Vec<(Vec<f64>, bool)>>,
    pub(super) history: History<'a>,
    pub(super) envelope: Envelope,
    pub(super) pictures: Pictures<'a>,
    pub(super) means: Option<WindowedMeans>,
    /// The rolling disks' contact forces averaged over the cutoff's period.
    pub(super) contact_means: Option<ContactMeans>,
    pub(super) watches: Watches,
    /// Whether the envelope along the beam is watched (not in a sweep's case).
    pub(super) watch_along: bool,
    /// The snapshot at the end of the last step watched.
    pub(super) last: Option<(f64, Snapshot)>,
    /// The snapshot before that: with the stations, the start of the last step watched.
    pub(super) before: Option<(f64, Snapshot)>,
    /// Whether the watches restarted (`Recorder::restart`) and have not sampled since: the
    /// next step's start is the state after the jump, a sample of its own.
    pub(super) restarted: bool,
    /// The least time between samples of steps far shorter than it (see `Recorder::watch`).
    pub(super) spacing: f64,
    /// The output times: the ledger reads a piece from its last booked time to each, so that
    /// the energy a row records is booked by the pieces' rule up to its time.
    pub(super) outputs: Vec<f64>,
    /// What the last output row showed the watches, taken in when the run ends: the watches
    /// see the steps, and of the rows the first and the last alone, which every output grid
    /// has, so that no number the run reports moves with the grid.
    pub(super) last_row: Option<RowSeen>,
    /// The probes and the disk at the last two step ends watched while a disk is on or over
    /// the beam: then every step is.
    pub(super) trail: Vec<Trailed>,
    /// The envelope's stations at the last two times they were sampled.
    pub(super) along_trail: Vec<(f64, Vec<f64>)>,
    /// The deck where the last step watched under riders ended (`watch_the_deck_over`).
    pub(super) deck_end: Option<DeckEnd>,
    /// The vehicles where the last step watched ended (`watch_the_vehicles`): their squares
    /// are booked up to it.
    pub(super) vehicles_end: Option<DeckEnd<Vec<f64>>>,
    /// Whether a long step's samples check their own pace (`watch_in_pairs`): a load is
    /// switched on the beam.
    pub(super) paces_long_steps: bool,
    pub(super) grid_check: GridCheck,
    /// When the last load left the beam: from then on the residual vibration is watched.
    pub(super) exit_t: Option<f64>,
    /// Whether the free vibration can no longer move any extreme watched (`settled.rs`):
    /// from then on nothing is watched.
    pub(super) settled: bool,
    /// The envelope's stations as rows over a modal beam's modes, once `settled.rs` asks.
    pub(super) station_rows: Option<Vec<super::modal_probes::Rows>>,
    pub(super) progress: Option<Progress>,
    /// When each vehicle came onto the deck (`None`: it never does).
    pub(super) arrivals: Vec<Option<f64>>,
    /// Per body of every vehicle, ∫ a² dt and the time it covers since the vehicle arrived.
    pub(super) squares: Vec<(f64, f64)>,
    /// The last step as the watches read it, for the rows inside it.
    pub(super) watched: Option<WatchedStep>,
    /// The times the loads turn at (an axle or a wheel entering or leaving the deck, crossing a
    /// node or a kink of the profile), ascending: what is sampled has a kink or a jump there,
    /// which a parabola through samples on both sides would overshoot.
    pub(super) kinks: Vec<f64>,
}

impl Recorder<'_> {
    /// The disks' part changed at t, the state y after it (one left, lifted off or landed):
    /// a train on the beam goes on, its power read again from y rather than carried over.
    pub(super) fn train_goes_on(&mut self, t: f64, y: &[f64]) {
        if self.phase.loaded.train.is_some() {
            self.ledger.restart(&self.phase, t, y);
        }
    }

    /// A rider leaves the beam at t: the residual vibration is what follows the last load
    /// out, so where a train left before it, what was watched since is not residual.
    pub(super) fn last_load_leaves(&mut self, t: f64) {
        if self.exit_t.is_some_and(|te| te >= t) {
            return;
        }
        self.exit_t = Some(t);
        self.watches.after_exit = Watch::new(self.history.probes.len(), Turning::OnTheSolution);
    }

    /// What the watches see at (t, y); the stations only when `along` asks for them.
    pub(super) fn snapshot(
        &self,
        t: f64,
        y: &[f64],
        rate: Option<&[f64]>,
        along: bool,
    ) -> Snapshot {
        let mut s = self.deck_snapshot(t, y, rate, along);
        if self.phase.vehicles.is_some() {
            // Of the model's accelerations, as `Recorder::vehicles_seen` says why.
            s.vehicles = self.vehicle_values(t, self.phase.vehicles(t, y).as_ref());
        }
        s
    }

    /// What the watches see at (t, y) of the beam and the disks, without the vehicles.
    pub(super) fn deck_snapshot(
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
            stations_watched(beam, &self.envelope.x, &displaced, &accelerations)
        } else {
            Vec::new()
        };
        Snapshot {
            probes,
            disk,
            along,
            vehicles: Vec::new(),
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
        let (probes, yp) = self.modal_probes.as_ref().zip(rate)?;
        if !self.reads_probes_alone() || (along && self.watch_along) {
            return None;
        }
        let n = phase.loaded.dim();
        let a = &phase.split(yp).1[..n];
        let mut out = probes.read(&y[..n], a, self.kept_accelerations());
        self.correct_probes(t, &mut out);
        Some(out)
    }

    /// Whether a snapshot is the probes of a modal beam alone: no disk, flight or vehicle.
    fn reads_probes_alone(&self) -> bool {
        let phase = &self.phase;
        self.modal_probes.is_some()
            && phase.coupled.is_none()
            && phase.flying.is_none()
            && phase.vehicles.is_none()
    }

    /// The modes whose accelerations the probes read: those below the cutoff.
    fn kept_accelerations(&self) -> usize {
        let n = self.phase.loaded.dim();
        self.filter.as_ref().map_or(n, |f| f.kept.min(n))
    }

    /// Add the static response of the modes left out at t to the probes' values `out`.
    fn correct_probes(&self, t: f64, out: &mut [f64]) {
        let (Some(probes), true) = (&self.modal_probes, self.phase.correct) else {
            return;
        };
        let loads = |add: &mut dyn FnMut(usize, f64)| self.phase.loaded.external_terms(t, add);
        probes.correct(out, &loads);
    }

    /// The probes' sums over the modes in closed form over the step `dense` holds, where a
    /// snapshot is the probes alone and the stepper holds its motion as one (`exact-modal`):
    /// what [`Self::probes_alone`] reads, at a fraction of reading the state.
    pub(super) fn probe_forms(&self, dense: &dyn Dense) -> Option<StepForms> {
        if !self.reads_probes_alone() || self.watch_along {
            return None;
        }
        let probes = self.modal_probes.as_ref()?;
        let rows = (self.probe_rows).get_or_init(|| probes.form_rows(self.kept_accelerations()));
        let rows: Vec<FormRow> = rows
            .iter()
            .map(|(weights, accelerations)| FormRow {
                weights,
                accelerations: *accelerations,
            })
            .collect();
        dense.forms(&rows)
    }

    /// The probes' static correction over the step [t0, t1] as polynomials in time, where
    /// the loads are moving forces and standing ones (no riders' inertia).
    pub(super) fn probe_correction(&self, t0: f64, t1: f64) -> Option<StepCorrection> {
        let (probes, phase) = (self.modal_probes.as_ref()?, &self.phase);
        let middle = 0.5 * (t0 + t1);
        if !phase.correct || !(t1 > t0) || !phase.loaded.riding(middle).is_empty() {
            return None;
        }
        let standing = |add: &mut dyn FnMut(usize, f64)| phase.loaded.standing_terms(middle, add);
        let paths = phase.loaded.axle_paths(t0, t1);
        probes.correction_over(phase.beam, (t0, t1), &standing, &paths)
    }

    /// The snapshot at t read from the probes' `forms` and, where the step has one, their
    /// static `correction` over it.
    pub(super) fn snapshot_of_forms(
        &self,
        forms: &StepForms,
        correction: Option<&StepCorrection>,
        t: f64,
    ) -> Snapshot {
        let mut probes = vec![0.0; forms.len()];
        forms.at(t, &mut probes);
        match correction {
            Some(c) => c.add_to(t, &mut probes),
            None => self.correct_probes(t, &mut probes),
        }
        Snapshot {
            probes,
            disk: None,
            along: Vec::new(),
            vehicles: Vec::new(),
        }
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
    pub(super) fn body_slots(&self) -> Vec<usize> {
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

    /// How a step's work and damping are booked: `None`, over the whole
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

    /// The step [t0, t1] booked in closed form as one piece, where the integrator holds the
    /// motion as one and its force is the moving loads' alone
    /// (`Ledger::books_in_closed_form`); with the pieces from t0 to each output time inside
    /// it, for the rows.
    fn exact_pieces(&self, t0: f64, t1: f64, dense: &dyn Dense) -> Option<(Piece, Vec<Piece>)> {
        if !self.ledger.books_in_closed_form(&self.phase) {
            return None;
        }
        let piece = |b: f64| -> Option<Piece> {
            let by = dense.power_integrals(t0, b)?;
            Some(self.ledger.exact_piece(&self.phase, b, &dense.at(b), by))
        };
        let whole = piece(t1)?;
        let rows = self
            .outputs_inside(t0, t1)
            .iter()
            .map(|&o| piece(o))
            .collect::<Option<Vec<Piece>>>()?;
        Some((whole, rows))
    }

    /// The output times within (t0, t1).
    fn outputs_inside(&self, t0: f64, t1: f64) -> &[f64] {
        let from = self.outputs.partition_point(|&o| o <= t0);
        let to = self.outputs.partition_point(|&o| o < t1);
        &self.outputs[from..to.max(from)]
    }

    /// The piece from `start` to t, by the Gauss–Lobatto rule on the step as the budget reads
    /// it ([`BookedStep`]).
    fn lobatto_piece(&self, start: f64, t: f64, step: &BookedStep) -> Piece {
        let times = LOBATTO.0.map(|x| start + (t - start) * x);
        let states = times.map(|ti| step.at(ti));
        let inner = [0, 1, 2].map(|k| (times[k], &states[k][..]));
        self.ledger.piece(&self.phase, start, inner, t, &step.at(t))
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
            contact_means: self
                .contact_means
                .as_ref()
                .map_or_else(Vec::new, ContactMeans::ranges),
        };
        (extremes, self.envelope.from_stations(&w.along.ranges))
    }
}

/// The stations' (u, w, φ, a), then the stretch of the axis through them and how far a
/// linear beam's sliding end would draw in.
pub(super) fn stations_watched(
    beam: &crate::beam::Beam,
    x: &[f64],
    along: &[crate::beam::PointDisplacement],
    accelerations: &[f64],
) -> Vec<f64> {
    let mut out: Vec<f64> = along
        .iter()
        .zip(accelerations)
        .flat_map(|(d, a)| [d.u, d.w, d.phi, *a])
        .collect();
    out.push(sensors::stretch(beam, x, along));
    out.push(sensors::draw_in(beam, x, along));
    out
}

/// What an output row shows the watches.
pub(super) struct RowSeen {
    t: f64,
    vehicles: Vec<f64>,
    probes: Vec<f64>,
    along: Option<Vec<f64>>,
    after_exit: Option<Vec<f64>>,
    gap: Option<f64>,
    disks: Option<Vec<f64>>,
}

impl Watches {
    /// Take in what an output row shows.
    fn see_row(&mut self, r: &RowSeen) {
        let t = r.t;
        self.vehicles.record_point(t, &r.vehicles);
        self.probes.record_point(t, &r.probes);
        if let Some(along) = &r.along {
            self.along.record_point(t, along);
        }
        if let Some(w) = &r.after_exit {
            self.after_exit.record_point(t, w);
        }
        if let Some(gap) = r.gap {
            self.gap.record_point(t, &[gap]);
        }
        if let Some(values) = &r.disks {
            self.disk.record_point(t, values);
        }
    }
}

impl Observer for Recorder<'_> {
    fn output(&mut self, t: f64, y: &[f64]) {
        let phase = &self.phase;
        let read = self.watched.as_ref().and_then(|s| s.read(t));
        let (y, rate) = match &read {
            Some((y, r)) => (&y[..], Some(&r[..])),
            None => (y, None),
        };
        let (disks, gap) = phase.disks(t, y);
        let energy = self.ledger.at_output(phase, t, y, &disks);
        let q = phase.displaced(t, y, &disks, None);
        let a = match rate {
            Some(r) => phase.split(r).1[..phase.loaded.dim()].to_vec(),
            None => phase.acceleration(t, y),
        };
        let reactions = self
            .reactions
            .at(phase, self.filter.as_ref(), (t, y), (&q, &a), &disks);
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
        let vehicles = phase.vehicles_at_rate(t, y, rate);
        let watched = self.vehicle_values(t, vehicles.as_ref());
        let sample = Sample {
            vehicles,
            t,
            q: &q,
            a: &a,
            along: &along,
            disks,
            gap,
            flying: phase.flying.as_ref().map(|f| f.k),
            energy,
            reactions,
        };
        self.history.record(&sample);
        self.pictures.record(&sample);
        let row = self.history.rows.last().expect("recorded above");
        let seen = RowSeen {
            t,
            vehicles: watched,
            probes: row
                .probes
                .iter()
                .zip(&row.accelerations)
                .flat_map(|(d, a)| [d.u, d.w, d.phi, *a])
                .collect(),
            along: self.watch_along.then(|| {
                let along_a = phase.beam.deflections(&self.stations, &a);
                stations_watched(phase.beam, &self.envelope.x, &along, &along_a)
            }),
            after_exit: self
                .exit_t
                .is_some_and(|te| t >= te)
                .then(|| row.probes.iter().map(|d| d.w).collect()),
            gap: self.phase.flying.is_some().then_some(gap),
            disks: (!row.disks.is_empty()).then(|| {
                row.disks
                    .iter()
                    .zip(&row.w_under)
                    .flat_map(|(d, w)| match d {
                        Some(d) => [d.rn, d.rt, d.mu_needed().unwrap_or(f64::NAN), *w],
                        None => [f64::NAN; 4],
                    })
                    .collect()
            }),
        };
        if self.history.rows.len() == 1 {
            self.watches.see_row(&seen);
        } else {
            self.last_row = Some(seen);
        }
    }

    fn step(&mut self, t: f64, y: &[f64]) {
        self.ledger.at_step(&self.phase, t, y);
        if let Some(p) = &mut self.progress {
            p.update(t);
        }
    }

    fn span(&mut self, t0: f64, t1: f64, dense: &dyn Dense) {
        let y1 = dense.at(t1);
        self.ledger.step_ends(&self.phase, t1, &y1);
        if self.ledger.damps_at_mean_state(&self.phase) {
            let mean: Vec<f64> = (dense.at(t0).iter().zip(&y1))
                .map(|(a, b)| 0.5 * (a + b))
                .collect();
            self.ledger.step_mean_state(&self.phase, (t0, t1), &mean);
        }
        // A long step books the work and the damping on the way (see `ledger_pieces`).
        let sample = self.sample_spacing(t0, dense);
        if let Some((whole, rows)) = self.exact_pieces(t0, t1, dense) {
            self.ledger.book_in_pieces(vec![whole]);
            self.ledger.to_outputs(rows);
            if self.settled {
                return;
            }
            // The step is exact: from a settled state on, the integration may stride over
            // the rest of the run.
            if self.settles(t1, &dense.at(t1)) {
                self.settled = true;
                self.phase.loaded.stride_freely();
            }
        } else if let Some(piece) = self.ledger_pieces(t0, t1, dense, sample) {
            let step = BookedStep::new(&self.phase, &self.ledger, (t0, t1), &y1, dense);
            // Even pieces over the step whatever the output times; an output inside one
            // reads its own piece from that one's start.
            let count = ((t1 - t0) / piece).ceil().max(1.0);
            let at = |i: f64| t0 + (t1 - t0) * i / count;
            let pieces: Vec<Piece> = (1..=count as usize)
                .map(|i| self.lobatto_piece(at(i as f64 - 1.0), at(i as f64).min(t1), &step))
                .collect();
            let rows = self
                .outputs_inside(t0, t1)
                .iter()
                .map(|&o| {
                    // The last piece starting by o: those before it end by o, and the ledger
                    // has booked them when it writes o's row.
                    let mut i = ((o - t0) / (t1 - t0) * count)
                        .floor()
                        .clamp(0.0, count - 1.0);
                    while i > 0.0 && at(i) > o {
                        i -= 1.0;
                    }
                    while i + 1.0 < count && at(i + 1.0) <= o {
                        i += 1.0;
                    }
                    self.lobatto_piece(at(i), o, &step)
                })
                .collect();
            self.ledger.book_in_pieces(pieces);
            self.ledger.to_outputs(rows);
        } else if self.phase.vehicles.is_some() && self.ledger.books_by_simpson(&self.phase) {
            let step = BookedStep::new(&self.phase, &self.ledger, (t0, t1), &y1, dense);
            let state = |t: f64| step.at(t);
            let rows = self.outputs_inside(t0, t1);
            let (whole, rows) = self
                .ledger
                .adaptive_pieces(&self.phase, (t0, t1), rows, &state);
            self.ledger.book_in_pieces(vec![whole]);
            self.ledger.to_outputs(rows);
        } else if self.ledger.books_by_simpson(&self.phase) {
            let tm = 0.5 * (t0 + t1);
            let step = BookedStep::new(&self.phase, &self.ledger, (t0, t1), &y1, dense);
            self.ledger.step_midpoint(&self.phase, t1, tm, &step.at(tm));
        }
        let crests = self.phase.vehicles.and_then(|v| v.crest_pace(t0));
        self.watched = WatchedStep::new(&self.phase, &self.ledger, (t0, t1), &y1, dense);
        let step = self.watched.take();
        let seen = Watched {
            step: step.as_ref(),
            dense,
        };
        self.watch(t0, t1, &seen, sample, crests);
        self.watched = step;
        if let Some(means) = &mut self.contact_means {
            let phase = &self.phase;
            means.record_span(t0, t1, |t| phase.seen_disks(t, &dense.at(t)));
        }
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

/// A step this much shorter than the time it ends at is read as the dense output: the
/// positions' round-off over it exceeds the velocity.
const SLIVER: f64 = 1e-9;

/// A step as the energy budget reads it inside: the dense output's positions, and as
/// velocities the derivative of the cubic Hermite through the step's end positions and
/// velocities. A fast mode the implicit steps damp sits near rest at their ends while its
/// acceleration there, which the dense output's velocity is drawn through, swings with any
/// small residue; weighed by the damping's βω² its velocity inside the step booked three
/// times the ends' power: a truck on a damped free–free exact beam drifted by 1.2e-2,
/// 3e-7 with the velocities from the positions, which the accelerations do not enter.
struct BookedStep<'d> {
    dense: &'d dyn Dense,
    ends: (f64, f64),
    /// The step's end states, where the state is the positions then the velocities.
    states: Option<(Vec<f64>, Vec<f64>)>,
}

impl<'d> BookedStep<'d> {
    /// The step `ends` of `dense`, whose end state `span` has read as `y1`; where the
    /// integrator does not step over fast modes (`Ledger::steps_over_fast_modes`) its dense
    /// output as it is.
    fn new(
        phase: &Phase,
        ledger: &Ledger,
        ends: (f64, f64),
        y1: &[f64],
        dense: &'d dyn Dense,
    ) -> Self {
        let states = ledger
            .steps_over_fast_modes
            .then(|| (dense.at(ends.0), y1.to_vec()))
            .filter(|(y0, _)| y0.len() == 2 * phase.split(y0).0.len());
        BookedStep {
            dense,
            ends,
            states,
        }
    }

    fn at(&self, t: f64) -> Vec<f64> {
        let mut y = self.dense.at(t);
        let Some((y0, y1)) = &self.states else {
            return y;
        };
        let (t0, t1) = self.ends;
        let h = t1 - t0;
        // An event at the step's start leaves nothing inside it to read, and over a sliver
        // left between two breakpoints the positions' round-off over h swamps the velocity.
        if h <= SLIVER * t0.abs().max(t1.abs()) {
            return y;
        }
        let th = (t - t0) / h;
        let d00 = 6.0 * th * (th - 1.0) / h;
        let d10 = (3.0 * th - 1.0) * (th - 1.0);
        let d11 = th * (3.0 * th - 2.0);
        let m = y.len() / 2;
        for i in 0..m {
            y[m + i] = d00 * (y0[i] - y1[i]) + d10 * y0[m + i] + d11 * y1[m + i];
        }
        y
    }
}

/// A step as the watches and the rows read it while a wheel with a mass or a train's moving
/// mass rides the mesh, where the integrator steps over fast modes: the cubic Hermite through the ends' positions and velocities (the dense
/// output's positions), its derivative as the velocities ([`BookedStep`]), and as the
/// accelerations the derivative of the cubic Hermite through the ends' velocities and
/// accelerations. A wheel with a mass bears the deck's acceleration under it, into which the
/// problem, read at the dense output's states, carries every fast mode's residue amplified
/// by ω²: after a 510 kg wheel's impulse at a kink of its track, the step read a contact
/// force of 9.2·10⁵ N where it is 3.8·10⁴ N, and at sixteen steps an element the least
/// contact force 1.2 % high, within 10⁻⁵ read so.
pub(super) struct WatchedStep {
    ends: (f64, f64),
    /// y(t0), y(t1), y'(t0) and y'(t1).
    data: [Vec<f64>; 4],
}

impl WatchedStep {
    /// The step `ends` of `dense`, whose end state `span` has read as `y1`, where it is read
    /// so: a wheel with a mass or a moving mass on the mesh at either end (where the steps are
    /// held to a sixteenth of an element's crossing; after the loads leave, on the steps of the
    /// free vibration, the cubic's derivative misses a body's acceleration by (ωh)³), an
    /// integrator that steps over fast modes, a step longer than a sliver.
    fn new(
        phase: &Phase,
        ledger: &Ledger,
        (t0, t1): (f64, f64),
        y1: &[f64],
        dense: &dyn Dense,
    ) -> Option<Self> {
        let long = t1 - t0 > SLIVER * t0.abs().max(t1.abs());
        if !ledger.steps_over_fast_modes || !long {
            return None;
        }
        let y0 = match phase.vehicles {
            Some(v) => {
                let y0 = dense.at(t0);
                let on = |t: f64, y: &[f64]| v.mass_on_the_mesh(t, phase.split(y).0);
                (on(t0, &y0) || on(t1, y1)).then_some(y0)?
            }
            None => {
                let riding = |t: f64| !phase.loaded.riding(t).is_empty();
                let on = phase.loaded.modal.is_none() && (riding(t0) || riding(t1));
                on.then(|| dense.at(t0))?
            }
        };
        if y0.len() != 2 * phase.split(&y0).0.len() {
            return None;
        }
        Some(WatchedStep {
            ends: (t0, t1),
            data: [y0, y1.to_vec(), dense.rate(t0)?, dense.rate(t1)?],
        })
    }

    /// (y, y') at t, where t lies within the step.
    fn read(&self, t: f64) -> Option<(Vec<f64>, Vec<f64>)> {
        let (t0, t1) = self.ends;
        if !(t0..=t1).contains(&t) {
            return None;
        }
        let [y0, y1, r0, r1] = &self.data;
        let h = t1 - t0;
        let s = (t - t0) / h;
        let (h00, h10) = ((1.0 + 2.0 * s) * (1.0 - s).powi(2), s * (1.0 - s).powi(2));
        let (h01, h11) = (s * s * (3.0 - 2.0 * s), s * s * (s - 1.0));
        let d00 = 6.0 * s * (s - 1.0) / h;
        let d10 = (3.0 * s - 1.0) * (s - 1.0);
        let d11 = s * (3.0 * s - 2.0);
        let m = y0.len() / 2;
        let (mut y, mut r) = (vec![0.0; 2 * m], vec![0.0; 2 * m]);
        for i in 0..m {
            let (v0, v1) = (y0[m + i], y1[m + i]);
            y[i] = h00 * y0[i] + h * h10 * v0 + h01 * y1[i] + h * h11 * v1;
            y[m + i] = d00 * (y0[i] - y1[i]) + d10 * v0 + d11 * v1;
            r[i] = y[m + i];
            r[m + i] = d00 * (v0 - v1) + d10 * r0[m + i] + d11 * r1[m + i];
        }
        Some((y, r))
    }
}

/// The step the watches read: a [`WatchedStep`] where there is one, else the dense output.
struct Watched<'d> {
    step: Option<&'d WatchedStep>,
    dense: &'d dyn Dense,
}

impl Dense for Watched<'_> {
    fn at(&self, t: f64) -> Vec<f64> {
        match self.step.and_then(|s| s.read(t)) {
            Some((y, _)) => y,
            None => self.dense.at(t),
        }
    }

    fn rate(&self, t: f64) -> Option<Vec<f64>> {
        match self.step.and_then(|s| s.read(t)) {
            Some((_, r)) => Some(r),
            None => self.dense.rate(t),
        }
    }

    fn forms(&self, rows: &[FormRow]) -> Option<StepForms> {
        self.step
            .is_none()
            .then(|| self.dense.forms(rows))
            .flatten()
    }
}

/// Hands the recorder the reduced state (q, s; v, ṡ) of the literal thesis system.
pub(super) struct ThesisSystemObserver<'a, 's, 'c, 'r> {
    pub(super) sys: &'a ThesisSystem<'s, 'c>,
    pub(super) rec: &'a mut Recorder<'r>,
}

impl Observer for ThesisSystemObserver<'_, '_, '_, '_> {
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
    let contact_means = filter.as_ref().map(|f| {
        let rolling: Vec<Option<(f64, f64)>> = setup
            .disks
            .iter()
            .map(|d| (d.coupling == Coupling::Consistent).then_some((d.disk.mass, d.gravity)))
            .collect();
        ContactMeans::new(1.0 / f.cutoff_hz, 0.0, &rolling)
    });
    let probe_xs: Vec<f64> = setup.probes.iter().map(|p| p.x).collect();
    Recorder {
        ledger: Ledger::new(&phase, &setup.loads, y0),
        modal_probes: ModalProbes::new(phase.loaded, &probe_xs),
        probe_rows: std::cell::OnceCell::new(),
        filter,
        reactions: Reactions::new(),
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
        contact_means,
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
        deck_end: None,
        vehicles_end: None,
        grid_check: GridCheck::new(setup.accuracy),
        paces_long_steps: setup.load_switched(),
        before: None,
        restarted: false,
        trail: Vec::new(),
        along_trail: Vec::new(),
        spacing,
        outputs: outputs.to_vec(),
        last_row: None,
        exit_t,
        settled: false,
        station_rows: None,
        arrivals,
        kinks,
        squares: vec![(0.0, 0.0); setup.vehicles.iter().map(|v| v.bodies.len()).sum()],
        watched: None,
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
    /// Per body of every vehicle, the root mean square of its acceleration since it arrived;
    /// `None` where no step was booked (a run stopped within its first).
    pub(super) vehicle_rms: Vec<Option<f64>>,
}

impl Recorded {
    pub(super) fn from(mut rec: Recorder, y_end: &[f64]) -> Recorded {
        if let Some(p) = &rec.progress {
            p.finish();
        }
        let y_end = on_mesh(&rec.phase, y_end);
        if let Some(last) = rec.last_row.take() {
            rec.watches.see_row(&last);
            // The last step watched ends where the run stops short of a terminal event's
            // crossing, and the root mean squares cover the run to its end.
            if let Some(end) = rec.vehicles_end.take().filter(|e| e.t < last.t) {
                rec.add_squares((end.t, last.t), [&end.end, &last.vehicles], None);
            }
        }
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
                .map(|&(sq, time)| (time > 0.0).then(|| (sq / time).sqrt()))
                .collect(),
        }
    }
}

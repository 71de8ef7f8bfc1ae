//! The extremes watched over every step: a short step sampled on an even grid that checks its
//! own resolution and refines itself, a long one in pairs of sub-steps whose turning points are
//! refined on the solution, a riding disk at every step's end; each sample taken in with the two
//! before it, the parabola through the three.

use super::*;
use crate::ode::same_breakpoint;
use std::collections::VecDeque;

/// Samples of the extremes' watch a period of the acceleration's cutoff, where the steps are
/// shorter (see `Recorder::watch`).
pub(super) const SAMPLES_PER_CUTOFF_PERIOD: f64 = 32.0;

/// Samples of the watch, where the steps are shorter, to the time a disk takes to cross its
/// contact patch's half-width.
pub(super) const SAMPLES_PER_PATCH: f64 = 20.0;

/// The most samples the watch's grid may take while the loads still change: as many as the
/// default step budget allows steps, each sample costing about what a step does.
const MAX_GRID_SAMPLES: f64 = 1.0e7;

/// What the grid's samples may read in all: each reads the mesh's displacements, on a modal
/// beam from its modes (mesh unknowns times modes). A railway car with its cutoff given at
/// 100 kHz kept 200 modes on a 960-unknown mesh and would have read them 3.6·10⁶ times,
/// 7·10¹¹ products.
const MAX_GRID_READS: f64 = 1.0e11;

/// Refuses, before the run, a run whose deck acceleration the watch's grid would sample more
/// than [`MAX_GRID_SAMPLES`] times, or read more than [`MAX_GRID_READS`]. An exact step is as
/// long as the loads allow, so the step budget does not see a tiny time scale, and the grid
/// is watched all the same: a beam nearly massless puts EN 1991-2's cutoff at megahertz,
/// billions of samples over a train's passage (counted until the loads stop changing: what
/// follows can be strided over once it settles, `settled.rs`). A time-stepped run's long
/// steps are watched the same way while the loads move: 2 GN of moving masses crawling at
/// 1 mm/s over a 15 m deck asked for 1.4·10⁷ samples over 15 000 s. A cutoff the scene gives
/// is watched and booked in pieces of the grid's spacing over the whole run, and one given at
/// 10³⁰ Hz asked for the memory of 10¹⁶ pieces in one step.
pub(super) fn grid_within_budget(
    scene: &Scene,
    loaded: &LoadedBeam,
    filter: Option<&AccelerationFilter>,
    (exact, given): (bool, bool),
) -> Result<(), Error> {
    let Some(f) = filter else { return Ok(()) };
    let (watched, over) = if given && !exact {
        (scene.duration, "the run lasts")
    } else {
        let changing = (loaded.breakpoints().into_iter())
            .fold(0.0, f64::max)
            .min(scene.duration);
        (changing, "the loads move or switch")
    };
    let samples = watched * SAMPLES_PER_CUTOFF_PERIOD * f.cutoff_hz;
    let mesh = loaded.beam.dim();
    let (read, from) = match loaded.modal {
        Some(m) => (mesh * m.dim(), format!(" from {} modes", m.dim())),
        None => (mesh, String::new()),
    };
    let reads = samples * read as f64;
    if samples <= MAX_GRID_SAMPLES && reads <= MAX_GRID_READS {
        return Ok(());
    }
    let past = if samples > MAX_GRID_SAMPLES {
        format!("past the budget of {MAX_GRID_SAMPLES:.0e} samples")
    } else {
        format!("each reading the mesh's {mesh} unknowns{from}: {reads:.1e} products, past the budget of {MAX_GRID_READS:.0e}")
    };
    Err(Error::Solver(format!(
        "scene {}: the deck's acceleration, cut off at {:.3e} Hz ({}), would be watched at about {samples:.1e} samples over the {watched:.3e} s {over}, {past}: shorten the run, set `output.acceleration_cutoff_hz` lower, or look for a time scale the scene makes tiny (a near-zero mass or density, a huge stiffness)",
        scene.name, f.cutoff_hz, f.rule
    )))
}

/// Samples a pair of a long step's sub-steps spans: a quarter of the cutoff's period, over
/// which the parabola through its three points turns at most once where the filtered signal
/// does; the three samples around each junction of two pairs are read as a pair as well
/// (`watch_in_pairs`). Over the HSLM sweep the largest accelerations come within 3.3·10⁻⁵ of
/// those watched at eight times the samples, and within 4.2·10⁻⁶ at pairs half as long.
/// Without the junctions these pairs read them up to 4.2·10⁻⁴ low: HSLM-A9's at 45 m/s turns
/// 0.5 ms after an axle crosses a node, where the acceleration kinks, and neither pair's
/// parabola turns there.
const SAMPLES_A_PAIR: f64 = 8.0;

/// The most pairs of samples one long step is watched in (a bound on a step far longer than
/// the cutoff's period, which is then watched at this many points).
const MAX_STEP_PAIRS: f64 = 2048.0;

/// A parabola's turning value through samples of a vibration the grid resolves is off by
/// about a twenty-fifth of their fourth difference at most (a cosine at 16 to 32 samples a
/// period, its peak anywhere between them: 0.033–0.040); read as a share of the turning value,
/// the check's bound is half the accuracy.
const TURNING_ERROR_PER_FOURTH_DIFFERENCE: f64 = 0.04;

/// How many times the grid halves its spacing before the deck is watched in every step
/// instead: at 512 samples a period of the cutoff what is still not resolved is as fast as the
/// steps.
const MAX_GRID_REFINEMENTS: u32 = 4;

/// The probes' and the vehicles' bodies' accelerations at their last samples on the grid, by
/// which it checks its own premise (see `Recorder::check_the_grid`); and the measure of the
/// probes' w, φ and a by which a long step's samples check theirs (`watch_in_pairs`).
pub(super) struct GridCheck {
    samples: VecDeque<(f64, Vec<f64>)>,
    /// Each quantity's largest value sampled or turned at.
    largest: Vec<f64>,
    /// The same for the probes' w, φ and a a long step's samples check (`unresolved_within`).
    largest_in_steps: Vec<f64>,
    accuracy: f64,
    /// How many times the grid was refined.
    refined: u32,
    /// Whether the grid refined [`MAX_GRID_REFINEMENTS`] times still did not resolve the
    /// probes: from then on the deck is watched in every step.
    pub(super) broken: bool,
}

impl GridCheck {
    pub(super) fn new(accuracy: f64) -> Self {
        GridCheck {
            samples: VecDeque::new(),
            largest: Vec::new(),
            largest_in_steps: Vec::new(),
            accuracy,
            refined: 0,
            broken: false,
        }
    }

    /// Take the values `a` sampled at t. Where the last five samples are evenly spaced with
    /// nothing turning among them (`smooth`), the first quantity whose turning point the five
    /// say is read off by more than half the accuracy (see [`GridCheck::unresolved_in`]).
    fn unresolved(
        &mut self,
        t: f64,
        a: Vec<f64>,
        spacing: f64,
        smooth: impl Fn(f64) -> bool,
    ) -> Option<usize> {
        let on_grid = |tl: f64| ((t - tl) - spacing).abs() <= 1e-9 * spacing;
        if self.samples.back().is_some_and(|(tl, _)| !on_grid(*tl)) {
            self.samples.clear();
        }
        self.samples.push_back((t, a));
        if self.samples.len() > 5 {
            self.samples.pop_front();
        }
        if self.samples.len() < 5 || !smooth(self.samples[0].0) {
            let newest = &self.samples.back().expect("just taken").1;
            self.largest.resize(newest.len(), 0.0);
            for (l, v) in self.largest.iter_mut().zip(newest) {
                *l = l.max(v.abs());
            }
            return None;
        }
        let five: Vec<&[f64]> = self.samples.iter().map(|(_, v)| v.as_slice()).collect();
        let (largest, accuracy) = (&mut self.largest, self.accuracy);
        unresolved_in(&five, largest, accuracy)
    }

    /// Over evenly spaced samples of one smooth stretch (a long step's pairs), the first
    /// quantity some five consecutive of them say is read off by more than half the accuracy.
    fn unresolved_within(&mut self, samples: &[&[f64]]) -> Option<usize> {
        if samples.len() < 5 {
            return None;
        }
        let (largest, accuracy) = (&mut self.largest_in_steps, self.accuracy);
        samples.windows(5).fold(None, |found, five| {
            found.or(unresolved_in(five, largest, accuracy))
        })
    }
}

/// Over five evenly spaced samples, the first quantity whose turning point, found by the
/// parabola through the last three and large enough to be an extreme (half the `largest` seen,
/// which it updates), the five's fourth difference says is read off by more than half the
/// accuracy.
fn unresolved_in(five: &[&[f64]], largest: &mut Vec<f64>, accuracy: f64) -> Option<usize> {
    let v = |i: usize, q: usize| five[i][q];
    largest.resize(five[4].len(), 0.0);
    for (l, x) in largest.iter_mut().zip(five[4]) {
        *l = l.max(x.abs());
    }
    let mut unresolved = None;
    for (q, seen) in largest.iter_mut().enumerate() {
        let (a, b, c) = (v(2, q), v(3, q), v(4, q));
        let curvature = a - 2.0 * b + c;
        let turns_at = 0.5 * (a - c) / curvature;
        if !(turns_at.abs() <= 1.0) {
            continue;
        }
        let turning = b - 0.25 * (a - c) * turns_at;
        *seen = seen.max(turning.abs());
        if turning.abs() < 0.5 * *seen {
            continue;
        }
        let fourth = v(0, q) - 4.0 * v(1, q) + 6.0 * v(2, q) - 4.0 * v(3, q) + v(4, q);
        if TURNING_ERROR_PER_FOURTH_DIFFERENCE * fourth.abs() > 0.5 * accuracy * turning.abs() {
            unresolved = unresolved.or(Some(q));
        }
    }
    unresolved
}

/// What the watches take at the end of every step a disk rides: the probes' (u, w, φ, a) and
/// the disks' values as a [`Snapshot`] holds them.
pub(super) struct Trailed {
    t: f64,
    probes: Vec<f64>,
    disk: Vec<f64>,
}

/// Where the last step watched ended: its end, and its last middle's time and values, the
/// first of the three across the boundary to the next step.
pub(super) struct DeckEnd<E = Snapshot> {
    pub(super) t: f64,
    pub(super) end: E,
    middle: (f64, Vec<f64>),
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
            // No stations, no stretch or drawing in through them.
            along: Watch::new(
                if stations == 0 { 0 } else { 4 * stations + 2 },
                Turning::OnTheParabola,
            ),
        }
    }
}

impl Recorder<'_> {
    /// Add ∫ a² dt over [t0, t1] for each body, from its values at the ends (the trapezoidal
    /// rule) or at the ends and the middle (Simpson's).
    pub(super) fn add_squares(
        &mut self,
        t: (f64, f64),
        values: [&[f64]; 2],
        middle: Option<&[f64]>,
    ) {
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
    /// the turning points between them that set an extreme; the vehicles' values also at
    /// `crests` (`VehiclesOnBeam::crest_pace`) on a random road.
    pub(super) fn watch(
        &mut self,
        t0: f64,
        t1: f64,
        dense: &dyn Dense,
        sample: f64,
        crests: Option<f64>,
    ) {
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
            let in_steps = self.deck_watched_in_steps(t0, dense);
            self.sample_inside(t0, t1, dense, spacing, riding.is_some(), in_steps, crests);
        } else {
            self.watch_in_pairs(t0, t1, dense, spacing, crests);
        }
    }

    /// Sample the step [t0, t1] on the even grid of `spacing` that runs on from the last
    /// sample, with a disk `riding` on or over the beam taking in the step's end as well, and
    /// the deck watched in the step itself where `in_steps` says (riders with a mass on it, or
    /// the grid's premise broken).
    fn sample_inside(
        &mut self,
        t0: f64,
        t1: f64,
        dense: &dyn Dense,
        spacing: f64,
        riding: bool,
        in_steps: bool,
        crests: Option<f64>,
    ) {
        // After a jump the step's start is a sample: a force left at a support as a disk
        // leaves the beam is gone at once, and the deck's acceleration is largest just after.
        self.starts_after_a_jump(t0);
        let jumped = std::mem::take(&mut self.restarted);
        // The contact force rings at the frequencies of the disk on the beam's local
        // stiffness, above any cutoff: sampled less often than every step, D44's largest
        // (the disk meeting the beam at rest) came out 11 % low. The deck's accelerations
        // carry it (every mode is forced by it directly), so the envelope's stations are
        // taken at every step too: D50's largest acceleration read 2.4·10⁻³ low.
        if riding {
            self.trail_rider(t1, dense);
        }
        if in_steps {
            self.watch_the_deck_over(t0, t1, dense, spacing);
        }
        if self.phase.vehicles.is_some() {
            let times = pair_times(t0, t1, vehicles_pair(spacing, crests));
            let start = match &self.vehicles_end {
                Some(e) if e.t == t0 => e.end.clone(),
                _ => self.vehicles_seen(t0, dense),
            };
            let shots = std::iter::once(start)
                .chain(times[1..].iter().map(|&t| self.vehicles_seen(t, dense)))
                .collect();
            self.watch_the_vehicles(&times, shots, dense);
        }
        let trailed = riding || in_steps;
        // The samples keep an even spacing, taken inside the step where they fall.
        let first = match &self.last {
            Some((t, _)) => (t + spacing).max(t0),
            None if t1 - t0 < spacing && !jumped => t1,
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
            let end = self.snapshot(ts, &dense.at(ts), self.rate(dense, ts).as_deref(), !trailed);
            self.sampled(end, ts, trailed);
        }
    }

    /// Watch the long step [t0, t1] in pairs of sub-steps no longer than [`SAMPLES_A_PAIR`]
    /// samples of `spacing`, and book its bodies' squares and the trails the next step reads.
    fn watch_in_pairs(
        &mut self,
        t0: f64,
        t1: f64,
        dense: &dyn Dense,
        spacing: f64,
        crests: Option<f64>,
    ) {
        self.starts_after_a_jump(t0);
        self.restarted = false;
        let fresh = self.along_trail.is_empty();
        let last = self.last.take();
        let before = self
            .before
            .take()
            .filter(|(tb, _)| *tb < t0 && last.as_ref().is_some_and(|l| l.0 == t0));
        let mut w = std::mem::replace(&mut self.watches, Watches::new(0, 0, 0, 0));
        let mut check = std::mem::replace(&mut self.grid_check, GridCheck::new(0.0));
        let forms = self.probe_forms(dense);
        let correction = forms.as_ref().and_then(|_| self.probe_correction(t0, t1));
        let see = |t: f64, along: bool, vehicles: bool| {
            if let Some(forms) = &forms {
                return self.snapshot_of_forms(forms, correction.as_ref(), t);
            }
            let (y, rate) = (dense.at(t), self.rate(dense, t));
            if vehicles {
                self.snapshot(t, &y, rate.as_deref(), along)
            } else {
                self.deck_snapshot(t, &y, rate.as_deref(), along)
            }
        };
        let start = match last {
            Some((t, s)) if t == t0 => s,
            _ => see(t0, fresh, true),
        };
        // A long step is watched in pairs of sub-steps no longer than a sample, each pair's
        // turning points refined on the solution: on three points alone a step the exact
        // integration takes between two node crossings (two thirds of the cutoff's period on
        // HSLM's bridge) read HSLM-A1's largest acceleration at 114 m/s 4.3·10⁻³ low, and the
        // envelope's stations on its ends alone overshot the deck's by 3·10⁻³.
        // The vehicles' values inside the step are read at the deck's times unless they ask
        // for finer ones; the step's ends carry them on to the next step either way.
        let finer_for = |spacing: f64| {
            (self.phase.vehicles.is_some())
                .then(|| pair_times(t0, t1, vehicles_pair(SAMPLES_A_PAIR * spacing, crests)))
                .filter(|finer| finer.len() != pair_times(t0, t1, SAMPLES_A_PAIR * spacing).len())
        };
        let inside_for =
            |spacing: f64| self.phase.vehicles.is_some() && finer_for(spacing).is_none();
        let refined_before = check.refined;
        let mut spacing = spacing;
        let mut times = pair_times(t0, t1, SAMPLES_A_PAIR * spacing);
        let mut n = times.len() - 1;
        let mut shots = vec![start];
        let inside = inside_for(spacing);
        shots.extend(times[1..n].iter().map(|&tk| see(tk, true, inside)));
        shots.push(see(t1, true, true));
        // A switched load rings every mode the model keeps, and the probes' w and φ carry
        // them far above the cutoff: the pairs are halved, as the grid is, until the step's
        // samples resolve what they turn at. A 200 kN load switched on a deep 30 m concrete
        // span (67 modes kept, undamped) read midspan's least rotation 0.9 % of it short.
        // Moving loads set the kept modes ringing far less, and their deflections turn
        // where the loads pass, which no pace resolves: HSLM's sweep is not checked.
        while self.paces_long_steps && check.refined < MAX_GRID_REFINEMENTS && spacing > 0.0 {
            let paced: Vec<Vec<f64>> = shots.iter().map(Snapshot::paced).collect();
            let paced: Vec<&[f64]> = paced.iter().map(Vec::as_slice).collect();
            if check.unresolved_within(&paced).is_none() {
                break;
            }
            check.refined += 1;
            spacing *= 0.5;
            times = pair_times(t0, t1, SAMPLES_A_PAIR * spacing);
            n = times.len() - 1;
            let end = shots.pop().expect("the step's end");
            shots.truncate(1);
            let inside = inside_for(spacing);
            shots.extend(times[1..n].iter().map(|&tk| see(tk, true, inside)));
            shots.push(end);
        }
        let finer = finer_for(spacing);
        let inside = finer.is_none() && self.phase.vehicles.is_some();
        let after_exit = self.exit_t.is_some_and(|te| t0 >= te);
        for i in (0..n).step_by(2) {
            let steps = StepWatch {
                t: [times[i], times[i + 1], times[i + 2]],
                after_exit,
                flying: self.phase.flying.is_some(),
            };
            steps.record(&mut w, [&shots[i], &shots[i + 1], &shots[i + 2]], |tt| {
                see(tt, false, false)
            });
        }
        // The pairs overlapped at their junctions, the step's start included: a peak a
        // sub-step either side of a junction, where both pairs' largest sample is the shared
        // one and neither parabola turns, is refined on the solution. The step's start is a
        // node crossing, where the acceleration kinks; the earlier step's solution is no
        // longer at hand, so its side is read at t0.
        let junctions = before
            .iter()
            .map(|(tb, b)| {
                let s: [&[f64]; 3] = [&b.probes, &shots[0].probes, &shots[1].probes];
                ([*tb, t0, times[1]], s)
            })
            .chain((2..n).step_by(2).map(|i| {
                let s: [&[f64]; 3] = [&shots[i - 1].probes, &shots[i].probes, &shots[i + 1].probes];
                ([times[i - 1], times[i], times[i + 1]], s)
            }));
        for (t, s) in junctions {
            w.probes
                .record_step(t, s, |tt| see(tt.max(t0), false, false).probes);
        }
        self.watches = w;
        self.spacing *= 0.5_f64.powi((check.refined - refined_before) as i32);
        self.grid_check = check;
        if self.watch_along {
            if fresh {
                self.trail_along(t0, shots[0].along.clone());
            }
            for k in 1..=n {
                self.trail_along(times[k], shots[k].along.clone());
            }
        }
        self.vehicles_in_pairs(finer, inside, &times, &shots, dense);
        self.keep_the_pairs_end(&times, shots);
    }

    /// The vehicles' values over a step watched in pairs: at `finer` times where they ask for
    /// them (the step's ends read from its first and last samples), or on the pairs' samples
    /// where they are read `inside` them.
    fn vehicles_in_pairs(
        &mut self,
        finer: Option<Vec<f64>>,
        inside: bool,
        times: &[f64],
        shots: &[Snapshot],
        dense: &dyn Dense,
    ) {
        if let Some(finer) = finer {
            let last = finer.len() - 1;
            let values = finer
                .iter()
                .enumerate()
                .map(|(k, &t)| match k {
                    0 => shots[0].vehicles.clone(),
                    k if k == last => shots[shots.len() - 1].vehicles.clone(),
                    _ => self.vehicles_seen(t, dense),
                })
                .collect();
            self.watch_the_vehicles(&finer, values, dense);
        } else if inside {
            let values = shots.iter().map(|s| s.vehicles.clone()).collect();
            self.watch_the_vehicles(times, values, dense);
        }
    }

    /// What the next step starts from: the pairs' last sample, the one before it, and the
    /// disk's trail at the end.
    fn keep_the_pairs_end(&mut self, times: &[f64], mut shots: Vec<Snapshot>) {
        let n = times.len() - 1;
        let end = shots.pop().expect("the step's end");
        let before = shots.pop().expect("a sample before the end");
        self.trail = end
            .disk
            .clone()
            .map(|disk| Trailed {
                t: times[n],
                probes: end.probes.clone(),
                disk,
            })
            .into_iter()
            .collect();
        self.before = Some((times[n - 1], before));
        self.last = Some((times[n], end));
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

    /// Whether the deck is watched in every step from t: a vehicle's wheel or a moving mass is
    /// on it, or the grid found its premise broken.
    fn deck_watched_in_steps(&self, t: f64, dense: &dyn Dense) -> bool {
        self.grid_check.broken
            || !self.phase.loaded.riding(t).is_empty()
            || self.phase.vehicles.is_some_and(|v| {
                let y = dense.at(t);
                v.load_passage(t, self.phase.split(&y).0).is_some()
            })
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

    /// Whether the step from t0 starts where the loads may jump (an axle entering or leaving
    /// over a free end, a load switched), the last sample taken there: that sample holds the
    /// loads before, and the step starts from those after. The watches then start afresh
    /// from the step's own start. Taking the sample before for the start, HSLM-A1 on a 15 m
    /// cantilever at 30 m/s read the tip's largest acceleration 1.2 % low (each axle leaving
    /// the tip lifts it from 11.6 to 20.5 m/s² at once), and joined across the jump
    /// generalized-α's samples read it 4.7 % high.
    fn starts_after_a_jump(&mut self, t0: f64) -> bool {
        let jumped = self.last.as_ref().is_some_and(|(t, _)| *t == t0) && self.turns_at(t0);
        if jumped {
            self.restart();
        }
        jumped
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

    /// Watch the deck over the step [t0, t1] while a vehicle's wheel or a moving mass is on it,
    /// in pairs of sub-steps no longer than a sample of `spacing`: the probes at each pair's
    /// start, middle and end, their turning points refined on the solution, and the envelope's
    /// stations at the pairs' ends. The grid reads a turning point off the parabola through
    /// its samples, on the premise that the filtered signal holds nothing faster than the
    /// cutoff's or the passage's pace; what rides on the deck with a mass or a damper breaks
    /// it, coupling the modes kept to those left out, whose pace the steps follow. A railcar's
    /// wheel nearing a 15 m cantilever's tip rings midspan at about 125 Hz, four times the
    /// cutoff: on the grid its largest acceleration read 3.9·10⁻³ low; moving masses of the
    /// same axles, 7.5·10⁻³ high.
    fn watch_the_deck_over(&mut self, t0: f64, t1: f64, dense: &dyn Dense, spacing: f64) {
        let times = pair_times(t0, t1, spacing);
        let n = times.len() - 1;
        let mut probes = std::mem::replace(
            &mut self.watches.probes,
            Watch::new(0, Turning::OnTheSolution),
        );
        let end_before = self.deck_end.take();
        let see = |t: f64, along: bool| {
            self.deck_snapshot(t, &dense.at(t), self.rate(dense, t).as_deref(), along)
        };
        let (start, before) = match end_before {
            Some(d) if d.t == t0 => (d.end, Some(d.middle)),
            _ => (see(t0, true), None),
        };
        let fresh = before.is_none();
        let mut shots = vec![start];
        shots.extend((1..=n).map(|k| see(times[k], k % 2 == 0)));
        // A turning point between the last middle before t0 and the first after it: on this
        // side refined on the solution, on the other, whose solution is no longer at hand,
        // read off the parabola through the three near t0 (`before_the_junction`). Left out,
        // a peak near a step's end that neither step's parabola turns at reads as the larger
        // end: the railcar over a 15 m cantilever, midspan's largest acceleration 2.1·10⁻⁴ low
        // (9.4·10⁻⁵ so).
        if let Some((tb, b)) = &before {
            let t = [*tb, t0, times[1]];
            let s: [&[f64]; 3] = [b, &shots[0].probes, &shots[1].probes];
            probes.record_step(t, s, |tt| {
                if tt >= t0 {
                    see(tt, false).probes
                } else {
                    before_the_junction(t, s, tt)
                }
            });
        }
        for i in (0..n).step_by(2) {
            let t = [times[i], times[i + 1], times[i + 2]];
            let s: [&[f64]; 3] = [&shots[i].probes, &shots[i + 1].probes, &shots[i + 2].probes];
            probes.record_step(t, s, |tt| see(tt, false).probes);
        }
        self.watches.probes = probes;
        if self.watch_along {
            for k in (0..=n).step_by(2).filter(|&k| k > 0 || fresh) {
                if self.trails_after(times[k]) {
                    self.trail_along(times[k], std::mem::take(&mut shots[k].along));
                }
            }
        }
        let end = shots.pop().expect("the step's end");
        let middle = shots.pop().expect("a middle before the end").probes;
        self.deck_end = Some(DeckEnd {
            t: t1,
            end,
            middle: (times[n - 1], middle),
        });
    }

    /// The vehicles' values (each body's acceleration, each wheel's contact force) at t, of
    /// the model's accelerations at the interpolated state: generalized-α's own acceleration
    /// lags the motion by a share of its step, and where a bogie's acceleration rose steeply
    /// to a wheel's lift-off (a railway car at 1000 m/s) it read the peak 2.3·10⁻³ high.
    fn vehicles_seen(&self, t: f64, dense: &dyn Dense) -> Vec<f64> {
        let seen = self
            .phase
            .vehicles_at_rate(t, &dense.at(t), self.rate(dense, t).as_deref());
        self.vehicle_values(t, seen.as_ref())
    }

    /// Take in the vehicles' values `shots` at `times`, a step cut into pairs of sub-steps
    /// (ends at the even entries, middles at the odd): each pair's turning points refined on
    /// the solution, and its bodies' squares by Simpson's rule. The vehicles are watched in
    /// every step, whatever the deck's pace: on the deck's grid of samples a railway car at
    /// 1000 m/s read its front bogie's largest acceleration 5.8·10⁻³ low (a peak between the
    /// last sample and a wheel's kink, where no parabola is drawn through the samples), and
    /// its rear bogie's root mean square 10 % high (the trapezoidal rule over the steep rise
    /// of its last tenth of a millisecond, up to a wheel's lift-off).
    fn watch_the_vehicles(&mut self, times: &[f64], shots: Vec<Vec<f64>>, dense: &dyn Dense) {
        let n = times.len() - 1;
        let t0 = times[0];
        let end_before = self.vehicles_end.take();
        let mut w = std::mem::replace(
            &mut self.watches.vehicles,
            Watch::new(0, Turning::OnTheSolution),
        );
        let see = |t: f64| self.vehicles_seen(t, dense);
        let mut squares: Vec<((f64, f64), [&[f64]; 2], Option<&[f64]>)> = Vec::new();
        match &end_before {
            // A turning point between the last middle before t0 and the first after it, as
            // the deck's (`watch_the_deck_over`).
            Some(e) if e.t == t0 => {
                let t = [e.middle.0, t0, times[1]];
                let s: [&[f64]; 3] = [&e.middle.1, &shots[0], &shots[1]];
                w.record_step(t, s, |tt| {
                    if tt >= t0 {
                        see(tt)
                    } else {
                        before_the_junction(t, s, tt)
                    }
                });
            }
            Some(e) if e.t < t0 => squares.push(((e.t, t0), [&e.end, &shots[0]], None)),
            _ => {}
        }
        for i in (0..n).step_by(2) {
            let t = [times[i], times[i + 1], times[i + 2]];
            let s: [&[f64]; 3] = [&shots[i], &shots[i + 1], &shots[i + 2]];
            w.record_step(t, s, see);
            squares.push(((t[0], t[2]), [s[0], s[2]], Some(s[1])));
        }
        self.watches.vehicles = w;
        for (t, ends, middle) in squares {
            self.add_squares(t, ends, middle);
        }
        let mut shots = shots;
        let end = shots.pop().expect("the step's end");
        let middle = shots.pop().expect("a middle before the end");
        self.vehicles_end = Some(DeckEnd {
            t: times[n],
            end,
            middle: (times[n - 1], middle),
        });
    }

    /// Whether the envelope's stations were last sampled before t.
    fn trails_after(&self, t: f64) -> bool {
        self.along_trail.last().is_none_or(|(tl, _)| *tl < t)
    }

    /// The run goes on from a state that jumped (a wheel landed, or its law changed as it
    /// lifted off) or under loads that jumped (a disk left the beam, its whole contact force
    /// gone at once): the steps before it are not joined to those after. Joined, the parabola
    /// through samples either side of a disk dropping off a cantilever's free end read the
    /// tip's largest acceleration 12 % above any the solution reaches.
    pub(super) fn restart(&mut self) {
        self.restarted = true;
        self.last = None;
        self.before = None;
        self.trail.clear();
        self.along_trail.clear();
        self.deck_end = None;
        self.vehicles_end = None;
    }

    /// Take the probes' and the vehicles' bodies' accelerations sampled at t into the grid's
    /// check of its premise: that they hold nothing faster than the grid's pace, so that the
    /// parabola through three samples finds their turning points, and Simpson's rule over the
    /// vehicles' pairs of sub-steps, no longer than a sample, their root mean square. Nonlinearity breaks it: an exact beam swinging ±1 m
    /// under two 10 t moving masses rings at about 300 Hz after they leave (a 31 Hz cutoff), and
    /// the grid read midspan's largest acceleration 1.4 % low. So do hubs on stiff tyres (400 kg
    /// on 10⁸ N/m over D44's section): one's largest acceleration read 2.0·10⁻³ low. Of the
    /// steel studies' sudden loads, whose largest accelerations the grid reads within 1.8·10⁻⁴
    /// of those watched in every step, B3 and C3 pass the bound late in their runs, and refine
    /// at no cost.
    fn check_the_grid(&mut self, t: f64, sample: &Snapshot) {
        if self.grid_check.broken {
            return;
        }
        let deck = sample.probes.len() / 4;
        let bodies = self.body_slots().into_iter().map(|s| sample.vehicles[s]);
        let a = sample
            .probes
            .iter()
            .skip(3)
            .step_by(4)
            .copied()
            .chain(bodies)
            .collect();
        let kinks = &self.kinks;
        let smooth = |from: f64| {
            let next = kinks.partition_point(|&k| k < from);
            kinks.get(next).is_none_or(|&k| k > t)
        };
        let Some(q) = self.grid_check.unresolved(t, a, self.spacing, smooth) else {
            return;
        };
        let check = &mut self.grid_check;
        check.samples.clear();
        if check.refined < MAX_GRID_REFINEMENTS {
            check.refined += 1;
            self.spacing *= 0.5;
        } else if q < deck {
            check.broken = true;
            // Without vehicles the grid now serves only what the steps' watch leaves to it
            // (the residual deflection), which it resolves at its own pace.
            if self.phase.vehicles.is_none() {
                self.spacing *= 2f64.powi(MAX_GRID_REFINEMENTS as i32);
            }
        }
    }

    /// Take in a sample at t of the beam alone, on its own (a short step's end): with the
    /// two before it, the parabola through the three. The probes are left out where the
    /// rider's trail has taken them (`trailed`).
    pub(super) fn sampled(&mut self, end: Snapshot, t: f64, trailed: bool) {
        if self.spacing > 0.0 {
            self.check_the_grid(t, &end);
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

/// Before a junction of two steps, where the earlier step's solution is no longer at hand:
/// the parabola through the values `v` at the three times `t` (the junction `t[1]`), at `at`,
/// for each quantity, within one later spacing `t[2] − t[1]` of the junction; NaN, no value,
/// farther back. The parabola stands for the solution only near its closely spaced samples: a
/// step cut short by an event puts them 36 µs apart after the junction and 0.78 ms before it,
/// and where a disk wheel's contact force rose steeply to a crest (191, 340, 417 kN) the
/// parabola turned 0.43 ms back at −107 kN, where the solution bore 200 kN; the earlier step's
/// own samples watched that stretch on its solution.
fn before_the_junction(t: [f64; 3], v: [&[f64]; 3], at: f64) -> Vec<f64> {
    if t[1] - at > t[2] - t[1] {
        return vec![f64::NAN; v[0].len()];
    }
    let l =
        |i: usize, j: usize, k: usize| (at - t[j]) * (at - t[k]) / ((t[i] - t[j]) * (t[i] - t[k]));
    let (l0, l1, l2) = (l(0, 1, 2), l(1, 0, 2), l(2, 0, 1));
    (0..v[0].len())
        .map(|q| l0 * v[0][q] + l1 * v[1][q] + l2 * v[2][q])
        .collect()
}

/// The longest pair of sub-steps the vehicles' values are watched in: the deck's `longest`,
/// and on a random road two of the `crests` pace. A wheel's contact force turns as fast as the
/// crests pass under it, and a landing restarts the watch at a force still rising: in the
/// deck's pairs alone a 500 kg axle's disk at 50 m/s over ISO class B waves of 0.2 m read its
/// largest force 7.5·10⁻³ low, the peak 58 µs past a landing.
fn vehicles_pair(longest: f64, crests: Option<f64>) -> f64 {
    match crests {
        Some(pace) if longest > 0.0 => longest.min(2.0 * pace),
        Some(pace) => 2.0 * pace,
        None => longest,
    }
}

/// The times that cut [t0, t1] into pairs of equal sub-steps, each pair no longer than
/// `longest` (one pair where `longest` is not positive), at most [`MAX_STEP_PAIRS`] of them:
/// the pairs' ends at the even entries, their middles at the odd.
fn pair_times(t0: f64, t1: f64, longest: f64) -> Vec<f64> {
    let pairs = if longest > 0.0 {
        ((t1 - t0) / longest).ceil().clamp(1.0, MAX_STEP_PAIRS) as usize
    } else {
        1
    };
    let n = 2 * pairs;
    (0..=n)
        .map(|k| {
            if k == n {
                t1
            } else {
                t0 + (t1 - t0) * k as f64 / n as f64
            }
        })
        .collect()
}

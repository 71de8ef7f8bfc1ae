//! What a beam run hands back: the run's rows, envelopes and extremes, and what it warns of
//! beyond the accuracy asked.

use super::acceleration::CutoffReport;
use super::vehicles::VehicleReport;
use crate::analysis::model_choice::SHARE;
use crate::beam::damping::Rayleigh;
use crate::beam::load::BeamStart;
use crate::beam::{Beam, PointDisplacement};
use crate::coupling::vehicles::VehicleObservation;
use crate::disk::DiskObservation;
use crate::run::extremes::Range;
use crate::run::{FlightRecord, RunHeader};
use crate::scene::BeamScene;
use std::sync::Arc;

#[derive(Clone, Debug)]
pub struct Frame {
    pub t: f64,
    pub along: Vec<PointDisplacement>,
    /// Per disk, while it is on or over the beam: its contact point s (in flight, the nearest
    /// point), the angle it has turned through, and its gap to the beam (0 while it rolls).
    pub disks: Vec<Option<(f64, f64, f64)>>,
    /// Where every vehicle's every wheel is along the beam (on the deck or off it).
    pub wheels: Vec<f64>,
}

#[derive(Clone, Debug)]
pub struct BeamRow {
    pub t: f64,
    /// One per probe, in the scene's order.
    pub probes: Vec<PointDisplacement>,
    /// Each disk, while it is on or over the beam (`None` once it has left; empty without
    /// disks, or once they have all left).
    pub disks: Vec<Option<DiskObservation>>,
    /// Deflection w of the beam under each disk (NaN while it is not on the beam).
    pub w_under: Vec<f64>,
    pub kinetic: f64,
    pub strain: f64,
    /// The disk's gravity potential (zero without a disk in the system).
    pub potential: f64,
    pub work: f64,
    /// What damping has taken since the start.
    pub dissipated: f64,
    /// What the disk's landings have taken since the start.
    pub impact: f64,
    /// The flying disk's gap to the beam (0 while it rolls).
    pub gap: f64,
    /// Which disk flies, while one does.
    pub flying: Option<usize>,
    /// One per probe: the vertical (global Y) acceleration, with the modes above the cutoff
    /// left out (see [`AccelerationFilter`](super::acceleration::AccelerationFilter)).
    pub accelerations: Vec<f64>,
    /// What the supports exert on the beam, global (fx, fy, mz), at `from` and at `to`.
    pub reactions: [[f64; 3]; 2],
    /// The vehicles, where the scene has them.
    pub vehicles: Option<VehicleObservation>,
}

impl BeamRow {
    /// The first disk (the disk, where it is alone) while it is on or over the beam.
    pub fn disk(&self) -> Option<DiskObservation> {
        self.disks.first().copied().flatten()
    }

    /// The deflection under the first disk (NaN while it is not on the beam).
    pub fn w_under_disk(&self) -> f64 {
        self.w_under.first().copied().unwrap_or(f64::NAN)
    }

    pub fn total(&self) -> f64 {
        self.kinetic + self.strain + self.potential - self.work + self.dissipated + self.impact
    }
}

/// Min and max over time of u, w and φ at each sample point.
#[derive(Clone, Debug)]
pub struct Envelope {
    pub x: Vec<f64>,
    pub min: Vec<PointDisplacement>,
    pub max: Vec<PointDisplacement>,
    /// The largest length the deformed axis reached minus L, in the beam's own measure of
    /// strain (`sensors::stretch`).
    pub stretch_max: f64,
    /// On a linear or modal beam with an end that may slide, the most that end would draw in
    /// as the axis bends (½ ∫ w'² dx, second order), which its u leaves out; else 0.
    pub draw_in_max: f64,
    /// The largest vertical acceleration over the sample points (filtered as the probes'),
    /// with where and when: (|a|, x, t).
    pub a_max: (f64, f64, f64),
}

pub struct BeamRun {
    pub header: RunHeader,
    pub setup: BeamScene,
    pub beam: Arc<Beam>,
    pub rows: Vec<BeamRow>,
    pub envelope: Envelope,
    /// Displacements at the sample points at each requested shape time.
    pub shapes: Vec<(f64, Vec<PointDisplacement>)>,
    /// Displacements at the sample points on a coarse grid of times (at most
    /// [`FRAMES`](super::FRAMES)), with the disk's contact point and turned angle while it is
    /// on the beam: the animation. Empty unless
    /// [`Overrides::animate`](crate::run::Overrides::animate) asked for them.
    pub frames: Vec<Frame>,
    /// Each probe's Hann-windowed mean deflection over [`MEAN_WINDOWS`](super::MEAN_WINDOWS)
    /// equal windows of the run, probe-major, for the windows the run covered whole: a
    /// headline the fast modes' phase leaves alone. Empty unless
    /// [`Overrides::windowed_means`](crate::run::Overrides::windowed_means) asked for them.
    pub windowed_means: Vec<f64>,
    /// The extremes of what the run reports, located on the solution.
    pub extremes: Extremes,
    /// When the last disk left the beam, if it did.
    pub left_track_t: Option<f64>,
    /// When each disk left the beam, if it did.
    pub disks_left_t: Vec<Option<f64>>,
    /// The disk (in the scene's order) whose event stopped the run: it lost contact, slipped
    /// or no longer fitted.
    pub stopped_disk: Option<usize>,
    /// The disk's flights over the beam.
    pub flights: Vec<FlightRecord>,
    /// (q, v) at the end of the run.
    pub y_end: Vec<f64>,
    /// What the recorded accelerations count.
    pub acceleration: Option<CutoffReport>,
    /// The Rayleigh damping the run had, α and β resolved.
    pub damping: Option<Rayleigh>,
    /// Each vehicle's extremes, in the scene's order.
    pub vehicles: Vec<VehicleReport>,
}

/// The extremes over the run of what the summary reports, each located on the solution
/// ([`crate::run::extremes`]).
#[derive(Clone, Debug, Default)]
pub struct Extremes {
    /// Per probe: u, w, φ and the vertical acceleration (filtered as recorded).
    pub probes: Vec<[Range; 4]>,
    /// Per probe: w after the last load left the beam (the disk, or a train's last axle).
    pub after_exit: Option<Vec<Range>>,
    /// Per disk, its normal and tangential contact force, the friction coefficient its
    /// rolling needs and the deflection under it, while it is on or over the beam (`None`
    /// for a disk never watched there).
    pub disks: Vec<Option<[Range; 4]>>,
    /// Per vehicle, each body's vertical acceleration then each axle's contact force, from
    /// the time the vehicle came onto the deck.
    pub vehicles: Vec<Range>,
    /// Per disk, its normal and tangential contact force averaged over a period of the
    /// acceleration's cutoff ([`contact_mean`](super::contact_mean)) and the friction coefficient those need, for
    /// the consistent coupling on the beam a whole window (`None` otherwise; empty without a
    /// cutoff).
    pub contact_means: Vec<Option<[Range; 3]>>,
}

impl Extremes {
    /// The first disk's (the disk's, where it is alone), if it was watched on the beam.
    pub fn disk(&self) -> Option<[Range; 4]> {
        self.disks.first().copied().flatten()
    }
}

/// The mean strain of the axis past which a run says its numbers are the model's, not a
/// material's: the beam's law is linear in its strains, and at a stretch of a tenth a
/// neo-Hookean solid in tension, (E/3)(λ − λ⁻²), lies 9 % below it. The rubber study stretches
/// its axis by 1.6 %; two 5 MN moving masses over D44's section by 380 %.
const SMALL_STRAIN: f64 = 0.1;

/// The energy drift (relative to the largest energy the run held) past which a run warns:
/// the studies drift by 1.8·10⁻³ at most (C2's generalized-α at its rtol of 10⁻⁴, its
/// numerical damping of the modes its steps pass over).
const DRIFT_WARNED: f64 = 1e-2;

impl BeamRun {
    /// Half the range of w at probe k after the last load left the beam: the residual
    /// vibration. `None` without an exit, or with nothing of the run after it.
    pub fn amplitude_after_exit(&self, k: usize) -> Option<f64> {
        self.extremes.after_exit.as_ref()?.get(k)?.half_range()
    }

    /// What the results depend on beyond the accuracy asked: the scene's (`BeamScene::warnings`)
    /// and what the run itself met.
    pub fn warnings(&self) -> Vec<String> {
        let mut out = self.setup.warnings();
        out.extend(self.setup.disks_meeting(self.header.t_end));
        if let [first, _, ..] = &self.flights[..] {
            let who = if self.setup.disks.len() > 1 {
                "the disks"
            } else {
                "the disk"
            };
            out.push(format!(
                "{who} lifted off the beam {} times: each landing's time and impulse, and the motion after it, carry the error of every step before it, so the extremes from the first lift-off at t = {:.6} s on are not held to the accuracy (a 5 t disk hopping on the HSLM bridge under A1: 15 flights at the defaults against 16 at rtol 1e-8, the deck's largest acceleration 7.7 % apart)",
                self.flights.len(),
                first.lift_off_t
            ));
        }
        out.extend(self.suspensions_outrun());
        out.extend(self.wheels_pulling());
        out.extend(self.wheels_landing());
        out.extend(self.wheels_set_down());
        out.extend(self.wheel_forces_outswing_the_correction());
        out.extend(self.nonlinearity_outgrown());
        out.extend(self.ends_drawn_in());
        out.extend(self.strained_past_small_strains());
        out.extend(self.energy_unbalanced());
        if let Some(c) = self.acceleration.as_ref().filter(|c| c.below > c.modes) {
            out.push(format!(
                "the modal beam keeps {} modes, fewer than the {} at or below the deck acceleration's cutoff ({:.2} Hz): the accelerations leave the others out; `track.beam.modes: {}` or more counts them all",
                c.modes, c.below, c.cutoff_hz, c.below
            ));
        }
        out
    }

    /// Where the plan chose a linear or modal beam from the exact beam's static gap g at a
    /// static deflection s, and the response grew to W at the probes: about how far the exact
    /// beam's would lie from it, of it, g (W/s)³. The static gap grows as the square of the
    /// amplitude, and a resonant build-up amplifies it as much again as it amplified the
    /// response: over HSLM's bridge (s = 1.56 mm under one axle, g = 4.4·10⁻⁸) it foresees
    /// 3·10⁻⁶, 9·10⁻⁵ and 1.1·10⁻³ for A1 at 60 m/s, A10 at 67 and A7 at 120, where the exact
    /// beam lies 2.2·10⁻⁶, 1.2·10⁻⁴ and 8.3·10⁻⁴ from the linear one in deflection (7.6·10⁻⁶,
    /// 1.6·10⁻⁴ and 9.9·10⁻⁴ in acceleration).
    pub fn nonlinear_gap_foreseen(&self) -> Option<f64> {
        self.growth().map(|(ratio, g)| g * ratio.powi(3))
    }

    /// W/s and g of [`Self::nonlinear_gap_foreseen`].
    fn growth(&self) -> Option<(f64, f64)> {
        let (s, g) = self.setup.static_gap?;
        let peak = (self.extremes.probes.iter())
            .map(|p| p[1].min.abs().max(p[1].max.abs()))
            .filter(|w| w.is_finite())
            .fold(0.0_f64, f64::max);
        (s > 0.0 && peak > 0.0).then_some((peak / s, g))
    }

    /// A warning where [`Self::nonlinear_gap_foreseen`] passes the share of the accuracy the
    /// plan chose the model by.
    fn nonlinearity_outgrown(&self) -> Option<String> {
        let (ratio, g) = self.growth()?;
        let gap = g * ratio.powi(3);
        let accuracy = self.setup.accuracy;
        (gap > SHARE * accuracy).then(|| format!(
            "the response grew to {ratio:.1} times the static deflection the plan judged the {} beam by: the geometric nonlinearity it leaves out grows about as the cube of that, here to some {gap:.1e} of the response, past a quarter of the accuracy {accuracy:e} (HSLM's bridge at A7's resonance: 1.1e-3 foreseen, the exact beam 8.3e-4 off in deflection, 9.9e-4 in acceleration); `track.beam.model: exact` holds it",
            self.setup.beam.model.name()
        ))
    }

    /// A warning where a linear or modal beam's sliding end would draw in by more than the
    /// share of the accuracy of the largest deflection the plan chooses a model by: its u, the
    /// linear one, leaves that out (HSLM-A1 at 90 m/s: 0.27 mm of a 41 mm peak, where the
    /// exact beam's roller moves 0.27 mm).
    fn ends_drawn_in(&self) -> Option<String> {
        let e = &self.envelope;
        let peak = (e.min.iter().chain(&e.max))
            .map(|d| d.w.abs())
            .fold(0.0_f64, f64::max);
        let (draw_in, accuracy) = (e.draw_in_max, self.setup.accuracy);
        (draw_in > SHARE * accuracy * peak).then(|| format!(
            "as the {} beam bends, the end that may slide would draw in by up to {draw_in:.2e} m ({:.1e} of the largest deflection, past a quarter of the accuracy {accuracy:e}), a second-order motion its u leaves out; `track.beam.model: exact` holds it",
            self.setup.beam.model.name(),
            draw_in / peak
        ))
    }

    /// A warning where the axis grew by more than [`SMALL_STRAIN`] of its length.
    fn strained_past_small_strains(&self) -> Option<String> {
        let ([x0, y0], [x1, y1]) = (self.setup.beam.from, self.setup.beam.to);
        let strain = self.envelope.stretch_max / (x1 - x0).hypot(y1 - y0);
        (strain > SMALL_STRAIN).then(|| format!(
            "the beam's axis grew to {:.3} times its length: the Reissner beam's law is linear in its strains (E and G constant), a law for small strains, and past a tenth a neo-Hookean solid's stress in tension lies 9 % below it, so the numbers this run reports are the model's, not a material's",
            1.0 + strain
        ))
    }

    /// A warning where the energy balance drifts past [`DRIFT_WARNED`].
    fn energy_unbalanced(&self) -> Option<String> {
        let drift = self.header.energy.max_rel_drift();
        (drift > DRIFT_WARNED).then(|| format!(
            "the energy balance drifts by {drift:.2e} of the largest energy the run held (past {DRIFT_WARNED:e}): the steps do not resolve the motion, and every number the run reports may be off by as much (the cantilever C2 over 1 s with `solver.atol: 0.5`, past any deflection it makes, drifts by 0.68 and reads its tip's deepest deflection 45 % too deep); a run at a hundredth of `solver.rtol`, with `solver.atol` left out for the plan to choose, shows which numbers move"
        ))
    }

    /// A warning for each vehicle whose wheels with a mass of their own read a contact force's
    /// extreme at t = 0, where they are set down on the beam at rest: a sudden load. At that
    /// instant the deck under a wheel gives way and takes part of its weight on the unsprung
    /// mass's inertia, a share set by how finely the model resolves the contact patch. A 10 t
    /// car on two 1 t wheels, the front one set at the support of a 20 m steel beam of 1.4 t:
    /// its least contact force 13 373, 4 433, 2 599 and 2 363 N on 16, 32 (the plan's), 64 and
    /// 128 exact elements, of a static 58.9 kN; started static, 25 335, 25 351 and 25 349 N on
    /// 16, 32 and 128, later in the run.
    fn wheels_set_down(&self) -> Vec<String> {
        if self.setup.start != BeamStart::Rest {
            return Vec::new();
        }
        (self.setup.vehicles.iter().zip(&self.vehicles))
            .filter_map(|(v, report)| {
                let wheels: Vec<&str> = (v.axles.iter().zip(&report.axles))
                    .filter(|(axle, (_, r))| {
                        axle.mass > 0.0
                            && (r.min_t <= 0.0 || r.max_t <= 0.0)
                            && self.setup.touches_the_deck_at_the_start(v, axle)
                    })
                    .map(|(_, (name, _))| name.as_str())
                    .collect();
                (!wheels.is_empty()).then(|| format!(
                    "vehicle {}'s wheel{} {} read{} an extreme of the contact force at t = 0, where the vehicle is set down on the beam at rest (`track.beam.initial: rest`), a sudden load: the deck under a wheel with a mass of its own gives way and takes part of its weight on that mass's inertia, a share that depends on how finely the mesh or the modes resolve the contact patch (a 10 t car on two 1 t wheels set at the support of a 20 m steel beam of 1.4 t: the least contact force 13 373 / 4 433 / 2 599 / 2 363 N on 16 / 32 / 64 / 128 elements); `initial: static` starts the beam carrying the vehicles",
                    v.name,
                    if wheels.len() > 1 { "s" } else { "" },
                    wheels.join(", "),
                    if wheels.len() > 1 { "" } else { "s" },
                ))
            })
            .collect()
    }

    /// A warning for each vehicle whose wheels landed: a plastic landing brings the wheel's mass
    /// to the deck's motion at once, and the contact force and the deck's acceleration just
    /// after it are an impact's, which grow the finer the steps and the mesh resolve it. Two
    /// 510 kg disk wheels landing past a 5 mm ramp's crest on a soft 30 m deck: the largest
    /// contact force 30.2, 34.0 and 48.5 MN, the deck's largest acceleration 5.3·10⁴, 5.9·10⁴
    /// and 8.5·10⁴ m/s² at accuracy 10⁻³, 10⁻⁵ and 10⁻⁶, where the landings' times hold within
    /// 2·10⁻⁶ s and the body's acceleration within 10⁻⁵.
    fn wheels_landing(&self) -> Vec<String> {
        self.vehicles
            .iter()
            .filter_map(|v| {
                let landed: Vec<(&str, Vec<f64>)> = (v.axles.iter().zip(&v.flights))
                    .map(|((axle, _), f)| (axle.as_str(), f.iter().filter_map(|f| f.land_t).collect()))
                    .filter(|(_, lands): &(&str, Vec<f64>)| !lands.is_empty())
                    .collect();
                let first = landed.iter().flat_map(|(_, l)| l).copied().reduce(f64::min)?;
                let count: usize = landed.iter().map(|(_, l)| l.len()).sum();
                let names: Vec<&str> = landed.iter().map(|(name, _)| *name).collect();
                Some(format!(
                    "vehicle {}'s wheel{} {} landed {count} time{} from t = {first:.6} s on: each landing is plastic, the wheel's mass meeting the deck at once, and the contact force and the deck's acceleration just after it are an impact's, set by how finely the steps and the mesh resolve it, not by the accuracy (two 510 kg disk wheels landing past a 5 mm ramp's crest on a soft 30 m deck: the largest contact force 30.2 / 34.0 / 48.5 MN, the deck's largest acceleration 5.3e4 / 5.9e4 / 8.5e4 m/s² at accuracy 1e-3 / 1e-5 / 1e-6, the landings' times within 2e-6 s, the body's acceleration within 1e-5); the energy each landing took is in `energy.impact`",
                    v.name,
                    if names.len() > 1 { "s" } else { "" },
                    names.join(", "),
                    if count > 1 { "s" } else { "" },
                ))
            })
            .collect()
    }

    /// A warning for each wheel whose contact force the watch saw below zero: it fell to zero
    /// and rose again between two of the times the run looks for a lift-off (the steps' ends,
    /// and on a random road its event pace), and the lift-off was stepped over. A disk wheel
    /// pivoting over a crest its radius cannot follow bears m V²/a less for the crest's width
    /// over the speed: looked for at the steps' ends only, a truck's 1 kg axles at 300 m/s over
    /// ISO class C waves of 0.2 m dipped to −1.4 kN (2 % of the static load). The wheel whose
    /// contact force falling below zero stopped the run is left to the stop's own sentence.
    fn wheels_pulling(&self) -> Vec<String> {
        let t_end = self.header.t_end;
        self.vehicles
            .iter()
            .flat_map(|v| v.axles.iter().map(move |(axle, r)| (v, axle, r)))
            .filter(|(v, axle, r)| {
                let stopped_it = v.lost_contact.as_deref() == Some(axle.as_str());
                r.min < 0.0 && !(stopped_it && r.min_t >= t_end)
            })
            .map(|(v, axle, r)| format!(
                "vehicle {}'s wheel {axle} pulled on the track with {:.4e} N at t = {:.6} s: its contact force fell below zero and rose again within a step, so the lift-off there was stepped over, and the motion after it is the wheel's held to the track; a wheel pivoting over a crest sharper than its radius follows does so for a time radius × the crest's turn of slope / speed, shorter than the steps",
                v.name, r.min, r.min_t
            ))
            .collect()
    }

    /// A warning where the vehicles' point wheels' contact forces swing so far from their
    /// static loads that the static correction of the modes left out, which follows the static
    /// loads alone, misses more than a quarter of the accuracy: those modes add a share s of
    /// the peak static deflection (the plan's count), and of a swing of x times the static
    /// load they hold none, some x s. A 40 t body on a 3 Hz suspension (ζ 10 %) at 80 m/s over
    /// a 30 m steel beam of 5.6 t (2 % damping): its wheel's force swung from 0 to 4.1 times
    /// its static load, s = 4.2·10⁻⁴ on the 24 modes planned, and the body's largest
    /// acceleration was 1.9·10⁻³ off the linear mesh of 48 elements (on 48 modes, 1.8·10⁻⁴);
    /// the railway study's railcars swing by up to 0.57 with s = 2.2·10⁻⁴, and hold.
    fn wheel_forces_outswing_the_correction(&self) -> Option<String> {
        let share = self.setup.left_out_share?;
        let point = |v: &crate::vehicle::Vehicle| v.wheel == crate::vehicle::Wheel::Point;
        if !self.setup.vehicles.iter().all(point) {
            return None;
        }
        let (mut swing, mut worst) = (0.0_f64, None);
        for (v, report) in self.setup.vehicles.iter().zip(&self.vehicles) {
            // A wheel bearing no static load has no swing to measure against it.
            let loaded = report
                .axles
                .iter()
                .zip(&v.static_loads)
                .filter(|(_, p)| **p > 0.0);
            for ((axle, r), p) in loaded {
                let x = (r.max - p).max(p - r.min) / p;
                if x > swing {
                    (swing, worst) = (x, Some((&report.name, axle)));
                }
            }
        }
        let (vehicle, axle) = worst?;
        let (missed, accuracy) = (swing * share, self.setup.accuracy);
        let modes = match self.setup.beam.model {
            crate::beam::BeamModel::Modal { modes } => modes,
            _ => return None,
        };
        (missed > SHARE * accuracy).then(|| format!(
            "vehicle {vehicle}'s wheel {axle}'s contact force swung by up to {swing:.2} times its static load, and the static correction of the modes left out follows the static loads alone: those modes add {share:.1e} of the peak static deflection at the probes, so the swing's part they leave out, some {missed:.1e}, passes a quarter of the accuracy {accuracy:e}, and the bodies' accelerations and the wheels' forces move with the modes kept (a 40 t body whose wheel's force swung 3.1 times its static load over a 30 m steel beam: its largest acceleration 1.9e-3 off on the 24 modes planned); `track.beam.modes: {}` or `model: linear` holds them",
            2 * modes
        ))
    }

    /// A warning for each vehicle whose bodies ring on their springs faster than the run's
    /// steps follow: more than a third of a radian of that vibration a step on average. What a
    /// kink of the track sets ringing is then carried with the error of steps that do not
    /// resolve it, and the bodies' accelerations with it: Biggs' sprung mass on springs 10³,
    /// 10⁴ and 10⁶ times as stiff (84 Hz, 266 Hz, 2.65 kHz) takes 0.25, 0.45 and 0.95 rad a
    /// step at the defaults, and its largest acceleration lands within 1.7·10⁻⁴, 2.7·10⁻² and
    /// 0.21 of the run at rtol 10⁻⁸ (itself 0.11 from the run at 10⁻⁹).
    fn suspensions_outrun(&self) -> Vec<String> {
        let steps = self.header.stats.steps;
        if steps == 0 {
            return Vec::new();
        }
        let mean = self.header.t_end / steps as f64;
        self.setup
            .vehicles
            .iter()
            .filter_map(|v| {
                let f = v.fastest_suspension_hz();
                let turn = std::f64::consts::TAU * f * mean;
                (turn > 1.0 / 3.0).then(|| format!(
                    "vehicle {}'s bodies ring on their springs at up to {f:.4e} Hz (the axles held), faster than the steps follow ({mean:.2e} s on average, {turn:.1} rad of that vibration a step): their accelerations are not held to the accuracy (Biggs' sprung mass on a spring 10⁴ times as stiff, 266 Hz, 0.45 rad a step: its largest acceleration 0.895 m/s² at the defaults, 0.871 at rtol 1e-8); a tighter `solver.rtol` follows it, and a spring that stiff is close to a rigid attachment",
                    v.name
                ))
            })
            .collect()
    }
}

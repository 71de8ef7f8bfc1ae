//! The scene file (see SCENE-FORMAT in the README): read with locations into a [`SceneSpec`]
//! (what the user wrote, which a typed [`SceneSpec::set`] may change key by key), and checked
//! into the model it names, and only that; nothing is chosen or computed here beyond what the
//! check needs. What the scene leaves out is chosen by the planning step (`plan/`). Every
//! problem is reported as one sentence with the file, the line and the key.
//!
//! Here: the public scene types, reading, and the check of the whole file. `file`: the file's
//! structure as serde reads it; `keys`: the table of dotted keys and editing by them; `checker`: the reporter and the
//! bounds; `rolling`, `beam`, `train`: each section's checks; `yaml_error`: a YAML reader's
//! error as one sentence.

use std::path::Path;

use serde::{Deserialize, Serialize};
use serde_saphyr::{Location, Spanned};

use crate::analysis::discretisation::{
    jumps, weight_drops, Discretisation, DEFAULT_ACCURACY, DEFAULT_ORDER,
};
use crate::beam::damping::DampingSpec;
use crate::beam::element::Section;
use crate::beam::load::{BeamStart, PointLoad, Probe};
use crate::beam::modal::MAX_MODES;
use crate::beam::supports::{mesh_multiple, statically_supported, Support};
use crate::beam::train::{hslm, Train, TrainModel, HSLM_NAMES};
use crate::beam::{BeamModel, BeamSpec, Quadrature, MAX_ORDER};
use crate::coupling::thesis_system::integrates_as_published;
use crate::coupling::{patch, Coupling, DiskOnBeamSpec};
use crate::curve::expr::Formula;
use crate::curve::spline::Spline;
use crate::curve::Curve;
use crate::disk::ContactLoss;
use crate::disk::Disk;
use crate::error::{quote, Error};
use crate::ode::Method;
use crate::rolling::Rolling;

mod beam;
mod checker;
mod disks;
mod file;
mod keys;
pub use keys::{holds_number, is_key};
mod rolling;
mod train;
mod vehicles;
mod yaml_error;

use beam::*;
use checker::*;
use disks::*;
use file::*;
use rolling::*;
use train::*;
use vehicles::*;

/// How the disk on a rigid curve is formulated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formulation {
    Minimal,
    Thesis,
}

impl Formulation {
    pub fn name(self) -> &'static str {
        match self {
            Formulation::Minimal => "minimal",
            Formulation::Thesis => "thesis",
        }
    }
}

#[derive(Clone, Debug)]
pub struct SolverSettings {
    pub method: Method,
    pub rtol: f64,
    pub atol: f64,
    /// Why rtol is what it is, where it was left out and the planner chose it from the beam
    /// scene's accuracy.
    pub rtol_chosen: Option<String>,
    /// atol was left out with rtol: it is rtol times this size of the response (m).
    pub atol_scale: Option<f64>,
    /// Why, where it was.
    pub atol_chosen: Option<String>,
    /// With that atol, the beam's lowest circular frequency (rad/s): the velocities' errors
    /// are measured against it times atol (see `ode::Options::velocity_rate`).
    pub velocity_rate: Option<f64>,
    /// Why the method is what it is, where the scene left it out and the planner chose it.
    pub method_chosen: Option<String>,
    /// Why the beam's free vibration after its riders leave is integrated exactly, where the
    /// scene left the method out and the planner chose so.
    pub free_vibration_chosen: Option<String>,
}

/// A disk on a rigid curve.
#[derive(Clone, Debug)]
pub struct RollingScene {
    pub rolling: Rolling,
    pub formulation: Formulation,
}

/// A flexible beam under point loads.
#[derive(Clone, Debug)]
pub struct BeamScene {
    pub beam: BeamSpec,
    pub start: BeamStart,
    /// The disks riding on the beam, in the scene's order (`disk:` is a list of one).
    pub disks: Vec<DiskOnBeamSpec>,
    /// A train of axle loads crossing the beam, if the scene has one (beside disks or vehicles
    /// too).
    pub train: Option<Train>,
    /// Vehicles crossing the beam (beside disks too).
    pub vehicles: Vec<crate::vehicle::Vehicle>,
    /// The running surface the vehicles ride on.
    pub profile: crate::vehicle::profile::Profile,
    pub loads: Vec<PointLoad>,
    pub probes: Vec<Probe>,
    pub shapes: Vec<f64>,
    pub magnify: f64,
    /// Spectral radius at infinity of generalized-α.
    pub rho_inf: f64,
    /// Why ρ∞ is what it is, when the plan chose it (`plan::rho_inf_for`).
    pub rho_inf_chosen: Option<String>,
    /// Relative accuracy asked of the peak deflection: what the mesh and tolerances are
    /// chosen from when the scene leaves them out.
    pub accuracy: f64,
    /// The mesh the plan chose for the scene, when it left elements or order out.
    pub discretisation: Option<Discretisation>,
    /// Why the beam has the model it has, when the plan chose it (or its modes).
    pub model_choice: Option<String>,
    /// Where the plan chose a linear or modal beam: the largest static deflection at the
    /// probes it measured the nonlinearity under (m), and the exact beam's gap from it, of it.
    pub static_gap: Option<(f64, f64)>,
    /// Where the plan counted a modal beam's modes: what those left out add to the static
    /// deflection at the probes, of its peak (`ModeShares::left_out`).
    pub left_out_share: Option<f64>,
    /// The frequency (Hz) above which the modes are left out of the recorded accelerations;
    /// `None`: EN 1991-2's max(30 Hz, 1.5 f1, f3).
    pub acceleration_cutoff_hz: Option<f64>,
    /// The size of the displacements its loads cause (m), when the supports allow a static
    /// estimate: see `analysis::discretisation::response_size`. Set by the plan.
    pub response: Option<f64>,
    /// The loads only turn the probes, and `response` is their rotation as a length
    /// (`beam::response_scale`). Set by the plan.
    pub response_turned: bool,
    /// Where what moves over the beam is on it too briefly to load it statically: the share
    /// of the static response it leaves, and how long it is on (s). Set by the plan.
    pub passage: Option<(f64, f64)>,
    /// What the plan could not hold to the accuracy, one sentence each. Set by the plan.
    pub plan_warnings: Vec<String>,
}

/// Whether `x` lies within a tenth of its span from a point that holds w, the spans bounded by
/// `ends` (`BeamScene::span_ends`): a pinned span deflects there by at most 30 % of its middle
/// under a load at the middle, a clamped one by 10 %.
fn near_a_support(x: f64, ends: &[f64]) -> bool {
    let held = &ends[1..ends.len() - 1];
    let span = (ends.windows(2))
        .find(|w| w[0] <= x && x <= w[1])
        .map_or(ends[ends.len() - 1] - ends[0], |w| w[1] - w[0]);
    held.iter().any(|&h| (x - h).abs() <= 0.1 * span)
}

impl BeamScene {
    /// The beam's undeformed length (m): the material points s run over [0, length].
    fn length(&self) -> f64 {
        let b = &self.beam;
        (b.to[0] - b.from[0]).hypot(b.to[1] - b.from[1])
    }

    /// Where the beam holds w: its ends whose supports hold it, and its bearings.
    fn held_w(&self) -> Vec<f64> {
        let b = &self.beam;
        let ends = [0.0, self.length()].into_iter().zip(b.supports);
        let mut held: Vec<f64> = (ends.filter(|(_, s)| s.held_components().contains(&1)))
            .map(|(x, _)| x)
            .chain(b.bearings.iter().copied())
            .collect();
        held.sort_by(f64::total_cmp);
        held
    }

    /// Whether every probe sits where a support or a bearing holds w (to read an end's
    /// rotation, say), so that no load deflects any of them.
    pub fn probes_all_held(&self) -> bool {
        let held = self.held_w();
        let close = |x: f64, h: f64| (x - h).abs() <= 1e-9 * (1.0 + h.abs());
        !self.probes.is_empty() && (self.probes.iter()).all(|p| held.iter().any(|&h| close(p.x, h)))
    }

    /// The points the plan measures the response at: the probes, and where every probe lies within
    /// a tenth of its span from a point that holds w, the middle of the longest span as well. The
    /// contract measures every number against the beam's peak deflection, which the middle stands
    /// for, and such probes deflect by a small share of it: they do not set the scale alone (the
    /// sprung-mass study on the linear mesh, read 0.125 m from its pinned end alone, would take 68
    /// elements and atol 8.7·10⁻¹³ m, and 294 562 steps; read at midspan, 16 elements, 2.2·10⁻⁹ m
    /// and 64 818 steps). Where every probe sits where w is held (`probes_all_held`), the middle
    /// alone, for at the probes every choice would see no response.
    pub fn planning_points(&self) -> Vec<f64> {
        let middle = self.longest_span_middle();
        if self.probes_all_held() {
            return vec![middle];
        }
        let mut xs: Vec<f64> = self.probes.iter().map(|p| p.x).collect();
        let ends = self.span_ends();
        if xs.iter().all(|&x| near_a_support(x, &ends)) {
            xs.push(middle);
        }
        xs
    }

    /// The points that bound the spans: the beam's two ends and, in order between them, the
    /// points that hold w.
    fn span_ends(&self) -> Vec<f64> {
        let mut ends = vec![0.0];
        ends.extend(self.held_w());
        ends.push(self.length());
        ends
    }

    /// The middle of the longest stretch between points that hold w and the beam's ends (the
    /// first of equal ones).
    pub fn longest_span_middle(&self) -> f64 {
        let ends = self.span_ends();
        let (a, z) = (ends.windows(2).rev())
            .map(|w| (w[0], w[1]))
            .max_by(|p, q| (p.1 - p.0).total_cmp(&(q.1 - q.0)))
            .unwrap_or((0.0, self.length()));
        0.5 * (a + z)
    }

    /// With no probe given, one named `mid` at the middle of the beam; where a support or a
    /// bearing holds w there (two equal spans), at the middle of the longest span instead, for
    /// there it would read only zeros.
    fn probe_mid_when_none_given(&mut self, length: f64) {
        if !self.probes.is_empty() {
            return;
        }
        self.probes.push(Probe {
            name: "mid".into(),
            x: 0.5 * length,
        });
        self.probes[0].x = self.longest_span_middle();
    }

    /// The disk, where the scene has one; the first, where it has several.
    pub fn disk(&self) -> Option<&DiskOnBeamSpec> {
        self.disks.first()
    }

    /// The disks' names in the outputs: `disk` alone, `disk1`, `disk2`, … for several.
    pub fn disk_names(&self) -> Vec<String> {
        match self.disks.len() {
            1 => vec!["disk".to_string()],
            n => (1..=n).map(|k| format!("disk{k}")).collect(),
        }
    }

    /// Why `exact-modal` cannot integrate this scene, if it cannot: it takes a modal beam under
    /// moving forces, point loads or its weight, and nothing that rides with inertia.
    pub fn exact_modal_refusal(&self) -> Option<String> {
        let what = if !self.disks.is_empty() {
            "a disk".to_string()
        } else if !self.vehicles.is_empty() {
            "vehicles".to_string()
        } else if self.carries_moving_masses() {
            "moving masses".to_string()
        } else if !matches!(self.beam.model, BeamModel::Modal { .. }) {
            format!("a {} beam", self.beam.model.name())
        } else {
            return None;
        };
        Some(format!(
            "exact-modal integrates a modal beam (`model: modal`) under moving forces, point loads or its weight; this scene has {what}: use genalpha"
        ))
    }

    /// Whether the beam alone, once every rider has left it, is uncoupled linear oscillators
    /// under a force of time: a modal beam with no moving masses.
    pub fn free_vibration_is_modal(&self) -> bool {
        matches!(self.beam.model, BeamModel::Modal { .. }) && !self.carries_moving_masses()
    }

    /// Whether anything moves along the beam: a train or a disk.
    pub fn carries_moving_loads(&self) -> bool {
        self.train.is_some() || !self.disks.is_empty()
    }

    /// Whether a train's axles ride with their mass (`train.model: moving-mass`): each follows
    /// the beam's motion, and its inertia switches on and off as it enters and leaves.
    pub fn carries_moving_masses(&self) -> bool {
        self.train
            .as_ref()
            .is_some_and(|t| t.model == TrainModel::MovingMass)
    }

    /// Whether a disk whose contact force follows the beam's motion (any coupling but a
    /// moving force) rolls on the beam: its force then rings in every mode the beam holds.
    pub fn rolls_with_inertia(&self) -> bool {
        self.disks
            .iter()
            .any(|d| d.coupling != Coupling::MovingForce)
    }

    /// Whether a load is switched on or off during the run, the beam's own weight included
    /// where it drops on a beam that starts undeformed: it then excites every mode the mesh
    /// holds.
    pub fn load_switched(&self) -> bool {
        jumps(&self.loads, self.start) || weight_drops(&self.beam, self.start)
    }
}

/// The shortest contact patch, and section depth, against the beam's length: below it the
/// patch's kernel (of height 1/b) and the kink's curvature (θ/b) leave floating point.
const MIN_PATCH_PER_LENGTH: f64 = 1e-6;

impl BeamScene {
    /// How much the disk's results depend on its contact patch (see `coupling::patch`): its
    /// weight's kink in the axis, at the fastest it can roll (its start speed, plus what the
    /// drop of the axis from its start can add), against the response size. Of the first
    /// disk, where there are several ([`Self::patch_sensitivity_of`] for each).
    pub fn patch_sensitivity(&self) -> Option<patch::Sensitivity> {
        Some(self.patch_sensitivity_of(self.disk()?))
    }

    /// [`Self::patch_sensitivity`] of the disk `d`.
    pub fn patch_sensitivity_of(&self, d: &DiskOnBeamSpec) -> patch::Sensitivity {
        let weight = d.disk.mass * d.gravity;
        let (from, to) = (self.beam.from, self.beam.to);
        let length = (to[0] - from[0]).hypot(to[1] - from[1]);
        let start_y = from[1] + (to[1] - from[1]) * d.s0 / length;
        let drop = (start_y - from[1].min(to[1])).max(0.0);
        let speed = (d.v0() * d.v0() + 2.0 * d.gravity * drop).sqrt();
        patch::Sensitivity::of(
            &self.beam.section,
            weight,
            d.gravity,
            speed,
            d.patch,
            self.response.unwrap_or(f64::INFINITY),
        )
    }

    /// Whether `axle` of `v` touches the deck at t = 0: its patch (widened by a disk wheel's
    /// radius) reaches the span.
    pub fn touches_the_deck_at_the_start(
        &self,
        v: &crate::vehicle::Vehicle,
        axle: &crate::vehicle::Axle,
    ) -> bool {
        let reach = v.reach(crate::coupling::patch::dispersed_half_width(
            self.beam.depth,
        ));
        let x = v.x0 - axle.x;
        x + reach > 0.0 && x - reach < self.length()
    }

    /// The fastest `v` runs until its last wheel has left the deck: its speed changes one
    /// way, so at the start or there.
    pub fn top_speed_on_deck(&self, v: &crate::vehicle::Vehicle) -> f64 {
        let [from, to] = [self.beam.from, self.beam.to];
        let length = (to[0] - from[0]).hypot(to[1] - from[1]);
        let gone = vehicles::vehicle_gone(
            v,
            length,
            crate::coupling::patch::dispersed_half_width(self.beam.depth),
        );
        v.top_speed(gone)
    }

    /// What the results depend on beyond the accuracy asked, one sentence each.
    pub fn warnings(&self) -> Vec<String> {
        let mut out: Vec<String> = self
            .disks
            .iter()
            .flat_map(|d| self.patch_sensitivity_of(d).warnings(self.accuracy))
            .collect();
        out.dedup();
        // Measured on D44 (consistent disk, exact beam, started at rest): the least and largest
        // contact force 11.4 / 6.2 / 2.3 kN and 17.1 / 19.0 / 20.2 kN on 5 / 10 / 20 elements,
        // all within a millisecond of the start; started static, 12.9–13.0 and 16.53–16.54 kN.
        // The deck's acceleration with it: a 0.27 m disk over D44's section, ESDIRK4 at rtol
        // 1e-7 on 16 elements, midspan's largest 1.336 / 2.347 / 2.360 m/s² on 16 (the plan's) /
        // 64 / 128 modes; started static 1.507 / 1.521 on 16 / 64.
        let rider = self
            .disks
            .iter()
            .any(|d| d.coupling != crate::coupling::Coupling::MovingForce);
        if rider && self.start == BeamStart::Rest {
            out.push("the disk is set down at t = 0 on a beam at rest (`track.beam.initial: rest`), a sudden load: its contact force rings from that touch in every mode the beam holds, on an undamped beam for the whole run, and the extremes of the contact force and of the accelerations depend on the mesh, the modes kept and the steps (the zip-line's least contact force moved by 1.7e-2 of the weight from rtol 3.3e-5 to 1e-7, started static by 1.4e-4; a 0.27 m disk over D44's section read midspan's largest acceleration 1.34 / 2.35 / 2.36 m/s² on 16 (the plan's) / 64 / 128 modes, started static 1.51 / 1.52); `initial: static` starts the beam carrying the disk".to_string());
        }
        // Measured on D50's 10 exact elements started static, at the defaults against rtol 1e-7:
        // the instantaneous least contact force 1.5e-3 of the weight off, its mean 4e-6. The
        // rows do not settle at any rtol a run affords: on D44's 10 exact elements started
        // static, midspan's acceleration was 2.6e-2 of its largest off at rtol 1e-6 and 4.1e-4
        // at 1e-8, against 1e-9; the zip-line's rows at a three-hundredth and a three-thousandth
        // of the accuracy lay 0.35 apart, in 340 000 and 1 140 000 steps.
        let meshed = !matches!(self.beam.model, crate::beam::BeamModel::Modal { .. });
        if meshed
            && self
                .disks
                .iter()
                .any(|d| d.coupling == crate::coupling::Coupling::Consistent)
        {
            out.push("a rolling disk on a mesh: its instantaneous contact force (`rn_min`, `rn_max`, `rt_min`, `rt_max`, `mu_needed_max`), and the accelerations while it rides, can ring in the mesh's highest modes faster than the steps the accuracy asks for follow, and are not held to it, the history's rows least of all (D50's 10 elements started carrying the disk: the least contact force 1.5e-3 of the weight, midspan's largest acceleration 4.9e-3 off; D44's 10 exact elements against rtol 1e-8: midspan's acceleration at some output time 4.7e-2 of its largest off started carrying the disk and 0.42 set down on the unloaded beam, the contact force 1.1e-2 and 9.3e-2 of the weight); `contact_mean`, the force averaged over a period of the acceleration's cutoff, is held to it".to_string());
        }
        // Measured on D44 started static, converged in time (rtol 1e-7) on 16 / 32 / 64 / 128
        // modes of 8 / 16 / 32 / 64 elements; D50 and the moving mass alike.
        if rider && !meshed {
            out.push("a disk with a mass on the modal beam: its instantaneous contact force (`rn_min`, `rn_max`, `rt_min`, `rt_max`, `mu_needed_max`) and the accelerations move with the modes kept by more than the accuracy, for the modes below the cutoff answer the contact force's ringing in the modes above it (D44 started carrying the disk, on 16 / 32 / 64 / 128 modes: midspan's largest acceleration 3.044 / 2.958 / 3.014 / 3.011 m/s², the least contact force 12 986 / 12 947 / 12 949 / 12 915 N); `contact_mean`, the force averaged over a period of the acceleration's cutoff, moves by less (13 133 / 13 136 / 13 143 / 13 141 N); a run with `track.beam.modes` doubled shows what a scene's move by".to_string());
        }
        out.extend(self.riders_moving_with_the_discretisation(meshed));
        out.extend(
            self.discretisation
                .iter()
                .filter_map(|d| d.unconfirmed.clone()),
        );
        out.extend(self.plan_warnings.iter().cloned());
        if self.disks.len() > 1
            && self
                .disks
                .iter()
                .any(|d| matches!(d.contact_loss, crate::disk::ContactLoss::Fly { .. }))
        {
            let beside_mass = self
                .disks
                .iter()
                .any(|d| d.coupling == Coupling::MovingMass);
            out.push(if beside_mass {
                "of several disks, one that loses contact beside a moving-mass disk ends the run (`contact-lost`): a landing's impulse is shared with the beam and the disks rolling on it, not with a moving mass's prescribed path"
            } else {
                "of several disks one flies at a time: another that loses contact while one flies ends the run (`contact-lost`)"
            }.to_string());
        }
        if let Some((j, k, apart)) = first_overlap(&self.disks) {
            out.push(format!(
                "disks[{j}] and disks[{k}] start {apart:.4} m apart along the track, closer than their radii together: the disks do not touch one another, and pass through each other as two loads do"
            ));
        }
        if self.probes_all_held() {
            out.push(format!(
                "every probe sits where a support holds w, which no load deflects: the plan chooses the mesh, the model and the tolerances from the response at x = {} m, the middle of the longest span, which the probes' rotations follow",
                self.longest_span_middle()
            ));
        }
        for v in &self.vehicles {
            let crate::vehicle::Wheel::Disk { radius } = v.wheel else {
                continue;
            };
            if self.profile.crest_scan(radius).is_some() {
                out.push(format!(
                    "vehicle `{}`'s disk wheels (radius {radius} m) ride a road that may bend by up to {:.2} 1/m against the disk's {:.2}: where it does, the disk bridges the hollow, and each crest ahead that comes level with the one a wheel rests on is met as a plastic impact, whose loss `energy.impact` books",
                    v.name,
                    self.profile.curvature_bound(),
                    1.0 / radius
                ));
            }
        }
        // The plan tightens rtol with the speed of wheels with a mass of their own, measured
        // up to this speed only (`plan::rtol_for`).
        for v in &self.vehicles {
            let top = self.top_speed_on_deck(v);
            if top > MAX_SPEED_WITH_UNSPRUNG_MASS && v.has_unsprung_mass() {
                out.push(format!("vehicle `{}` runs at up to {top} m/s on wheels with a mass of their own: the plan's tolerance for their impulses at the deck's ends and kinks is measured to {MAX_SPEED_WITH_UNSPRUNG_MASS} m/s; beyond, compare a run at a tenth of `solver.rtol`", v.name));
            }
        }
        out
    }

    /// Where the trains' moving masses and the vehicles move the accelerations with the modes
    /// kept or the mesh by more than the accuracy, one sentence each.
    fn riders_moving_with_the_discretisation(&self, meshed: bool) -> Vec<String> {
        let mut out = Vec::new();
        // Measured at the defaults against the same scene on the linear mesh (and on four
        // times the modes, which agree with it within 2e-4): two 2 t moving masses at 20 m/s
        // over D44's section, two 50 kN at 10 m/s over a 20 m beam of A 0.05 m², I 0.01 m⁴,
        // and twelve 135 kN axles at 100 m/s over the railway study's deck.
        if self.carries_moving_masses() && !meshed {
            out.push("a train of moving masses on the modal beam: the accelerations and the support reactions can move with the modes kept by more than the accuracy, for each mass turns with the beam's slope as it enters and crosses, and the modes below the cutoff answer those kicks in the modes above it (two 2 t masses at 20 m/s over D44's section, on 16 (the plan's) / 32 / 64 / 128 modes: midspan's largest acceleration 4.399 / 4.400 / 4.427 / 4.574 m/s², the linear mesh of 16 / 32 / 64 elements 4.571 / 5.602 / 5.468; two 50 kN at 10 m/s over a 20 m beam, on 48 / 96 / 144 modes: 2.066 / 2.091 / 2.093, the mesh 2.093; the railcar's axles at 100 m/s over the railway study's 15 m concrete deck: 5e-5 of the largest from the mesh's; HSLM-A1's 50 masses at 90 m/s over its 15 m bridge, on the 18 modes planned: the reactions 1.3e-3 and the accelerations 5.5e-4 of their largest off 72 modes', on 36 within 3.1e-4); `track.beam.model: linear` holds them where its mesh does, and a run with `track.beam.modes` doubled shows what a scene's move by".to_string());
        }
        // Measured with ESDIRK4 at rtol 1e-7 on the exact beam's 12 elements, the finer meshes
        // at rtol 1e-9, which moved two 40 t masses' reading on the 12 elements
        // by 3e-7. A 40 t mass leaving a light two-span beam whipped it: 4.49e5 and 3.17e5
        // m/s² on 16 and 32 elements; the 6 m beam's, both meshes at rtol 1e-9 and 1e-7.
        if self.carries_moving_masses() && meshed {
            out.push("a train of moving masses on a mesh: the accelerations can move with the mesh by more than the accuracy, for each mass turns with the beam's slope at every node it crosses, kicks whose size and timing are the mesh's, and where the deck is stiff the loads' own accelerations are small beside them (two 1 t masses at 10 m/s over a 30 m clamped HEB 360 beam, on 12 / 24 / 48 / 96 elements: the envelope's largest acceleration 0.0978 / 0.0924 / 0.0957 / 0.0958 m/s², midspan's 0.0837 / 0.0861 / 0.0833 / 0.0832; the same beam pinned and sliding, ten times the accelerations, on the linear mesh of 24 / 48 / 96: 0.9934 / 0.9941 / 0.9941); a mass far heavier than the beam sets it whipping as it leaves, and then the deflections move with the mesh too (a 40 t mass at 20 m/s off a 6 m steel beam of 0.43 t: midspan's deepest deflection after it -0.461 and -0.422 m on 12 and 24 elements); a run with `track.beam.elements` doubled shows what a scene's move by".to_string());
        }
        // Measured at the defaults on the planned 32 exact elements and on 16, 64 and 128 (64
        // and 128 agree within 1.2e-4; rtol 1e-9 on the 32 moves the reading by 3e-6).
        if meshed && self.vehicles.iter().any(|v| v.has_unsprung_mass()) {
            out.push("vehicles on unsprung masses (axles with a `mass`) on a mesh: the accelerations can move with the mesh by more than the accuracy, for each unsprung mass rides the deck as a moving mass does, turning with the beam's slope at every node it crosses, kicks whose size and timing are the mesh's (a 10 t car on two 1 t wheels at 20 m/s over a 20 m pinned-roller steel beam of 1.4 t, 2 % damping: the quarter point's largest acceleration 12.213 / 12.287 / 12.265 / 12.264 m/s² on 16 / 32 / 64 / 128 elements, 1.3e-3 of the deck's largest on the 32 planned; on massless wheels the 32 within 7e-5 of 128); a run with `track.beam.elements` doubled shows what a scene's move by".to_string());
        }
        // Measured on the planned 22 modes, on 44, on 88 modes of twice the mesh and on the
        // linear mesh of 24 elements, each at rtol 1e-8; the railcars on 18 modes as planned
        // against 72 of 40 elements, at the defaults.
        if !meshed && self.vehicles.iter().any(|v| v.has_unsprung_mass()) {
            out.push("vehicles on unsprung masses (axles with a `mass`) on the modal beam: the accelerations and the wheels' contact forces (`rn_min`, `rn_max`) can move with the modes kept by more than the accuracy, for each unsprung mass rides the deck as a moving mass does, kicked where the beam's slope turns, and the modes below the cutoff answer those kicks in the modes above it (a 40 t body on an 8 Hz suspension over a 400 kg wheel at 10 m/s across a 15 m steel beam of 4.3 t: midspan's largest acceleration 40.1 m/s² on the 22 modes planned, 43.9 on 44, 53.3 on 88, 55.1 on the linear mesh, the wheel's largest contact force 490.6 / 497.5 / 504.6 / 508.6 kN; the railway study's railcars over its 15 m concrete deck: 4e-5 of the largest on four times the modes); a run with `track.beam.modes` doubled shows what a scene's move by".to_string());
        }
        let quiet = (self.beam.damping.as_ref()).is_some_and(|d| d.damps_high_modes());
        // Measured on one 1 t mass at 10 m/s over clamped steel beams (A 241 cm², I 12 370
        // cm⁴): 10 m long on the 46 modes planned, at the defaults and at rtol 1e-6, 1e-8 and
        // 1e-9 (atol rtol times 2.02 mm); 30 m long on the 40 exact elements planned, at the
        // defaults and at rtol 1e-5, 1e-6 and 1e-8; both again with 0.1 % Rayleigh damping.
        if self.carries_moving_masses() && !quiet {
            out.push("a train of moving masses on a deck without stiffness-proportional damping: the accelerations while a mass rides can move with the steps' tolerance (and with the modes or the mesh) by more than the accuracy, for each mass is kicked where the beam's slope turns, the beam's highest modes ring without decay, and the mass hands their accelerations through its inertia to the modes below the cutoff (one 1 t mass at 10 m/s over a 10 m clamped steel beam, on the 46 modes planned: history rows 2e-2 of the deck's largest acceleration off rtol 1e-9 at the defaults, in 136 070 steps; over the 30 m beam, on the 40 exact elements planned: the envelope's largest acceleration 0.954 / 0.989 / 1.007 m/s² at rtol 1e-6 / 1e-7, the plan's / 1e-8, in 695 617 steps at the plan's); damping quiets them (`track.beam.damping`: at ζ 0.1 % the 30 m beam reads 0.2639 m/s², within 4e-7 of rtol 1e-9, in 3537 steps)".to_string());
        }
        // Measured on a 40 t body on an 8 Hz suspension (ζ 10 %) at 10 m/s over a 20 m clamped
        // concrete deck (A 18 m², I 1.98 m⁴): the planned 46 modes of 28 elements, 92 of 56 and
        // the linear meshes of 28 and 56 elements, the last two at rtol 1e-9; the same deck with
        // 0.1 % Rayleigh damping; a 2 t car on an 8 Hz suspension (ζ 10 %) at 40 m/s over a 30 m
        // clamped-roller steel beam (A 90.5 cm², I 10 798 cm⁴) on 21 modes of 20 elements and
        // the linear mesh of 40 at rtol 1e-10; Biggs' sprung mass on 7 and 14 modes.
        if !self.vehicles.is_empty() && !quiet {
            out.push("vehicles on a deck without stiffness-proportional damping: the accelerations, the bodies' and the deck's, can move with the modes the beam holds (kept, or its mesh's) by more than the accuracy, for the modes above those the loads excite ring without decay and the vehicles hand them to the bodies and back to the deck (a 40 t body on an 8 Hz suspension at 10 m/s over a 20 m concrete deck: its largest acceleration 5.037e-3 m/s² on the 46 modes planned, 5.146e-3 on every mode of the planned mesh, 5.182e-3 on 92 modes of twice the mesh and on its every mode; a 2 t car at 40 m/s over a 2.1 t, 30 m steel beam: the deck's largest acceleration 99.14 m/s² on the 21 modes planned, 99.54 on every mode of twice the mesh; Biggs' sprung mass: 2e-5 on half its modes); damping quiets them (`track.beam.damping`: at ζ 0.1 % the same body holds within 2e-4), and a run with `track.beam.modes` doubled shows what a scene's move by".to_string());
        }
        out
    }

    /// Where two disks that start apart would come within their radii together before `until`
    /// (s), both still on the track, at their starting speeds: the disks do not touch one
    /// another, so one said to roll into another passes through it. A rolling disk's speed
    /// changes only as the deck it rolls on sags and rises, so its starting speed places the
    /// meeting to within that.
    pub fn disks_meeting(&self, until: f64) -> Option<String> {
        let length = self.length();
        let on = |s: f64| (0.0..=length).contains(&s);
        let disks = &self.disks;
        let (j, k, t, s) = disks.iter().enumerate().find_map(|(j, a)| {
            disks[j + 1..].iter().enumerate().find_map(|(i, b)| {
                let (gap, reach) = (b.s0 - a.s0, a.disk.radius + b.disk.radius);
                let closing = (a.v0() - b.v0()) * gap.signum();
                if gap.abs() < reach || !(closing > 0.0) {
                    return None;
                }
                let t = (gap.abs() - reach) / closing;
                let (sa, sb) = (a.s0 + a.v0() * t, b.s0 + b.v0() * t);
                (t <= until && on(sa) && on(sb)).then_some((j + 1, j + i + 2, t, 0.5 * (sa + sb)))
            })
        })?;
        Some(format!(
            "disks[{j}] and disks[{k}] come within their radii together at t = {t:.3} s near s = {s:.2} m, at their starting speeds: the disks do not touch one another, and one passes through the other as two loads do"
        ))
    }
}

/// The first two disks (numbered from 1, as errors name them) whose starting points lie closer
/// than their radii together, and how far apart.
fn first_overlap(disks: &[DiskOnBeamSpec]) -> Option<(usize, usize, f64)> {
    disks.iter().enumerate().find_map(|(j, a)| {
        disks[j + 1..].iter().enumerate().find_map(|(i, b)| {
            let apart = (a.s0 - b.s0).abs();
            (apart < a.disk.radius + b.disk.radius).then_some((j + 1, j + i + 2, apart))
        })
    })
}

/// The fastest a vehicle with unsprung masses has been measured to hold the accuracy at the
/// defaults (m/s; see [`BeamScene::warnings`]): beyond it, the run says so.
pub const MAX_SPEED_WITH_UNSPRUNG_MASS: f64 = 3000.0;

/// What the scene models, and only that.
#[derive(Clone, Debug)]
pub enum Model {
    Rolling(RollingScene),
    Beam(BeamScene),
}

/// A checked scene: everything the run needs, nothing it does not.
#[derive(Clone, Debug)]
pub struct Scene {
    pub name: String,
    pub duration: f64,
    pub model: Model,
    pub solver: SolverSettings,
    /// Time between rows of history.csv.
    pub interval: f64,
}

impl Scene {
    pub fn rolling(&self) -> Option<&RollingScene> {
        match &self.model {
            Model::Rolling(r) => Some(r),
            Model::Beam(_) => None,
        }
    }

    pub fn beam(&self) -> Option<&BeamScene> {
        model_of_beam(&self.model)
    }
}

pub const DEFAULT_GRAVITY: f64 = 9.81;

/// A scene as written: the file's values with their lines, nothing chosen. [`SceneSpec::set`]
/// changes one of them by its dotted key, as `sweep --set` and the tests do; checking and
/// planning it again gives the changed scene.
#[derive(Clone)]
pub struct SceneSpec {
    file: SceneFile,
    /// Names the source in messages.
    source: String,
    /// The default scene name.
    stem: String,
    /// Whether messages name the text's lines ([`SceneSpec::parse_unlined`]).
    lined: bool,
}

/// A checked scene, not yet planned: what only the planning step (`plan/`) turns into a
/// [`Scene`], choosing what the scene left out.
pub struct Checked {
    /// The scene with the mesh and tolerances as given, or provisional where left out.
    pub scene: Scene,
    /// Element count and degree as the scene gives them.
    pub elements: Option<usize>,
    pub order: Option<usize>,
    /// Element counts are kept to multiples of this, which puts a node at each bearing.
    pub multiple: usize,
    /// The scene names its beam model (the plan chooses it otherwise).
    pub model_given: bool,
    pub rtol_given: bool,
    pub atol_given: bool,
    /// The scene gives generalized-α's ρ∞ (the plan chooses it otherwise).
    pub rho_inf_given: bool,
    /// The scene names its method (the plan chooses it otherwise).
    pub method_given: bool,
}

/// Largest scene file read. The reader's own budget of 250 000 values stops a list first: a
/// curve of about 83 000 points (a profile takes at most 10 000).
pub const MAX_SCENE_BYTES: u64 = 64 << 20;

impl SceneSpec {
    pub fn load(path: &Path) -> Result<SceneSpec, Error> {
        let text = crate::files::read_text(path, MAX_SCENE_BYTES, "scene file")?;
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        SceneSpec::parse(&text, &path.display().to_string(), &stem)
    }

    /// Read and check; `source` names the source in messages, `stem` is the default scene name.
    pub fn parse(text: &str, source: &str, stem: &str) -> Result<SceneSpec, Error> {
        SceneSpec::read(text, source, stem, true)
    }

    /// As [`SceneSpec::parse`], for a text a program wrote from data (the Python package's
    /// scene dicts): its messages name the keys, never a line of a text the author never saw.
    pub fn parse_unlined(text: &str, source: &str, stem: &str) -> Result<SceneSpec, Error> {
        SceneSpec::read(text, source, stem, false)
    }

    fn read(text: &str, source: &str, stem: &str, lined: bool) -> Result<SceneSpec, Error> {
        let file: SceneFile = serde_saphyr::from_str(text).map_err(|e| {
            let at = e.location().map(|l| (l.line(), l.column()));
            let (line, sentence) = yaml_error::describe(text, &e.to_string(), at);
            let place = Checker {
                file: source,
                lined,
            }
            .place(line.unwrap_or(0));
            Error::Input(format!("{place}: {sentence}"))
        })?;
        let spec = SceneSpec {
            file,
            source: source.into(),
            stem: stem.into(),
            lined,
        };
        spec.check()?;
        Ok(spec)
    }

    /// The scene as a scene file: what it was read from with every [`SceneSpec::set`]
    /// applied. Reading the text back gives the same scene (a planned sweep's case files,
    /// the Python package's pickled scenes).
    pub fn to_yaml(&self) -> Result<String, Error> {
        serde_saphyr::to_string(&self.file)
            .map_err(|e| Error::Output(format!("cannot write the scene as YAML: {e}")))
    }

    /// The model the scene names, checked; mesh and tolerances as given.
    pub fn check(&self) -> Result<Checked, Error> {
        let c = Checker {
            file: &self.source,
            lined: self.lined,
        };
        check(&self.file, &c, &self.stem)
    }
}

/// The track's model (a disk on a rigid curve or a beam with what rides on it) and the mesh
/// as the file gives it.
fn track_model(
    c: &Checker,
    raw: &SceneFile,
    gravity: f64,
    duration: f64,
) -> Result<(Model, MeshAsGiven), Error> {
    let track = &raw.track;
    match (&track.value.curve, &track.value.beam) {
        (Some(_), Some(_)) | (None, None) => c.err(
            track.referenced.line(),
            "track",
            "must name exactly one of `curve` or `beam`",
        ),
        (Some(curve), None) => Ok((
            Model::Rolling(rolling_scene(c, raw, curve, gravity)?),
            MeshAsGiven {
                elements: None,
                order: None,
                multiple: 1,
                model: true,
                duration,
            },
        )),
        (None, Some(beam)) => {
            let (scene, mesh) = beam_scene(c, raw, beam, duration, gravity)?;
            Ok((Model::Beam(scene), mesh))
        }
    }
}

/// The solver as the file gives it, over the track's defaults; whether rtol and atol were
/// given.
fn solver_settings(
    c: &Checker,
    raw: &SceneFile,
    model: &Model,
    mesh: &MeshAsGiven,
) -> Result<(SolverSettings, bool, bool), Error> {
    let beam_default = matches!(model, Model::Beam(_));
    let mut solver = SolverSettings {
        method: if beam_default {
            Method::GenAlpha
        } else {
            Method::Dopri5
        },
        rtol: 1e-6,
        atol: 1e-9,
        rtol_chosen: None,
        atol_scale: None,
        atol_chosen: None,
        velocity_rate: None,
        method_chosen: None,
        free_vibration_chosen: None,
    };
    let (mut rtol_given, mut atol_given) = (false, false);
    let Some(s) = &raw.solver else {
        return Ok((solver, rtol_given, atol_given));
    };
    if let Some(m) = &s.method {
        solver.method = Method::from_name(&m.value).map_or_else(
            || {
                c.err(
                    m.referenced.line(),
                    "solver.method",
                    format!("is {}; use one of {}", quote(&m.value), method_names()),
                )
            },
            Ok,
        )?;
        if matches!(solver.method, Method::GenAlpha | Method::ExactModal) && !beam_default {
            return c.err(m.referenced.line(), "solver.method", format!("{} integrates structural (beam) scenes; use dopri5, trbdf2 or esdirk4 for a rigid curve", solver.method.name()));
        }
    }
    if let Some(r) = &s.rtol {
        solver.rtol = c.positive(r, "solver.rtol")?;
        if let Some(why) = crate::ode::rtol_problem(solver.rtol) {
            return c.err(r.referenced.line(), "solver.rtol", why);
        }
        rtol_given = true;
    }
    if let Some(a) = &s.atol {
        solver.atol = c.positive(a, "solver.atol")?;
        atol_given = true;
        if let Some(why) = model_of_beam(model).and_then(|b| b.atol_problem(solver.atol)) {
            return c.err(a.referenced.line(), "solver.atol", why);
        }
    }
    if let (Model::Beam(b), Some(m)) = (model, &s.method) {
        if b.disk().is_some_and(|d| d.coupling == Coupling::Thesis)
            && integrates_as_published(solver.method)
            && b.beam.model != BeamModel::Exact
            && mesh.model
        {
            return c.err(m.referenced.line(), "solver.method", format!("{} integrates the thesis coupling as the published 3n + 6 system, which transcribes the exact beam; use `model: exact`, or genalpha or esdirk4 for the thesis coupling on a {} beam", solver.method.name(), b.beam.model.name()));
        }
    }
    Ok((solver, rtol_given, atol_given))
}

fn model_of_beam(model: &Model) -> Option<&BeamScene> {
    match model {
        Model::Beam(b) => Some(b),
        Model::Rolling(_) => None,
    }
}

impl BeamScene {
    /// Why an absolute tolerance cannot serve this beam, if it cannot: one the size of the
    /// structure holds no step (C2's 3 m cantilever at atol 1000 ran 45 s into a singular
    /// iteration matrix, at 10 past the step budget after 22 s).
    pub fn atol_problem(&self, atol: f64) -> Option<String> {
        let [x0, y0] = self.beam.from;
        let [x1, y1] = self.beam.to;
        let length = (x1 - x0).hypot(y1 - y0);
        (atol >= length).then(|| format!("= {atol} is not below the beam's length ({length} m): no step would be held to it; leave it out for the plan to choose it from rtol and the response's size"))
    }
}

/// The history's interval: the file's, or a 500th of the run.
fn output_interval(c: &Checker, raw: &SceneFile, duration: f64) -> Result<f64, Error> {
    let Some(i) = raw.output.as_ref().and_then(|o| o.interval.as_ref()) else {
        return Ok(duration / 500.0);
    };
    let interval = c.positive(i, "output.interval")?;
    if interval > duration {
        return c.err(
            i.referenced.line(),
            "output.interval",
            format!("= {interval} s is longer than `duration` = {duration} s; history.csv would hold t = 0 alone"),
        );
    }
    if duration / interval > MAX_ROWS {
        return c.err(i.referenced.line(), "output.interval", format!("= {interval:e} would write {:.3e} rows of history; at most {MAX_ROWS:.0} are allowed", duration / interval));
    }
    Ok(interval)
}

fn check(raw: &SceneFile, c: &Checker, stem: &str) -> Result<Checked, Error> {
    let name = scene_name(c, raw.name.as_ref(), stem)?;
    let gravity = match &raw.gravity {
        Some(g) => c.finite(g, "gravity")?,
        None => DEFAULT_GRAVITY,
    };
    let duration = c.positive(&raw.duration, "duration")?;
    let (model, mesh) = track_model(c, raw, gravity, duration)?;
    let duration = mesh.duration;
    let (solver, rtol_given, atol_given) = solver_settings(c, raw, &model, &mesh)?;
    let interval = output_interval(c, raw, duration)?;
    Ok(Checked {
        scene: Scene {
            name,
            duration,
            model,
            solver,
            interval,
        },
        elements: mesh.elements,
        order: mesh.order,
        multiple: mesh.multiple,
        model_given: mesh.model,
        rtol_given,
        atol_given,
        rho_inf_given: raw.solver.as_ref().is_some_and(|s| s.rho_inf.is_some()),
        method_given: raw.solver.as_ref().is_some_and(|s| s.method.is_some()),
    })
}

pub fn method_names() -> String {
    Method::NAMED.map(|m| m.name()).join(", ")
}

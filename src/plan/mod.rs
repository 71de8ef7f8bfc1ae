//! Planning: a checked scene ([`Checked`]) becomes the [`Scene`] a run is built from, with what
//! it left out chosen from its accuracy and the reason recorded: the mesh
//! (`analysis::discretisation::choose`), the beam model (`analysis::model_choice`), the size
//! of its response, and the steps' tolerances (`tolerances.rs`: [`rtol_for`] and
//! [`atol_for`]). A [`Planner`] keeps the mesh choices it has made, so that the cases of a
//! sweep that share a beam plan it once.

use std::collections::BTreeMap;
use std::path::Path;
use std::sync::{Arc, Mutex};

use crate::analysis::discretisation::{
    choose, lowest_omega, passage_share, response_size, Discretisation, MovingLoads,
};
use crate::analysis::model_choice;
use crate::beam::damping::DampingSpec;
use crate::beam::supports::Support;
use crate::beam::train::TrainModel;
use crate::beam::{shear_rigid_limit, BeamModel};
use crate::coupling::Coupling;
use crate::error::Error;
use crate::ode::Method;
use crate::scene::{BeamScene, Checked, Model, Scene, SceneSpec, SolverSettings};

mod tolerances;
use tolerances::damped_by_the_scene;
pub use tolerances::{atol_for, rtol_for};

/// A beam model chosen, why, what its count of modes was chosen from, why the loads are more
/// than the beam carries, where they are, and the static nonlinearity it was chosen from.
type ChosenModel = (
    BeamModel,
    String,
    Option<Arc<model_choice::Recount>>,
    Option<String>,
    Option<(f64, f64)>,
);

/// Plans scenes, keeping the choices made (mesh, model, ρ∞, the response's size) by everything
/// they depend on: the eigenproblems and static solves behind a choice cost seconds on a fine
/// mesh, and a sweep's cases share them.
#[derive(Default)]
pub struct Planner {
    chosen: Mutex<BTreeMap<String, Discretisation>>,
    models: Mutex<BTreeMap<String, ChosenModel>>,
    dampings: Mutex<BTreeMap<String, (f64, String)>>,
    responses: Mutex<BTreeMap<String, Option<(f64, bool)>>>,
    gaps: Mutex<BTreeMap<String, Option<f64>>>,
    lowest: Mutex<BTreeMap<String, Option<f64>>>,
}

impl Planner {
    /// Check the scene as it now stands and plan it.
    pub fn plan(&self, spec: &SceneSpec) -> Result<Scene, Error> {
        let scene = self.plan_checked(spec.check()?)?;
        // Whether the scene's `exact-modal` applies is known once the model is chosen: refused
        // here, `check` and every run say so alike.
        match scene.beam().and_then(|b| b.exact_modal_refusal()) {
            Some(why) if scene.solver.method == crate::ode::Method::ExactModal => Err(
                Error::Input(format!("scene {}: `solver.method`: {why}", scene.name)),
            ),
            _ => Ok(scene),
        }
    }

    /// The beam's lowest circular frequency, kept.
    fn lowest_omega(&self, b: &BeamScene) -> Option<f64> {
        kept(&self.lowest, format!("{:?}", b.beam), || {
            lowest_omega(&b.beam)
        })
    }

    /// How far the beam's static response is from linear ([`nonlinearity`]), kept.
    fn gap(&self, b: &BeamScene) -> Option<f64> {
        let key = format!(
            "{:?} {:?} {:?} {:?}",
            b.beam,
            b.loads,
            weight_at_once(b),
            b.planning_points()
        );
        kept(&self.gaps, key, || nonlinearity(b))
    }

    /// Whether the exact beam folds under what rides on it ([`FOLDING_GAP`]), with nothing
    /// switched on or off (whose steps are chosen for every mode it excites). Held along the
    /// axis at both ends it does not fold but stretches: its gap from the linear beam is the
    /// axis' tension stiffening it, and it vibrates about its deflected state. Under moving
    /// forces at 5 to 40 m/s (a 12 m beam of 1.3 t under three 50 kN axles, D44's section
    /// clamped–clamped and pinned–pinned under 1 MN, a 30 m beam under two 100 kN axles, a
    /// light 15 m clamped–pinned one under 20 kN; gaps 0.24 to 0.89) ESDIRK4 at a
    /// three-hundredth of the accuracy comes within 1.2·10⁻⁵ of a three-thousandth in every
    /// number the run reports, in 1.8 to 5 times fewer steps; the 30 m beam that swings ±10 m
    /// after a 40 t moving-force disk on a roller (7.9·10⁻³ off at the three-hundredth), held
    /// pinned at both ends (gap 0.92): within 1.1·10⁻⁴, the deck's numbers 1.9·10⁻⁵.
    fn folds(&self, b: &BeamScene) -> bool {
        !b.load_switched() && self.bend(b) == Bend::Folds
    }

    /// How far the exact beam bends from linear under its loads, and how it is held.
    fn bend(&self, b: &BeamScene) -> Bend {
        if b.beam.model != BeamModel::Exact {
            return Bend::Slight;
        }
        let gap = self.gap(b);
        if gap.is_some_and(|g| g > FOLDING_GAP) {
            if b.beam.holds_u_at_both_ends() {
                Bend::Stretches
            } else {
                Bend::Folds
            }
        } else if moving(b)
            && !b.load_switched()
            && b.beam.supports.contains(&Support::Free)
            && gap.is_some_and(|g| !model_choice::linear_enough(g, b.accuracy))
        {
            Bend::Whips
        } else {
            Bend::Slight
        }
    }

    /// The plan, step by step: the mesh, the beam model, ρ∞, the response's size, the method,
    /// the tolerances; each only where the scene leaves it out.
    fn plan_checked(&self, checked: Checked) -> Result<Scene, Error> {
        let Checked {
            mut scene,
            elements,
            order,
            multiple,
            model_given,
            rtol_given,
            atol_given,
            rho_inf_given,
            method_given,
        } = checked;
        let Model::Beam(b) = &mut scene.model else {
            return Ok(scene);
        };
        if elements.is_none() || order.is_none() {
            self.choose_mesh(b, elements, order, multiple, false);
        }
        let meshed_as = b.beam.model;
        if !model_given || b.beam.model == (BeamModel::Modal { modes: 0 }) {
            self.choose_model(b, model_given)
                .map_err(|why| Error::Input(format!("scene {}: {why}", scene.name)))?;
        }
        if elements.is_none() && self.bends(b) {
            let model = std::mem::replace(&mut b.beam.model, meshed_as);
            self.choose_mesh(b, elements, order, multiple, true);
            b.beam.model = model;
        }
        if !rho_inf_given {
            self.choose_rho_inf(b);
        }
        self.size_response(b);
        if !method_given {
            self.choose_method(b, &mut scene.solver);
        }
        if !rtol_given {
            let lowest = || self.lowest_omega(b);
            choose_tolerances(b, &mut scene.solver, atol_given, || self.bend(b), lowest);
        }
        if let Some(rounded) = kink_rounded_off(b) {
            b.plan_warnings.push(damped_kink(rounded));
        }
        let far = b.load_switched() && matches!(self.bend(b), Bend::Stretches | Bend::Folds);
        if let Some(gap) = self.gap(b).filter(|_| far) {
            b.plan_warnings.push(switched_far_from_linear(gap));
        }
        Ok(scene)
    }

    /// Whether loads move along an exact beam that bends visibly from linear under them
    /// (`MovingLoads::bent`): its mesh is chosen again once the model is.
    fn bends(&self, b: &BeamScene) -> bool {
        b.beam.model == BeamModel::Exact
            && moving(b)
            && self
                .gap(b)
                .is_some_and(|g| !model_choice::linear_enough(g, b.accuracy))
    }

    /// The elements and their degree, where the scene leaves either out.
    fn choose_mesh(
        &self,
        b: &mut BeamScene,
        elements: Option<usize>,
        order: Option<usize>,
        multiple: usize,
        bent: bool,
    ) {
        let (weight, xs) = (riding_weight(b), b.planning_points());
        // A switched load excites every mode, and the probes read their shapes and slopes as
        // under moving loads. On the frequencies' mesh alone, 200 kN released on a 40 m steel
        // beam 6.3·10⁻² off linear read the envelope's largest acceleration 1.4·10⁻³ off twice
        // the elements (1.2·10⁻⁴ on the mesh this takes), and 100 kN released on a 25 m
        // concrete span midspan's rotation 1.5·10⁻³ of the largest off (1.3·10⁻⁴); C1–C3 take
        // 12 elements where 6 held. Every excited mode's slopes, as moving loads on a bent beam
        // take them, would put B1–B3 on 48 elements where 12 hold.
        let moving = (moving(b) || b.load_switched()).then_some(MovingLoads {
            vehicles: !b.vehicles.is_empty(),
            cutoff_hz: b.acceleration_cutoff_hz,
            bent,
        });
        let key = format!(
            "{:?} {elements:?} {order:?} {:?} {weight:?} {xs:?} {:?} {multiple} {:?} {moving:?}",
            b.beam, b.loads, b.accuracy, b.start
        );
        let d = kept(&self.chosen, key, || {
            choose(
                &b.beam, elements, order, &b.loads, weight, &xs, b.accuracy, multiple, b.start,
                moving,
            )
        });
        b.beam.elements = d.elements;
        b.beam.order = d.order;
        b.discretisation = Some(d);
    }

    /// The beam model (and a modal beam's modes), or why no model carries the scene.
    fn choose_model(&self, b: &mut BeamScene, model_given: bool) -> Result<(), String> {
        let xs = b.planning_points();
        let inputs = model_choice::ModelInputs {
            spec: &b.beam,
            given: model_given.then_some(b.beam.model),
            loads: &b.loads,
            weight: riding_weight(b),
            at_once: weight_at_once(b),
            followers: followers(b),
            xs: &xs,
            accuracy: b.accuracy,
            start: b.start,
            thesis_coupling: b.disks.iter().any(|d| d.coupling == Coupling::Thesis),
            cutoff: b.acceleration_cutoff_hz,
        };
        // The key is every input of the choice: a sweep's cases share one planner, and a case
        // that differs in any of them (the coupling alone) chooses again.
        let key = format!("model {inputs:?}");
        let (mut model, mut why, recount, uncarried, gap) = kept(&self.models, key, || {
            let c = model_choice::choose(&inputs);
            let recount = c.recount.map(Arc::new);
            (c.model, c.why, recount, c.uncarried, c.static_gap)
        });
        if let Some(why) = uncarried {
            return Err(why);
        }
        if let (Some(r), Some(v)) = (&recount, passing_speed(b)) {
            (model, why) = r.at(Some(v));
        }
        b.left_out_share = match (&recount, model) {
            (Some(r), BeamModel::Modal { modes }) => Some(r.shares.left_out(modes)),
            _ => None,
        };
        b.beam.model = model;
        b.model_choice = Some(why);
        b.static_gap = gap;
        Ok(())
    }

    fn choose_rho_inf(&self, b: &mut BeamScene) {
        let key = format!(
            "{:?} {:?} {:?} {:?} {:?} {:?}",
            b.beam,
            b.loads,
            (riding_weight(b), weight_at_once(b)),
            b.planning_points(),
            b.accuracy,
            b.start
        );
        let (rho, why) = kept(&self.dampings, key, || rho_inf_for(b, || self.gap(b)));
        b.rho_inf = rho;
        b.rho_inf_chosen = Some(why);
    }

    /// The response's size the tolerances are measured against: the largest static
    /// displacement at a probe, shrunk to the impulse's share for a crossing shorter than the
    /// beam's first period.
    fn size_response(&self, b: &mut BeamScene) {
        let (weight, xs) = (riding_weight(b), b.planning_points());
        let key = format!("{:?} {:?} {weight:?} {xs:?}", b.beam, b.loads);
        let response = kept(&self.responses, key, || {
            response_size(&b.beam, &b.loads, weight, &xs)
        });
        b.response = response.map(|(size, _)| size);
        b.response_turned = response.is_some_and(|(_, turned)| turned);
        b.passage = loaded_for(b).and_then(|crossing| {
            let share = passage_share(self.lowest_omega(b)?, crossing);
            (share < 1.0).then_some((share, crossing))
        });
        if let (Some(size), Some((share, _))) = (b.response, b.passage) {
            b.response = Some(size * share);
        }
    }

    /// The integrator, where the scene names none: exact where it applies, ESDIRK4 where a
    /// second-order method's phase or nonlinear error would pass the accuracy, else the default.
    fn choose_method(&self, b: &BeamScene, solver: &mut SolverSettings) {
        let thesis = b.disks.iter().any(|d| d.coupling == Coupling::Thesis);
        let chosen = if b.exact_modal_refusal().is_none() {
            Some((Method::ExactModal, EXACT_MODAL))
        } else if thesis && !damped_by_the_scene(b) {
            Some((Method::Esdirk4, THESIS))
        } else if b.rolls_with_inertia() && b.vehicles.is_empty() && !damped_by_the_scene(b) {
            Some((Method::Esdirk4, ROLLING_CONTACT))
        } else if !b.vehicles.is_empty() && !damped_by_the_scene(b) {
            Some((Method::Esdirk4, VEHICLES))
        } else if b.carries_moving_masses() && b.vehicles.is_empty() && !damped_by_the_scene(b) {
            Some((Method::Esdirk4, MOVING_MASSES))
        } else if b.vehicles.is_empty() && !damped_by_the_scene(b) && self.folds(b) {
            Some((Method::Esdirk4, FOLDING))
        } else if b.vehicles.is_empty() && !damped_by_the_scene(b) && b.load_switched() {
            Some((Method::Esdirk4, SWITCHED))
        } else if b.vehicles.is_empty()
            && (!damped_by_the_scene(b) || b.beam.damping.is_some())
            && !b.load_switched()
            && b.carries_moving_loads()
        {
            Some((Method::Esdirk4, MOVING_FORCES))
        } else {
            None
        };
        if let Some((method, why)) = chosen {
            solver.method = method;
            solver.method_chosen = Some(why.to_string());
        }
        if solver.method != Method::ExactModal && b.free_vibration_is_modal() {
            solver.free_vibration_chosen = Some(FREE_EXACT.to_string());
        }
    }
}

/// rtol from the accuracy and, unless the scene gives it, atol from the response's size.
fn choose_tolerances(
    b: &BeamScene,
    solver: &mut SolverSettings,
    atol_given: bool,
    bend: impl Fn() -> Bend,
    lowest_omega: impl Fn() -> Option<f64>,
) {
    let (rtol, why) = rtol_for(b, solver.method, bend);
    solver.rtol = rtol;
    solver.rtol_chosen = Some(why.to_string());
    if !atol_given {
        if let Some((size, why)) = atol_for(b) {
            solver.atol = rtol * size;
            solver.atol_scale = Some(size);
            solver.velocity_rate = rings_freely(b).then(lowest_omega).flatten();
            // Generalized-α and exact-modal measure no velocities.
            let measured = !matches!(solver.method, Method::GenAlpha | Method::ExactModal);
            solver.atol_chosen = Some(match solver.velocity_rate.filter(|_| measured) {
                Some(w) => format!("{why}; {}", velocities_at(w)),
                None => why,
            });
        }
    }
}

/// Whether moving forces alone cross an undamped beam, which then rings, its speeds ω₁ times
/// its displacements: there a velocity's error is measured against ω₁ atol. In metres per
/// second, atol held that ringing ω₁ times tighter than its displacement and set every step:
/// three 100 kN axles at 30 m/s over D44's section took 130 846 ESDIRK4 steps so, nearly every
/// error norm the velocities'; against ω₁ atol 33 744, every headline alike within 6e-7.
/// Elsewhere the speeds carry what the run reports in their own right, and ω₁ atol missed the
/// accuracy: a disk with inertia (D44's contact force, 2.1e-3), a switched load (C1's
/// envelope of φ, 1.1e-3), the rubber beam's accelerations (1.5e-3), a slow crossing of a
/// damped deck, quasi-static far below ω₁ (1.3e-3); vehicles' bodies ring below ω₁.
fn rings_freely(b: &BeamScene) -> bool {
    b.carries_moving_loads()
        && !b.rolls_with_inertia()
        && !b.carries_moving_masses()
        && !b.load_switched()
        && b.vehicles.is_empty()
        && b.beam.damping.is_none()
}

fn velocities_at(omega: f64) -> String {
    format!("velocities against omega1 atol ({omega:.3e} rad/s), the speed of a vibration of amplitude atol in the first mode, as atol in metres per second would hold the velocities omega1 times tighter than the displacements")
}

/// Why the plan integrates a modal beam under moving forces and loads exactly.
const EXACT_MODAL: &str = "exact-modal: the modal beam under moving forces and loads is uncoupled damped oscillators under a force of time alone, which it integrates in closed form between the axles' crossings of the nodes: exact whatever rtol, where a time-stepped run carries the error of every step into what it reports after the loads have moved along";

/// Why the plan integrates the thesis coupling with the fourth-order ESDIRK in its (s, ṡ) form,
/// as it does a rolling disk. Generalized-α with the planned ρ∞ = 0.9 converges slowly to the
/// undamped solution: on D44's 10 exact elements set down at rest, midspan's acceleration at
/// some output time was 3.7·10⁻³ of its largest off at a thousandth of the accuracy and still
/// 1.0·10⁻³ at rtol 3·10⁻¹⁰; started carrying the disk, 7.8·10⁻² at a thousandth. ESDIRK4 on
/// the (s, ṡ) form and on the published 3n + 6 system, both at rtol 10⁻⁸, agree within
/// 4·10⁻⁷, and that is the reference.
const THESIS: &str = "esdirk4: the thesis coupling in its (s, ṡ) form is a disk rolling on the axis, and its contact force rings in every mode the beam holds as a rolling disk's does; generalized-α with the planned rho_inf = 0.9 read D44's midspan acceleration at some output time 3.7e-3 of its largest off at a thousandth of the accuracy on 10 exact elements set down at rest, 7.8e-2 started carrying the disk, where the fourth-order steps come within 7.5e-4 and 1.2e-4 (dopri5 and trbdf2 integrate the published 3n + 6 system instead)";

/// Why the plan integrates a rolling disk with the fourth-order ESDIRK, on a modal beam or a
/// mesh, unless the scene asks for numerical damping itself. On D44's linearly responding mesh
/// (10 exact elements) started carrying the disk, generalized-α with the planned ρ∞ = 0.9 read
/// the deck's largest acceleration 9 % low and the largest contact force 4·10⁻³ of the weight
/// high; the fourth-order steps there come within 1.1·10⁻⁴ and 7·10⁻⁴, at 1.6 times the steps.
const ROLLING_CONTACT: &str = "esdirk4: a rolling disk's contact force is its mass times the beam's acceleration under it, which rings in every mode the beam holds from the moment the disk is set down; generalized-α carries that ringing with the phase error of every step (at a three-hundredth of the accuracy it read the deck's largest acceleration 1.2 % low on D44's modal beam, 4 % on the rubber beam and twice the converged on the zip-line; with rho_inf = 0.9, 9 % low on D44's exact mesh started carrying the disk), where the fourth-order method at a thirtieth of the accuracy comes within 6.9e-4 of the weight in the contact force and 6e-4 in the acceleration";

/// Why the plan integrates vehicles with the fourth-order ESDIRK unless the scene asks for
/// numerical damping itself. A wheel with a mass of its own takes an impulse at each kink of its track, which
/// sets every mode of the deck ringing, and generalized-α (ρ∞ = 1) carries that ringing with
/// the phase error of every step: at a three-thousandth of the accuracy it read midspan's
/// largest acceleration under Biggs' sprung mass on a 500 kg wheel at 5 m/s 8.7·10⁻³ off
/// (still 1.5·10⁻³ at rtol 10⁻⁹, where ESDIRK4 agrees with itself to 10⁻⁸ from rtol 10⁻⁸ to
/// 10⁻¹¹), and the body's of a cart braking to a stop on a cantilever 2.9·10⁻³ off. The
/// fourth-order steps at a thousandth hold every number of those scenes, of the railway
/// study, of the railway cars on 0.46 m disk wheels hopping at the abutment at 121 m/s and of
/// a van hopping over a pothole within 6.4·10⁻⁵ of ESDIRK4 and generalized-α at rtol 10⁻¹⁰
/// (each number against the largest of its kind), and one railway car at 300, 600, 1000 and
/// 3000 m/s within 1.3·10⁻⁴, in 74 to 181 steps (generalized-α at a three-thousandth of the
/// accuracy and (300 m/s / v)² of that took 954 at 1000 m/s).
const VEHICLES: &str = "esdirk4: the vehicles' bodies vibrate on their suspensions over the whole run and the deck under them in every mode it holds, and a wheel with a mass of its own sets every mode ringing where its track turns; generalized-alpha carries both with the phase error of every step, adding up over their periods (at a three-thousandth of the accuracy it read the deck's largest acceleration under Biggs' sprung mass at 100 m/s 1.4e-3 low, in the free vibration after the wheel left, and at 5 m/s on a 500 kg wheel 8.7e-3 off), where the fourth-order steps at a thousandth come within 6.4e-5 of every number the vehicle scenes report, and within 1.3e-4 for a railway car at 300 to 3000 m/s";

/// Why the plan integrates a train of moving masses with the fourth-order ESDIRK unless the
/// scene asks for numerical damping itself. Each axle's mass follows the beam, turning with
/// the slope at every node of the mesh (the modes' shapes are C⁰ there) and dropping off at the
/// far support, and the deck's accelerations carry those impulses. Generalized-α (ρ∞ = 1) at a
/// three-hundredth of the accuracy read them up to 10⁻² of the largest acceleration off: two
/// 2 t axles at 20 m/s over D44's section (modal beam) 5.8·10⁻³ at midspan and 10⁻² at the
/// quarter point; two 10 t axles (exact beam) 6.2·10⁻³, the least deflection 1.9·10⁻³; at a
/// three-thousandth still 6.4·10⁻³. The fourth-order steps (at a ten-thousandth of the
/// accuracy, `rtol_for`) come within 3.6·10⁻⁴ of the quarter point's, at 5 to 9 times
/// generalized-α's cost.
const MOVING_MASSES: &str = "esdirk4: each moving mass follows the beam, turning with its slope at every node of the mesh and dropping off at the far support, impulses that ring in the deck's accelerations, which generalized-alpha carries with the phase error of every step (at a three-hundredth of the accuracy it read the largest accelerations under two axles over D44's section up to 1e-2 off, at a three-thousandth 6.4e-3), where the fourth-order steps at a ten-thousandth come within 3.6e-4";

/// Why the plan steps a load switched on or off with the fourth-order ESDIRK. Undamped,
/// generalized-α keeps every mode the load sets ringing with the phase error of every step, its
/// global error falling as rtol^(2/3): at the default accuracy it needs a ten-thousandth of it
/// (B1–B3 and C1–C3 within 3.6–5.0·10⁻⁴ of their family's largest, C1 in 1.64 M steps, B1 in
/// 1.13 M), where ESDIRK4 at a thirtieth comes within 1.3–3.9·10⁻⁴ in 104 000–223 000 steps, at
/// half the time (at a tenth C1's tip rotation missed by 1.9·10⁻³); the plan takes a
/// hundredth, which holds the history's rows too (`rtol_for`). Below the default accuracy
/// generalized-α no longer holds them: C3's cantilever on 4 elements over 1.5 s asked for 10⁻⁴
/// and 10⁻⁵ (rtol a ten-thousandth of it) read the largest rotations 3.0·10⁻⁴ and 4.2·10⁻⁴ of
/// the largest off, B2 asked for 10⁻⁴ 2.7·10⁻⁴, against ESDIRK4 at rtol 10⁻⁹ or 10⁻¹⁰ of the
/// same scene; ESDIRK4 at a thousandth of the accuracy comes within 2.6·10⁻⁵, 2.6·10⁻⁶ and
/// 1.4·10⁻⁵.
const SWITCHED: &str = "esdirk4: a load switched during the run excites every mode of the mesh, and undamped generalized-alpha carries them with the phase error of every step, its global error falling as rtol^(2/3): at the default accuracy it needs a ten-thousandth of it (B1-B3 and C1-C3 within 5e-4, C1 in 1.64 M steps), where the fourth-order steps at a thirtieth come within 3.9e-4 in at most 223 000 steps (the plan takes a hundredth, which the history's rows need); asked for 1e-4 and 1e-5 (the cantilever C3 on 4 elements) generalized-alpha read the largest rotations 3.0e-4 and 4.2e-4 off at a ten-thousandth, the fourth-order steps at a thousandth 2.6e-5 and 2.6e-6";

/// The static gap (the exact static deflection this share of it off the linear one) past which
/// the exact beam folds under its loads and the plan steps it with ESDIRK4: D44's section under
/// one moving force at 4 m/s for 1 s, gaps 0.032, 0.2 and 0.6, generalized-α (ρ∞ = 1) at a
/// three-hundredth of the accuracy missed midspan's least deflection by 7·10⁻⁵, 4.1·10⁻⁴ and
/// 4.6·10⁻³ of it (over 3 s at 0.95, 7.9·10⁻³) against ESDIRK4 at rtol 10⁻⁸, the energy
/// balance drifting by 7·10⁻⁴ at 0.6; ESDIRK4 at the same rtol lands within 3·10⁻⁶ there, at
/// four times the cost; the milder gaps keep the cheaper steps. Its rtol: [`rtol_for`].
const FOLDING_GAP: f64 = 0.1;

/// How far an exact beam bends from linear under its loads ([`FOLDING_GAP`]), where the steps'
/// tolerance depends on it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bend {
    /// Within a tenth of the linear beam's static deflection, or not the exact beam.
    Slight,
    /// Further, held along its axis at both ends: the axis' tension stiffens it.
    Stretches,
    /// Further, with an end free to draw in.
    Folds,
    /// Less far but beyond the accuracy, with a free end that moving loads cross: the tip
    /// whips as each leaves or comes on.
    Whips,
}

/// What the plan says of an exact beam far from linear under a load switched during the run,
/// whose extremes neither the mesh rule nor an affordable rtol settles. A 10 m clamped steel
/// cantilever (A 149 cm², I 2.5·10⁻⁴ m⁴, undamped) whose 1.2 MN tip load is taken off after
/// 0.3 s (gap 0.26) read its largest acceleration 4.2·10⁻³, 2.8·10⁻³ and 1.1·10⁻² off at rtol
/// 3.3·10⁻⁵, 3.3·10⁻⁶ and 3.3·10⁻⁷, 5·10⁻⁵ at 10⁻⁹ (against 10⁻¹⁰, 1.2 M steps); a 20 m
/// pinned steel beam (A 181 cm², I 4.3·10⁻⁴ m⁴) under 1 MN for 0.15 s (gap 0.71), on the 16
/// elements planned, its envelope's least rotation 1.5·10⁻³ off 32 at rtol 10⁻⁹.
fn switched_far_from_linear(gap: f64) -> String {
    format!(
        "the exact beam is far from linear under a load switched during the run (its static deflection {:.2} off the linear one): it rings in every mode the load excites, passing energy between them, and its extremes can move with the mesh and the steps by more than the accuracy (a 20 m pinned beam stretched under 1 MN: the envelope's least rotation 1.5e-3 off twice the planned mesh; a 10 m cantilever folded by a 1.2 MN tip load taken off after 0.3 s: the largest acceleration 1.1e-2 off at a three-thousandth of the accuracy); runs with `track.beam.elements` doubled and at a tenth of `solver.rtol` show what a scene's move by",
        gap
    )
}

/// What the mesh may round off of the kink a train's moving force at a point makes in the
/// axis, as a share of the largest static deflection at the probes, where a stiffness-
/// proportional damping makes the deflection under the force feel it and a quarter of the
/// share passes the accuracy: see [`damped_kink`]. Shear kinks the axis under a force P by
/// κ = P/(G Av); the elements hold it at their nodes and, interpolating at the Gauss–Lobatto
/// nodes of degree p, miss it anywhere between by at most κ h/(4p) (0.25, 0.096, 0.055,
/// 0.024 κ h for p = 1, 2, 4, 10). Both κ and the deflection grow with P: the share is the
/// beam's and the mesh's.
fn kink_rounded_off(b: &BeamScene) -> Option<f64> {
    let train = b
        .train
        .as_ref()
        .filter(|t| t.model == TrainModel::MovingForce)?;
    let stiffness_damped = match b.beam.damping? {
        DampingSpec::Ratio { .. } => true,
        DampingSpec::Rayleigh { beta, .. } => beta > 0.0,
    };
    let force = train.loads.iter().fold(0.0_f64, |m, p| m.max(p.abs()));
    let length = (b.beam.to[0] - b.beam.from[0]).hypot(b.beam.to[1] - b.beam.from[1]);
    let gav = b.beam.section.gav.min(shear_rigid_limit(&b.beam, length));
    let deflection = b.response? / b.passage.map_or(1.0, |(share, _)| share);
    if !(deflection > 0.0 && deflection.is_finite()) {
        return None;
    }
    let h = length / b.beam.elements as f64;
    let share = force / gav * h / (4.0 * b.beam.order as f64) / deflection;
    // The deflection under the force moved by up to a quarter of the share (see
    // [`damped_kink`]).
    (stiffness_damped && share > 4.0 * b.accuracy).then_some(share)
}

/// The warning of [`kink_rounded_off`]. Three 20 kN axles at 80 m/s over three 6 m spans of a
/// concrete section 1.95 m deep (κ h/(4p) 5.6·10⁻³ of the deflection on the 48 elements the
/// modes chose), as the linear mesh: the deepest deflection 2.8·10⁻⁴ apart on 48 and 96
/// elements undamped, 1.4·10⁻³ with β = 5·10⁻⁵ s and 1.1·10⁻³ with 5·10⁻⁴ s, converging as h²
/// (1.3·10⁻³ at 48, 2.8·10⁻⁴ at 96 elements from 192's with 5·10⁻⁴ s); the modal beam moves
/// as far. The damping's stiffness term resists the shear's rate, which a moving kink makes
/// large right under the force, and the mesh resolves that only as it resolves the kink.
/// Three damped continuous beams of the same concrete rounding off 1.1·10⁻³ to 1.3·10⁻³ moved
/// their deepest deflection by 5·10⁻⁶, 1.2·10⁻⁴ and about 3·10⁻⁴ from the planned mesh to
/// four times its elements: up to a quarter of the share.
fn damped_kink(share: f64) -> String {
    format!(
        "a train's axles are point forces, and shear kinks the axis under each by P/(G Av), which the mesh rounds off between its nodes by up to {share:.1e} of the largest static deflection at the probes, more than four times the accuracy; with stiffness-proportional damping (β > 0) the deflection under a moving force then moves with the mesh by up to about a quarter of that (three 20 kN axles over concrete spans 6 m long and 1.95 m deep, 5.6e-3 rounded off: the deepest deflection 1.1e-3 to 1.4e-3 apart on 48 and 96 elements, converging as the square of the element length); a run with `track.beam.elements` doubled shows what a scene's numbers move by"
    )
}

/// Why the plan integrates an exact beam that folds under its loads with the fourth-order
/// ESDIRK ([`FOLDING_GAP`]).
const FOLDING: &str = "esdirk4: the exact beam folds under its loads (its static deflection more than a tenth off the linear one, an end free to draw in), where generalized-alpha's steps, each within rtol, add up to more than the accuracy over the crossing (D44's section under one moving force, the exact static deflection 0.6 off the linear one: midspan's least deflection 4.6e-3 off at a three-hundredth of the accuracy), and the fourth-order steps at the same rtol land within 3e-6";

/// Why the plan integrates moving forces with the fourth-order ESDIRK where `exact-modal` does not
/// take them (a mesh, or a moving-force disk) and the plan leaves generalized-α undamped (ρ∞ = 1: a
/// modal beam, a train, or a mesh that responds nonlinearly) or the beam is damped, with nothing
/// switched and no vehicles. Each force crossing a node of the mesh turns the load vector's rate,
/// which sets the highest modes ringing, and generalized-α (ρ∞ = 1) carries that ringing into the
/// accelerations with the phase error of every step: at a three-hundredth of the accuracy, three
/// 100 kN axles at 10 m/s over D44's section read midspan's largest acceleration 10 % low (exact
/// beam; 8.5 % on the linear one), one 1 MN axle at 50 m/s 6.5·10⁻³ off, a 1.5 t moving-force disk
/// on the modal beam 2.6·10⁻², with the deflections within 1.4·10⁻⁴; at a ten-thousandth still
/// 1.8·10⁻³. The fourth-order steps at the same rtol land within 2.5·10⁻⁴ of every headline, at 4
/// to 28 times the cost. On a damped mesh (Rayleigh's βK damps its highest modes) generalized-α at
/// ρ∞ = 0.9 and accuracy/1000 read the quarter point's largest acceleration under D44's
/// moving-force disk 1.5·10⁻² off with 0.5 % damping and 5.5·10⁻³ with 2 % (at ρ∞ = 1: 6.5·10⁻³; at
/// accuracy/10000: 1.1·10⁻³), where the fourth-order steps at accuracy/300 land within 2.1·10⁻⁴ and
/// 5.4·10⁻⁴ in fewer steps (599 and 394 against 1152 and 862). A moving-force disk on an undamped
/// mesh that responds linearly gets them too: generalized-α at the ρ∞ = 0.9 planned for it held
/// every extreme of D44's within 2.1·10⁻⁴ at accuracy/1000, but a history row carries every earlier
/// step's phase error (the accelerations 2.1·10⁻³ and 3.0·10⁻³ off on 10 and 16 exact elements;
/// started static, 3.5·10⁻³ even at accuracy/10000), and it converges to the damped model's answer
/// (6.9·10⁻⁴ from the undamped one in the accelerations). ESDIRK4 at accuracy/300 holds every row
/// within 8.9·10⁻⁴ (started static; 1.5·10⁻⁴ from rest) in about the time generalized-α takes at
/// accuracy/10000 (1.11 s against 0.96 s on the 10 elements), though where the shear is stiff (G ×
/// 10⁴) it takes 2.2–2.3 times the steps, the damped steps 1.15 to 1.8 times.
const MOVING_FORCES: &str = "esdirk4: each force crossing a node of the mesh sets its highest modes ringing, which generalized-alpha carries into the accelerations with the phase error of every step (at a three-hundredth of the accuracy it read midspan's largest acceleration under three 100 kN axles over D44's section 10 % low, under a moving-force disk on its modal beam 2.6e-2 high, the deflections within 1.4e-4), where the fourth-order steps at the same rtol land within 2.5e-4 of every headline";

/// Why the plan integrates a modal beam's free vibration after its riders leave exactly.
const FREE_EXACT: &str = "exact-modal once the riders have left: the modal beam alone is uncoupled damped oscillators, whose free vibration a time-stepped method of second order would carry with the phase error of the highest mode the accelerations report, growing with every period (on D44 at the defaults the deck's largest acceleration, 2 s after the disk left, came out 5 % low)";

/// What rides on the beam, as the static load the mesh and model are chosen for: the disks'
/// weight, or the heaviest of a train's axles and the vehicles' wheels, whichever is larger,
/// standing at each probe.
fn riding_weight(b: &BeamScene) -> Option<f64> {
    let axles = b
        .train
        .iter()
        .flat_map(|t| t.loads.iter())
        .chain(b.vehicles.iter().flat_map(|v| v.static_loads.iter()))
        .fold(None, |m: Option<f64>, p| {
            Some(m.unwrap_or(0.0).max(p.abs()))
        });
    let disks =
        (!b.disks.is_empty()).then(|| b.disks.iter().map(|d| d.disk.mass * d.gravity).sum::<f64>());
    match (disks, axles) {
        (Some(d), Some(a)) => Some(d.max(a)),
        (d, a) => d.or(a),
    }
}

/// What rides on the beam as the static load its nonlinearity is measured under: as
/// [`riding_weight`], but a train by the axles a span's length of track holds at once. The
/// stretching of a beam held at both ends grows as the square of its deflection: four 50 kN
/// axles within 7.5 m on a 30 m deck pinned at both ends measured 8.8e-5 one by one, 1.4e-3
/// together, and the linear modes read the crossing's deflections 2e-3 and its largest
/// accelerations 1e-2 off the exact beam's.
fn weight_at_once(b: &BeamScene) -> Option<f64> {
    let span = (b.beam.to[0] - b.beam.from[0]).hypot(b.beam.to[1] - b.beam.from[1]);
    let train = b.train.as_ref().map(|t| t.heaviest_within(span));
    match (riding_weight(b), train) {
        (Some(w), Some(t)) => Some(w.max(t)),
        (w, t) => w.or(t),
    }
}

/// Whether something on the beam follows its kept modes: a disk that is not a moving force,
/// a vehicle's wheels, a train of moving masses.
fn followers(b: &BeamScene) -> bool {
    !b.vehicles.is_empty()
        || b.disks.iter().any(|d| d.coupling != Coupling::MovingForce)
        || b.train
            .as_ref()
            .is_some_and(|t| t.model == TrainModel::MovingMass)
}

/// How long the beam carries what moves over it, from the first entry to the last exit,
/// where that is all it carries: a train or vehicles that cross it at speed. `None` with a
/// disk, a load, or a vehicle that slows down or stays on the deck, whose response is as large
/// as the static one.
fn loaded_for(b: &BeamScene) -> Option<f64> {
    if !b.disks.is_empty() || !b.loads.is_empty() || (b.train.is_none() && b.vehicles.is_empty()) {
        return None;
    }
    let length = (b.beam.to[0] - b.beam.from[0]).hypot(b.beam.to[1] - b.beam.from[1]);
    let mut spans = Vec::new();
    if let Some(train) = &b.train {
        (train.speed > 0.0).then_some(())?;
        spans.push((0.0, (length + train.length()) / train.speed));
    }
    for v in &b.vehicles {
        (v.speed > 0.0 && v.acceleration >= 0.0).then_some(())?;
        let spread = v.axles.iter().map(|a| a.x).fold(0.0, f64::max);
        let enters = v.time_at(0.0).unwrap_or(0.0);
        spans.push((enters, v.time_at(length + spread)?));
    }
    let first = spans.iter().map(|s| s.0).fold(f64::INFINITY, f64::min);
    let last = spans.iter().map(|s| s.1).fold(0.0, f64::max);
    (last > first).then_some(last - first)
}

/// The speed of the moving forces where they are all that changes on the beam: a train of
/// them alone, nothing riding with inertia. The modes they leave to the static correction
/// are counted at it (`model_choice::ModeShares::count`).
fn passing_speed(b: &BeamScene) -> Option<f64> {
    let train = b.train.as_ref()?;
    (train.model == TrainModel::MovingForce && b.disks.is_empty() && b.vehicles.is_empty())
        .then_some(train.speed.abs())
}

/// How far the beam's static response to what rides on it and its loads is from linear
/// (`model_choice::nonlinearity_of`).
/// Whether anything moves along the beam: a disk, a train or a vehicle.
fn moving(b: &BeamScene) -> bool {
    !b.vehicles.is_empty() || b.train.is_some() || !b.disks.is_empty()
}

fn nonlinearity(b: &BeamScene) -> Option<f64> {
    model_choice::nonlinearity_of(&b.beam, &b.loads, weight_at_once(b), &b.planning_points())
}

/// Whether that nonlinearity is visible at the scene's accuracy, the test that also decides
/// ρ∞ ([`rho_inf_for`]): a large deflection, as on the rubber beam and the zip-line.
pub fn responds_nonlinearly(b: &BeamScene) -> bool {
    nonlinearity(b).is_some_and(|g| !model_choice::linear_enough(g, b.accuracy))
}

/// The choice kept under `key`, or `choose`'s, kept.
fn kept<T: Clone>(
    choices: &Mutex<BTreeMap<String, T>>,
    key: String,
    choose: impl FnOnce() -> T,
) -> T {
    if let Some(known) = choices.lock().ok().and_then(|c| c.get(&key).cloned()) {
        return known;
    }
    let chosen = choose();
    if let Ok(mut c) = choices.lock() {
        c.insert(key, chosen.clone());
    }
    chosen
}

impl Scene {
    /// Read, check and plan a scene file.
    pub fn load(path: &Path) -> Result<Scene, Error> {
        Planner::default().plan(&SceneSpec::load(path)?)
    }

    /// Read, check and plan a scene from text; `file` names the source in messages, `stem` is
    /// the default scene name.
    pub fn parse(text: &str, file: &str, stem: &str) -> Result<Scene, Error> {
        Planner::default().plan(&SceneSpec::parse(text, file, stem)?)
    }
}

/// ρ∞ of generalized-α for a beam scene that leaves it out, and why.
/// - A finite-element beam (exact or linear) under loads that only move holds shear and axial
///   modes far above anything the loads excite. Undamped (ρ∞ = 1) they keep what the rolling
///   contact puts into them: D44 with G × 10⁴ took 5001 steps against 2423 at the real G, the
///   error estimate spread over modes of 100–800 Hz and Newton stalling on the shear. With
///   ρ∞ = 0.9 it takes 1140 against 1289 (docs/numerics.md, "Generalized-α"). Any damping removes the growth
///   (0.98: 3377 against 2945; 0.95: 1603 against 1983); 0.9 also halves the real beam's
///   steps and lands within 0.05 of the accuracy, where 0.8 takes little more off. It damps
///   a mode the step resolves only at third order in ω h, which the error estimate watches.
/// - Only where the beam responds linearly at the accuracy asked (`model_choice`'s measure):
///   then the modes the loads excite are the linear ones the mesh was chosen for, and those
///   above carry nothing. A nonlinear beam passes energy between its modes, and damping the
///   high ones takes from the response: the rubber beam's rebound at midspan lost 12 % at
///   ρ∞ = 0.9.
/// - A load switched on or off excites every mode of the mesh, and the damped share of them
///   rides on the peak (`rtol_for`): there ρ∞ = 1. A modal beam holds no such modes: ρ∞ = 1.
/// - A train's axles are point loads: each crossing a node kinks the load vector's rate and
///   excites every mode of the mesh, and the highest carry part of the acceleration at the
///   node. Three 15 kN axles at 30 m/s over D44's section (exact, responding linearly):
///   midspan's largest acceleration 3.2·10⁻² of the envelope's off at ρ∞ = 0.9 and
///   accuracy/300 (4·10⁻³ at accuracy/1000, 5·10⁻⁴ at accuracy/3000), against ESDIRK4 at
///   rtol 10⁻⁹; there ρ∞ = 1, and the plan steps it with ESDIRK4 (`MOVING_FORCES`). A disk's
///   load spreads over its contact patch, whose rate does not kink.
pub fn rho_inf_for(scene: &BeamScene, gap: impl FnOnce() -> Option<f64>) -> (f64, String) {
    let undamped = |why: &str| (1.0, format!("1, no numerical damping: {why}"));
    if matches!(scene.beam.model, BeamModel::Modal { .. }) {
        return undamped("the modal beam holds no modes far above what the loads excite");
    }
    if scene.load_switched() {
        return undamped("a load switched during the run excites every mode of the mesh, and what damping takes of them would ride on the peak");
    }
    if scene.train.is_some() {
        return undamped("a train's axles are point loads, and each crossing a node of the mesh excites every mode it holds, whose highest carry part of the acceleration at the node (three 15 kN axles at 30 m/s over D44's section: midspan's largest acceleration 3.2e-2 off at rho_inf = 0.9)");
    }
    match gap() {
        Some(g) if model_choice::linear_enough(g, scene.accuracy) => (
            PLANNED_RHO_INF,
            format!("{PLANNED_RHO_INF}: the beam responds linearly (the exact static deflection at the probes is {g:.1e} off the linear one), so the mesh's modes above those the moving loads excite carry nothing, and undamped they keep what the rolling contact puts into them and cost steps"),
        ),
        Some(g) => undamped(&format!("the beam's response is nonlinear (the exact static deflection at the probes is {g:.1e} off the linear one), and it passes energy between its modes, so damping the high ones would take from the response")),
        None => undamped("the beam has no static response to measure its nonlinearity by"),
    }
}

/// The ρ∞ a finite-element beam under moving loads gets ([`rho_inf_for`]).
pub const PLANNED_RHO_INF: f64 = 0.9;

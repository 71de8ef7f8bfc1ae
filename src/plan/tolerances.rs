//! The steps' tolerances a beam scene gets when it leaves them out: rtol from its accuracy and
//! what it holds ([`rtol_for`], a table of rules tried in order), atol from the size of its
//! response ([`atol_for`]).

use std::cell::OnceCell;

use super::Bend;
use crate::analysis::discretisation::DEFAULT_ACCURACY;
use crate::beam::BeamModel;
use crate::coupling::Coupling;
use crate::ode::Method;
use crate::scene::BeamScene;

/// The fastest a vehicle on wheels with a mass of their own runs at a three-thousandth of the
/// accuracy (m/s): one railway car holds every number within 1.7·10⁻⁴ there.
const UNSPRUNG_SPEED: f64 = 300.0;

/// The fastest any vehicle runs at a thousandth of the accuracy under ESDIRK4 (m/s): Biggs'
/// sprung mass holds every number within 2.6·10⁻⁴ of its kind's largest at 300 m/s with the
/// factor [`vehicle_speed_factor`] sets from here.
const VEHICLE_SPEED: f64 = 150.0;

/// The finest rtol the plan sets: a ten-thousandth of the finest accuracy a scene may ask for
/// (the checker's bound), past which a step's round-off outweighs the error it is held to.
const FINEST_RTOL: f64 = 1e-11;

/// How much tighter than a thousandth of the accuracy ESDIRK4 needs rtol for vehicles: 1 up to
/// [`VEHICLE_SPEED`], that over the fastest vehicle's top speed on the deck beyond.
fn vehicle_speed_factor(b: &BeamScene) -> f64 {
    let fastest = fastest_on_deck(b, |_| true);
    if fastest > VEHICLE_SPEED {
        VEHICLE_SPEED / fastest
    } else {
        1.0
    }
}

/// The fastest the vehicles `counted` run on the deck (m/s); 0 without one.
fn fastest_on_deck(b: &BeamScene, counted: impl Fn(&crate::vehicle::Vehicle) -> bool) -> f64 {
    (b.vehicles.iter())
        .filter(|v| counted(v))
        .map(|v| b.top_speed_on_deck(v))
        .fold(0.0, f64::max)
}

/// The fastest a vehicle on wheels with a mass of their own runs on the deck (m/s); 0 without
/// one: a vehicle without unsprung masses, however fast, deals the deck no impulses.
fn unsprung_speed(b: &BeamScene) -> f64 {
    fastest_on_deck(b, |v| v.has_unsprung_mass())
}

/// How much tighter than a three-thousandth of the accuracy generalized-α (where the scene
/// gives ρ∞) needs rtol for a vehicle on wheels with a mass of their own: 1 up to [`UNSPRUNG_SPEED`], (that / speed)² beyond. Measured on one
/// railway car against ESDIRK4 at rtol 10⁻¹⁰: at a three-thousandth, 600 m/s read the deck's
/// least rotation 1.5·10⁻³ off and 3000 m/s a bogie's largest acceleration 13 times the
/// converged; with the factor, 600, 1000 and 3000 m/s land within 5.1·10⁻⁴ of each number's
/// scale (the car's bodies' largest, the wheels' static loads, midspan's largest |w|).
fn unsprung_speed_factor(b: &BeamScene) -> f64 {
    let fastest = unsprung_speed(b);
    if fastest > 0.0 {
        (UNSPRUNG_SPEED / fastest).powi(2).min(1.0)
    } else {
        1.0
    }
}

/// The rtol a beam scene gets for its accuracy ε when it leaves rtol out, and why.
/// - A rolling disk with the planned ESDIRK4: its contact force rings in every mode, and on a
///   modal beam the error norm weighs each mode by its acceleration (`contact_norm_weights`);
///   at ε/10 D44's contact force missed by 1.7 ε, at ε/30 every headline of D44, D50 (modal
///   beams) and the rubber beam lands within 0.69 ε. A row of the history carries the phase
///   error of every step before it, which an extreme hardly feels: at ε/30 midspan's
///   acceleration on D44's and D50's modal beams came 9.2 ε and 12 ε off at some output time,
///   at ε/300 0.99 ε and 1.2 ε, and at ε/1000, which the modal beam gets, within 0.36 ε (the
///   run twice as long). On a linearly responding mesh the
///   contact force also rings in the mesh's highest modes, whose phase no rtol the run can
///   afford settles: on D44's 10 and 20 exact elements started static it lands within 1.1 ε
///   of the weight at ε/30 and 1.4 ε at ε/100, the accelerations within 0.11 ε at either; D50
///   (20 m/s) misses its largest accelerations by up to 4.4 ε at ε/30 and 0.5 ε at ε/1000.
/// - With a ρ∞ < 1 the scene gives, the damped high modes that ride on a sudden load's peak
///   cost up to 2.4 ε at ε/10 (B2 at ρ∞ = 0.8) and 0.06 ε at ε/100 (REPORT.md), hence ε/100;
///   under moving loads too, where the plan has not shown the damped modes to carry nothing
///   (the rubber beam at ρ∞ = 0.8 missed by 1.4 ε at ε/30).
/// - Under moving loads the error that decides is the global one: each step's error stays
///   within rtol, but what the run reports after many steps (the residual vibration after the
///   load leaves, the peak of a train's resonant build-up, the largest acceleration) carries
///   the sum of them. At ε/30 the residual after D44's moving force missed by 2.8 ε on the
///   modal beam, and HSLM-A1's at 90 m/s by 1.8 ε on the modal beam and 1.4 ε on the
///   linear one, its rebound and its acceleration by 1.0 ε; the global error of the
///   generalized-α steps falls as rtol^(2/3), and at ε/300 these land within 0.6 ε and
///   0.4 ε. The peak alone was within 0.2 ε at ε/30.
/// - An exact beam that folds under its loads swings far from its linear modes, and its
///   accelerations carry the error of every step: under a moving force that sinks D44's
///   midspan 8.7 m they missed by 0.9 ε at ε/300, by 0.04 ε at ε/3000; a 40 t force over a
///   30 m beam of half D44's area, which swings 10 m after it, by 7.9 ε and 0.22 ε.
/// - Under the planned ρ∞ = 0.9 (a moving-force disk on a mesh that responds linearly) the
///   damping takes a share of the ringing each node crossing sets off, which shrinks with the
///   step: D44's quarter point's largest acceleration 1.1 ε off at ε/300, 0.5 ε at ε/500,
///   0.21 ε at ε/1000, at 2.2 times the steps. A row of the history carries the phase error of
///   every step before it: at ε/1000 the probes' accelerations came 2.1 ε and 3.0 ε off at
///   some output time on D44's exact meshes of 10 and 16 elements, at ε/10000 within 0.24 ε,
///   at 2.3 and 3.1 times the time, so a named generalized-α gets ε/10000; the plan steps the
///   disk with ESDIRK4 ([`MOVING_FORCES`]). Named for the thesis' coupling, it keeps ε/1000:
///   its rows converge to the undamped solution only slowly (D44 from rest, 1.0 ε off at rtol
///   3·10⁻¹⁰), so the plan steps that coupling with ESDIRK4 at ε/300 ([`THESIS`]).
/// - A load switched on or off during the run excites every mode the mesh holds, and
///   undamped they all stay in what the run reports: B1's peak read on the output grid missed
///   by 2.2 ε at ε/30 and by 0.96 ε at ε/300; located on the solution, C1–C3's largest tip
///   acceleration and rotation in the free vibration after the load is taken off missed by
///   2.0–3.5 ε at ε/1000 and land within 0.6 ε at ε/10000 (B1–B3 within 0.7 ε at either);
///   the plan steps it with ESDIRK4 at ε/100, and below the default accuracy at ε/1000
///   ([`SWITCHED`]): at ε/30 every extreme of B1–B3 lands within 0.27 ε, but a row of the
///   history carries every earlier step's phase error, and u and φ came 1.0–1.5 ε off at
///   some output time on B1–B3's planned exact meshes (C1 on 2 and 4 exact elements: 3.3 ε
///   and 2.0 ε), at ε/100 within 0.58 ε (0.60 ε and 0.96 ε), at 1.6–2.4 times the steps.
///   Damped, such a peak is not monotone in rtol (B1 at ρ∞ = 0.8: 0.54 ε, 2.3 ε, 1.3 ε at
///   ε/100, ε/300, ε/1000), since what moves it is how much of the mesh's highest modes the
///   damping removes; the scene is told so.
///   Far from linear the switched load's modes pass energy between them: an exact beam folded
///   by it (an end free to draw in) takes ε/3000 (a 20 m pinned–roller beam under 2 MN for
///   0.2 s, gap 0.11: 2.6 ε off at ε/30, 3.1 ε at ε/300, 0.41 ε at ε/3000), one held at both
///   ends and stretched by it ε/300 (a 40 m pinned–pinned beam under 200 kN for 0.32 s, gap
///   0.87: 2.8 ε at ε/30, 0.29 ε at ε/300; a 20 m clamped one under 3 MN, gap 0.52: 0.82 ε
///   and 0.12 ε; a 20 m pinned one under 1 MN, gap 0.71: 0.11 ε and 0.07 ε).
/// `bend` says how far the exact beam bends from linear, asked once and only where a rule
/// turns on it.
pub fn rtol_for(scene: &BeamScene, method: Method, bend: impl Fn() -> Bend) -> (f64, &'static str) {
    let case = Case {
        scene,
        accuracy: scene.accuracy,
        esdirk: method == Method::Esdirk4,
        genalpha: method == Method::GenAlpha,
        vehicles: !scene.vehicles.is_empty(),
        switched: scene.load_switched(),
        bend: OnceCell::new(),
        measure_bend: &bend,
    };
    let rule = (RTOL_RULES.iter())
        .find(|r| (r.when)(&case))
        .expect("the last rule holds for every scene");
    ((rule.rtol)(&case), rule.why)
}

/// What the rules of [`RTOL_RULES`] read of a scene and its method.
struct Case<'a> {
    scene: &'a BeamScene,
    accuracy: f64,
    esdirk: bool,
    genalpha: bool,
    vehicles: bool,
    switched: bool,
    bend: OnceCell<Bend>,
    /// Measuring the bend solves the exact beam statically: only the rules that turn on it ask.
    measure_bend: &'a dyn Fn() -> Bend,
}

impl Case<'_> {
    fn bend(&self) -> Bend {
        *self.bend.get_or_init(self.measure_bend)
    }

    /// Generalized-α damping its highest modes (the plan's ρ∞ < 1) under moving loads.
    fn genalpha_damping_moving_loads(&self) -> bool {
        self.genalpha && self.scene.carries_moving_loads() && self.scene.rho_inf < 1.0
    }
}

/// One rule of the rtol table: where it holds, the rtol it sets, and why.
struct Rule {
    when: fn(&Case) -> bool,
    rtol: fn(&Case) -> f64,
    why: &'static str,
}

/// The first rule that holds sets rtol: vehicles, then what ESDIRK4 carries (moving masses, a
/// rolling disk, an exact beam far from linear, a switched load), then numerical damping the
/// scene asks for, a switched load, and generalized-α's own damping under moving loads.
const RTOL_RULES: &[Rule] = &[
    Rule {
        when: |c| c.vehicles && c.esdirk,
        rtol: |c| (c.accuracy / 1000.0 * vehicle_speed_factor(c.scene)).max(FINEST_RTOL),
        why: "a thousandth of the accuracy, and faster than 150 m/s times 150 m/s over the speed (not below 1e-11): the fourth-order steps carry the bodies' vibration on their suspensions and the deck's under them over the whole run with a global error of a few times rtol (Biggs' sprung mass at 27.8 and 100 m/s and a truck over a raised deck: every number within 3.6e-4 of the converged); a wheel that crosses the deck in less than the period of a mode the rotations carry rings them all at once (the sprung mass at a thousandth read the rotation at a support 4.9e-3 off at 1000 m/s, 1.6e-3 at 10 000; with the factor, from 300 to 30 000 m/s, every number within 6.9e-4 of its kind's largest)",
    },
    Rule {
        when: |c| c.vehicles,
        rtol: |c| c.accuracy / 3000.0 * unsprung_speed_factor(c.scene),
        why: "a three-thousandth of the accuracy: the vehicles' bodies vibrate on their suspensions over the whole run, and the phase error of every step adds up over their periods (a sprung mass over a ramp comes within 5.4e-4 of its closed form over six periods at this rtol, 2.5e-3 at a three-hundredth); with wheels of their own mass faster than 300 m/s, times (300 m/s / speed)^2: their impulses where the deck ends and turns grow with the speed (a railway car at 3000 m/s read a bogie's largest acceleration 13 times the converged at a three-thousandth, and lands within 4e-4 of the car's scale at this rtol)",
    },
    Rule {
        when: |c| c.esdirk && c.scene.carries_moving_masses(),
        rtol: |c| c.accuracy / 10000.0,
        why: "a ten-thousandth of the accuracy: the fourth-order steps carry the impulses of the moving masses turning at the nodes and dropping off at the far support into the deck's accelerations and on through the free vibration after them (two 2 t axles over D44's section: the quarter point's largest acceleration within 3.6e-4 of the largest at this rtol, 1.1e-3 at a three-thousandth, 3.4e-3 at a three-hundredth)",
    },
    Rule {
        when: |c| c.esdirk && c.scene.rolls_with_inertia() && matches!(c.scene.beam.model, BeamModel::Modal { .. }),
        rtol: |c| c.accuracy / 1000.0,
        why: "a thousandth of the accuracy: the fourth-order steps carry the disk's contact force and the deck's acceleration over the whole run, and each row of the history carries the phase error of every step in the modes up to the cutoff, which the extremes hardly feel (D44's and D50's modal beams at the defaults, set down at rest: midspan's acceleration at some output time 9.2e-3 and 1.2e-2 of its largest off at a thirtieth, 9.9e-4 and 1.2e-3 at a three-hundredth, within 3.6e-4 at this rtol, the largest alone within 6e-6 at a thirtieth; started carrying the disk 1.8e-3 at a thirtieth)",
    },
    Rule {
        when: |c| c.esdirk && c.scene.disks.iter().any(|d| d.coupling == Coupling::Thesis),
        rtol: |c| c.accuracy / 300.0,
        why: "a three-hundredth of the accuracy: the thesis coupling's contact force rings in the mesh's modes from the moment the disk is set down, and each row of the history carries the phase error of every step before it (D44 on 10 exact elements over 1.5 s, against ESDIRK4 at rtol 1e-8: the worst row of the accelerations and the supports' forces 1.9e-3 of its kind's largest off set down at rest and 5.7e-3 started carrying the disk at a thirtieth, 1.8e-3 and 3.8e-4 at a hundredth, within 7.5e-4 and 1.2e-4 at this rtol)",
    },
    Rule {
        when: |c| c.esdirk && c.scene.rolls_with_inertia(),
        rtol: |c| c.accuracy / 30.0,
        why: "a thirtieth of the accuracy: the fourth-order steps carry the disk's contact force and the deck's acceleration over the crossing with a global error of a few times rtol (D44's 10- and 20-element exact meshes started carrying the disk: the acceleration within 1.1e-4, the contact force within 1.1e-3 of the weight, which rings in the mesh's highest modes with a phase that tightening rtol does not settle: 1.4e-3 at a hundredth; D50's mesh at 20 m/s: the acceleration 4.4e-3 off)",
    },
    Rule {
        when: |c| c.esdirk && !c.switched && c.bend() == Bend::Whips,
        rtol: |c| c.accuracy / 3000.0,
        why: "a three-thousandth of the accuracy: moving loads cross an exact beam with a free end that bends visibly off linear under them, whose tip whips as each load leaves or comes on, and its accelerations carry the error of every step (a 15 m steel cantilever under six 100 kN axles at 40 m/s that drop off its tip, its static deflection 7.4e-2 off the linear one: the largest acceleration 9.0e-4 off at a three-hundredth of the accuracy, 1.0e-4 at this rtol; under 60 kN, 2.9e-2 off: 1.2e-3 and 1.4e-4; on the linear beam 2e-6 at either)",
    },
    Rule {
        when: |c| c.esdirk && !c.switched && c.bend() == Bend::Folds,
        rtol: |c| c.accuracy / 3000.0,
        why: "a three-thousandth of the accuracy: the exact beam folds under its loads, and swinging far from its linear modes its accelerations carry the error of every step (D44's section under a moving force that sinks midspan 8.7 m: the largest accelerations 9e-4 off at a three-hundredth, 3.6e-5 at this rtol; a 40 t force over a 30 m beam of half its area that swings 10 m after it: 7.9e-3 and 2.2e-4)",
    },
    Rule {
        when: |c| c.esdirk && c.switched && c.bend() == Bend::Folds,
        rtol: |c| c.accuracy / 3000.0,
        why: "a three-thousandth of the accuracy: a load switched on an exact beam that folds under it (its static deflection more than a tenth off the linear one, an end free to draw in) sets it swinging in every mode, passing energy between them, and the accelerations carry the error of every step (a 20 m pinned-roller beam under 2 MN for 0.2 s, gap 0.11: the largest acceleration 2.6e-3 off at a thirtieth, 3.1e-3 at a three-hundredth, 4.1e-4 at this rtol)",
    },
    Rule {
        when: |c| c.esdirk && c.switched && c.accuracy >= DEFAULT_ACCURACY && c.bend() == Bend::Stretches,
        rtol: |c| c.accuracy / 300.0,
        why: "a three-hundredth of the accuracy: a load switched on an exact beam held along its axis at both ends and stretched by it (its static deflection more than a tenth off the linear one) rings in modes its tension couples, and the accelerations carry the error of every step (a 40 m pinned-pinned beam under 200 kN for 0.32 s, gap 0.87: midspan's largest acceleration 2.8e-3 off at a thirtieth, 2.9e-4 at this rtol; a 20 m clamped one under 3 MN, gap 0.52: 8.2e-4 and 1.2e-4)",
    },
    Rule {
        when: |c| c.esdirk && c.switched && c.accuracy >= DEFAULT_ACCURACY,
        rtol: |c| c.accuracy / 100.0,
        why: "a hundredth of the accuracy: the fourth-order steps carry every mode a switched load excites through the run, and each row of the history carries the phase error of every step before it, which the extremes hardly feel (B1-B3 on the exact meshes planned: u and phi at some output time 1.0-1.5e-3 of their kind's largest off at a thirtieth, within 5.8e-4 at this rtol, every extreme within 2.7e-4 at either; C1's cantilever on 2 and 4 exact elements: 3.3e-3 and 2.0e-3 at a thirtieth, 6.0e-4 and 9.6e-4 at this rtol)",
    },
    Rule {
        when: |c| c.esdirk && c.switched,
        rtol: |c| c.accuracy / 1000.0,
        why: "a thousandth of the accuracy: the fourth-order steps carry every mode a switched load excites through the run (the cantilever C3 on 4 elements asked for 1e-4 and 1e-5, B2 for 1e-4: every extreme within 2.6e-5, 2.6e-6 and 1.4e-5 of the converged, against generalized-alpha's 3.0e-4, 4.2e-4 and 2.7e-4)",
    },
    Rule {
        when: |c| damped_by_the_scene(c.scene) && c.switched,
        rtol: |c| c.accuracy / 100.0,
        why: "a hundredth of the accuracy; with rho_inf < 1 a switched load's peak depends on how much of the mesh's highest modes the damping removes, which tightening rtol does not settle: rho_inf = 1 holds the accuracy",
    },
    Rule {
        when: |c| damped_by_the_scene(c.scene),
        rtol: |c| c.accuracy / 100.0,
        why: "a hundredth of the accuracy: with rho_inf < 1 the damped high modes that ride on a peak need the margin",
    },
    Rule {
        when: |c| c.switched,
        rtol: |c| c.accuracy / 10000.0,
        why: "a ten-thousandth of the accuracy: a load switched during the run excites every mode of the mesh, undamped (rho_inf = 1) they all stay in what the run reports, and what it reports seconds later carries every step's error (the cantilevers' tip acceleration two seconds after the load is taken off missed by 2.0-3.5e-3 at a thousandth, and lands within 6e-4 at this rtol)",
    },
    Rule {
        when: |c| c.genalpha_damping_moving_loads() && c.scene.disks.iter().all(|d| d.coupling == Coupling::MovingForce),
        rtol: |c| c.accuracy / 10000.0,
        why: "a ten-thousandth of the accuracy: the planned rho_inf damps the mesh's highest modes, which each force crossing a node sets ringing and which carry a share of the deck's acceleration that the damping takes less of the shorter the step, and each row of the history carries the phase error of every step before it, which the extremes hardly feel (D44's moving-force disk on its exact meshes of 10 and 16 elements: the probes' accelerations at some output time 2.1e-3 and 3.0e-3 of their largest off at a thousandth, within 2.4e-4 at this rtol, every extreme within 2.1e-4 at a thousandth)",
    },
    Rule {
        when: |c| c.genalpha_damping_moving_loads(),
        rtol: |c| c.accuracy / 1000.0,
        why: "a thousandth of the accuracy: the planned rho_inf damps the mesh's highest modes, which each force crossing a node sets ringing and which carry a share of the deck's acceleration that the damping takes less of the shorter the step (D44's moving-force disk on its exact mesh: the quarter point's largest acceleration 1.1e-3 off at a three-hundredth, 2.1e-4 at a thousandth)",
    },
    Rule {
        when: |_| true,
        rtol: |c| c.accuracy / 300.0,
        why: "a three-hundredth of the accuracy: what the run reports after the loads have moved along (the residual vibration, a train's resonant build-up) carries the error of every step before it",
    },
];

/// Numerical damping the scene asks for, rather than the plan's ([`rho_inf_for`]).
pub(super) fn damped_by_the_scene(scene: &BeamScene) -> bool {
    scene.rho_inf < 1.0 && scene.rho_inf_chosen.is_none()
}

/// The size of the response a beam scene's atol is rtol times when it leaves both tolerances
/// out, and why: the size `response_size` found, unless the scene asks for numerical damping itself. With
/// a ρ∞ < 1 the scene gives, the step also sets how much of the high modes numerical damping
/// takes, and a sudden load's peak is carried by them: at the looser steps such an atol
/// allows, B1, B3, C1, C2 and the zip-line missed by 1.1–1.6 ε, so there atol stays at
/// round-off size and the tolerance relative to the state. The plan's own ρ∞ = 0.9 damps only
/// modes shown to carry nothing ([`rho_inf_for`]).
pub fn atol_for(scene: &BeamScene) -> Option<(f64, String)> {
    if damped_by_the_scene(scene) {
        return None;
    }
    let size = scene.response?;
    let at = if scene.planning_points().len() > scene.probes.len() {
        "at a probe or the middle of the longest span, every probe lying near a support"
    } else {
        "at a probe"
    };
    let at = if scene.response_turned {
        format!("{at}, here a rotation, which the loads only turn the probes by, times the longest span over pi")
    } else {
        at.to_string()
    };
    let why = match scene.passage {
        Some((share, crossing)) => format!(
            "rtol times {size:.3e} m, the largest static displacement the loads cause {at} ({:.3e} m) times {share:.3e}: they are on the beam for {crossing:.3e} s, short against its first period, an impulse that leaves (2/pi) omega1 T of the static response; each step's error is measured against the response, not against the displacement of the moment, which a vibration takes through zero twice a period",
            size / share
        ),
        None => format!(
            "rtol times {size:.3e} m, the largest static displacement the loads cause {at}: each step's error is measured against the response, not against the displacement of the moment, which a vibration takes through zero twice a period"
        ),
    };
    Some((size, why))
}

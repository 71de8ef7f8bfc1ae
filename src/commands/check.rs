//! `rollbeam check`: read a scene and print the model it would build, running nothing.

use std::fmt;
use std::path::PathBuf;

use crate::analysis::modes::ModeKind;
use crate::beam::damping::DampingSpec;
use crate::beam::load::BeamStart;
use crate::beam::supports::statically_supported;
use crate::beam::train::{Train, TrainModel};
use crate::beam::{shear_rigid_ratio, Beam, BeamModel};
use crate::coupling::patch;
use crate::coupling::DiskOnBeamSpec;
use crate::error::Error;
use crate::ode::Method;
use crate::output;
use crate::say;
use crate::scene::{BeamScene, Model, RollingScene, Scene};

#[derive(clap::Args)]
pub struct CheckArgs {
    scene: PathBuf,
}

pub fn check(args: CheckArgs) -> Result<(), Error> {
    let scene = Scene::load(&args.scene)?;
    say!(
        "{}",
        crate::error::short_numbers(Described(&scene).to_string().trim_end())
    );
    Ok(())
}

/// What a scene builds: the track, the mesh and what chose it, the disk, the loads and probes,
/// and the solver settings with the reasons for those the scene left out.
pub struct Described<'a>(pub &'a Scene);

impl fmt::Display for Described<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let scene = self.0;
        writeln!(f, "scene {}: valid", scene.name)?;
        match &scene.model {
            Model::Rolling(setup) => rolling(f, setup)?,
            Model::Beam(setup) => beam(f, setup, scene.duration)?,
        }
        if let (Some(b), Some(why)) = (scene.beam(), &scene.solver.method_chosen) {
            writeln!(f, "  method chosen for accuracy {:e}: {why}", b.accuracy)?;
        }
        if let (Some(b), Some(why)) = (scene.beam(), &scene.solver.free_vibration_chosen) {
            writeln!(
                f,
                "  free vibration integrated for accuracy {:e}: {why}",
                b.accuracy
            )?;
        }
        if let (Some(b), Method::GenAlpha) = (scene.beam(), scene.solver.method) {
            if let Some(why) = &b.rho_inf_chosen {
                writeln!(f, "  rho_inf chosen for accuracy {:e}: {why}", b.accuracy)?;
            }
        }
        if let (Some(b), Some(why)) = (scene.beam(), &scene.solver.rtol_chosen) {
            writeln!(
                f,
                "  rtol chosen for accuracy {:e}: {}, {why}",
                b.accuracy,
                output::tolerance(scene.solver.rtol)
            )?;
            if let Some(why) = &scene.solver.atol_chosen {
                writeln!(
                    f,
                    "  atol chosen with it: {}, {why}",
                    output::tolerance(scene.solver.atol)
                )?;
            }
        }
        writeln!(
            f,
            "  solver: {} rtol {} atol {}; duration {} s, output every {} s",
            scene.solver.method.name(),
            output::tolerance(scene.solver.rtol),
            output::tolerance(scene.solver.atol),
            scene.duration,
            scene.interval
        )?;
        Ok(())
    }
}

/// The rigid curve, the disk, and the model's size.
fn rolling(f: &mut fmt::Formatter<'_>, setup: &RollingScene) -> fmt::Result {
    let r = &setup.rolling;
    writeln!(
        f,
        "  track: rigid {} curve{}",
        r.curve.kind(),
        r.curve
            .domain()
            .map_or(String::new(), |(a, b)| format!(", s in [{a}, {b}]"))
    )?;
    writeln!(
        f,
        "  disk: m = {} kg, a = {} m, C = {} kg m², s0 = {}, Ω0 = {} 1/s{}",
        r.disk.mass,
        r.disk.radius,
        r.disk.inertia(),
        r.s0,
        r.omega0,
        r.mu.map_or(String::new(), |m| format!(", mu = {m}"))
    )?;
    writeln!(f, "  {}", contact_loss(r.contact_loss))?;
    writeln!(
        f,
        "  model: {} formulation, {} unknowns (no beam)",
        setup.formulation.name(),
        crate::run::model(setup).initial_state().len()
    )?;
    Ok(())
}

/// The beam and its mesh (and what chose it), the disk on it, the loads and the probes.
fn beam(f: &mut fmt::Formatter<'_>, setup: &BeamScene, duration: f64) -> fmt::Result {
    let b = Beam::shared(&setup.beam);
    let spec = &b.spec;
    writeln!(
        f,
        "  track: Reissner beam, L = {:.6} m at {:.4}° , supports {} / {}{}, starting {}",
        b.length,
        b.angle.to_degrees(),
        spec.supports[0].name(),
        spec.supports[1].name(),
        if spec.bearings.is_empty() {
            String::new()
        } else {
            format!(", bearings holding w at x = {:?}", spec.bearings)
        },
        match setup.start {
            BeamStart::Rest => "undeformed at rest",
            BeamStart::Static => "at rest in static equilibrium",
        }
    )?;
    writeln!(
        f,
        "  mesh: {} elements of degree {}, {} quadrature, {} beam unknowns",
        spec.elements,
        spec.order,
        spec.quadrature.name(),
        b.dim()
    )?;
    if let Some(d) = &setup.discretisation {
        writeln!(f, "  chosen for accuracy {:e}: {}", d.accuracy, d.why)?;
    }
    writeln!(
        f,
        "  beam model: {}{}",
        match spec.model {
            BeamModel::Exact => "exact (geometrically exact Reissner beam)".to_string(),
            BeamModel::Linear =>
                "linear (small displacements: constant stiffness and mass about the undeformed state)"
                    .to_string(),
            BeamModel::Modal { modes } => format!(
                "modal ({modes} modes of the linear beam{}; {} unknowns in the equations of motion)",
                if statically_supported(spec.supports, spec.bearings.len()) {
                    ", with the static correction of the modes left out"
                } else {
                    ""
                },
                modes
            ),
        },
        setup
            .model_choice
            .as_ref()
            .map_or(" (as the scene gives)".to_string(), |why| format!(
                ", chosen for accuracy {:e}: {why}",
                setup.accuracy
            ))
    )?;
    shear(f, &b)?;
    damping(f, &b)?;
    if let Some(g) = spec.self_weight {
        writeln!(
            f,
            "  self-weight: on, ρA g = {:.6e} N/m (g = {g} m/s²), as a consistent load M g",
            spec.section.rho_a * g
        )?;
    }
    for v in &setup.vehicles {
        vehicle(f, v)?;
    }
    if setup.profile != crate::vehicle::profile::Profile::Smooth {
        writeln!(f, "  profile: {}", profile(&setup.profile))?;
    }
    if let Some(t) = &setup.train {
        train(f, t, b.length)?;
    }
    if !setup.disks.is_empty() {
        disks(f, setup)?;
    } else if setup.train.is_none() && setup.vehicles.is_empty() {
        writeln!(f, "  disk: none (no disk unknowns)")?;
    }
    for w in setup
        .warnings()
        .into_iter()
        .chain(setup.disks_meeting(duration))
    {
        writeln!(f, "  warning: {w}")?;
    }
    writeln!(
        f,
        "  loads: {}, probes: {}",
        setup.loads.len(),
        setup
            .probes
            .iter()
            .map(|p| format!("{} at x = {}", p.name, p.x))
            .collect::<Vec<_>>()
            .join(", ")
    )?;
    Ok(())
}

/// Where the scene's shear stiffness is held back (`beam::shear_rigid_limit`), by how much.
fn shear(f: &mut fmt::Formatter<'_>, b: &Beam) -> fmt::Result {
    let spec = &b.spec;
    if let Some(given) = b.shear_given {
        let taken = spec.section.gav;
        let bending = spec.section.ei / (b.length * b.length);
        writeln!(
            f,
            "  shear: G Av = {given:.4e} N against E I/L² = {bending:.4e} N, so stiff that the stiffness matrix would keep the bending beside it only to round-off; the beam is assembled with G Av = {taken:.4e} N ({:.1e} E I/L², the shear then adding about {:.1e} of the deflection), {}",
            shear_rigid_ratio(spec),
            12.0 / shear_rigid_ratio(spec),
            if spec.model == BeamModel::Exact {
                "where the exact beam's tangent still keeps its Newton iteration converging"
            } else {
                "where the shear adds as much of the deflection as the round-off it saves"
            }
        )?;
    }
    Ok(())
}

/// Each disk on the beam, its coupling, contact and patch.
fn disks(f: &mut fmt::Formatter<'_>, setup: &BeamScene) -> fmt::Result {
    for (d, name) in setup.disks.iter().zip(setup.disk_names()) {
        writeln!(
            f,
            "  {name}: m = {} kg, a = {} m, s0 = {}, Ω0 = {} 1/s, {} coupling ({}){}",
            d.disk.mass,
            d.disk.radius,
            d.s0,
            d.omega0,
            d.coupling.name(),
            if d.coupling.rolls() {
                "1 more unknown: the contact point s"
            } else {
                "prescribed travel, no disk unknowns"
            },
            d.mu.map_or(String::new(), |m| format!(", mu = {m}"))
        )?;
        if d.coupling.rolls() {
            writeln!(f, "  {}", contact_loss(d.contact_loss))?;
        }
        patch(f, setup, d)?;
    }
    Ok(())
}

/// The Rayleigh damping, its α and β, and the ratio it gives the lowest modes.
fn damping(f: &mut fmt::Formatter<'_>, b: &Beam) -> fmt::Result {
    let Some(spec) = b.spec.damping else {
        return Ok(());
    };
    let r = match crate::analysis::modes::rayleigh(b) {
        Ok(Some(r)) => r,
        Ok(None) => return Ok(()),
        Err(why) => return writeln!(f, "  damping: cannot be anchored: {why}"),
    };
    let anchored = match spec {
        DampingSpec::Ratio { zeta, modes } => {
            format!(
                ", from ζ = {zeta} at bending modes {} and {}",
                modes[0], modes[1]
            )
        }
        DampingSpec::Rayleigh { .. } => String::new(),
    };
    let lowest = crate::analysis::modes::modes(b, 6.min(b.dim()))
        .map(|m| {
            m.omega
                .iter()
                .zip(m.kinds(b))
                .filter(|(w, kind)| w.is_normal() && *kind != ModeKind::Rigid)
                .map(|(w, kind)| {
                    format!(
                        "{:.3} Hz ({}) {:.4}",
                        w / std::f64::consts::TAU,
                        kind.name(),
                        r.ratio_at(*w)
                    )
                })
                .collect::<Vec<_>>()
                .join(", ")
        })
        .unwrap_or_default();
    writeln!(
        f,
        "  damping: Rayleigh C = α M + β K₀, α = {:.6e} 1/s, β = {:.6e} s{anchored}; ζ of the lowest modes: {lowest}",
        r.alpha, r.beta
    )
}

/// Where the contact patch's width comes from, and what depends on it.
fn patch(f: &mut fmt::Formatter<'_>, setup: &BeamScene, d: &DiskOnBeamSpec) -> fmt::Result {
    let spec = &setup.beam;
    let weight = d.disk.mass * d.gravity;
    let hertz = patch::hertz_half_width(&spec.section, spec.depth, d.disk.radius, weight);
    let rule = patch::physical_half_width(&spec.section, spec.depth, d.disk.radius, weight);
    writeln!(
        f,
        "  contact patch: ±{:.4} m{}; the physical width for this section is ±{rule:.4} m: the load dispersed at one to one through half the depth {:.4} m{} (EN 1991-2 §4.3.6), plus Hertz's half-width {hertz:.2e} m",
        d.patch,
        if (d.patch - rule).abs() <= 1e-12 * rule {
            " (from the section)"
        } else {
            " (given)"
        },
        spec.depth,
        if (spec.depth - patch::rectangular_depth(&spec.section)).abs() > 1e-12 * spec.depth {
            " (given)"
        } else {
            ", the depth of the rectangle with the section's A and I"
        },
    )?;
    {
        let s = setup.patch_sensitivity_of(d);
        writeln!(
            f,
            "  patch sensitivity: the axis kinks by P/(G Av) = {:.2e} rad under the disk; deflection ~{:.1e} of the response, contact force ~{:.1e} of the weight",
            s.kink_angle, s.deflection, s.contact_force
        )?;
    }
    Ok(())
}

/// The train: its axles, their loads, its speed and how the axles act.
fn train(f: &mut std::fmt::Formatter, t: &Train, length: f64) -> std::fmt::Result {
    let total: f64 = t.loads.iter().sum();
    writeln!(
        f,
        "  train: {} with {} axles over {:.3} m ({:.6e} N in all), at {} m/s: on the beam from t = 0 until the last axle leaves at {:.6} s",
        t.name,
        t.axles.len(),
        t.length(),
        total,
        t.speed,
        t.gone(length)
    )?;
    match t.model {
        TrainModel::MovingForce => writeln!(
            f,
            "  axles: moving forces (no inertia, no unknowns), each a point force"
        ),
        TrainModel::MovingMass => writeln!(
            f,
            "  axles: moving masses load/g (heaviest {:.6e} kg) following the beam, riding on the axis averaged over ±{:.6} m (the load dispersed through half the depth): they add to the mass matrix as they travel, and their convected acceleration 2 v ẇ' + v² w'' to the forces",
            t.masses.iter().copied().fold(0.0, f64::max),
            t.patch
        ),
    }
}

/// A vehicle: its parts, how it travels, what each wheel bears at rest.
fn vehicle(f: &mut std::fmt::Formatter, v: &crate::vehicle::Vehicle) -> std::fmt::Result {
    let loads: Vec<String> = v
        .axles
        .iter()
        .zip(&v.static_loads)
        .map(|(a, p)| format!("{} {:.6e} N", a.name, p))
        .collect();
    writeln!(
        f,
        "  vehicle {}: {} bodies ({} unknowns), {} axles, {} springs; from x = {} m at {} m/s{}; point wheels bearing at rest {}",
        v.name,
        v.bodies.len(),
        v.unknowns(),
        v.axles.len(),
        v.springs.len(),
        v.x0,
        v.speed,
        if v.acceleration == 0.0 {
            String::new()
        } else {
            format!(
                ", accelerating at {} m/s²{}",
                v.acceleration,
                v.stops_at()
                    .map_or(String::new(), |t| format!(" (stops at t = {t:.6} s)"))
            )
        },
        loads.join(", ")
    )
}

/// The running surface, in one phrase.
fn profile(p: &crate::vehicle::profile::Profile) -> String {
    use crate::vehicle::profile::Profile;
    match p {
        Profile::Smooth => "level".into(),
        Profile::Points(pts) => format!(
            "piecewise linear through {} points from x = {} to {} m, constant beyond",
            pts.len(),
            pts[0][0],
            pts[pts.len() - 1][0]
        ),
        Profile::Cosines(c) => format!("ISO 8608 random profile, {} cosines", c.terms.len()),
    }
}

/// Where the normal force falls to zero, in one line.
fn contact_loss(loss: crate::disk::ContactLoss) -> String {
    match loss {
        crate::disk::ContactLoss::Stop => {
            "at a loss of contact: the run stops (contact-lost)".into()
        }
        crate::disk::ContactLoss::Fly { restitution } => format!(
            "at a loss of contact: the disk flies and lands (restitution {restitution}{})",
            if restitution == 0.0 { ", plastic" } else { "" }
        ),
    }
}

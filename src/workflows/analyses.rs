//! Static equilibrium and natural modes of a beam scene: solved, written as `static.yaml` /
//! `modes.yaml` (and mode-shape plots), and the text printed to the user returned.

use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::Path;

use serde::Serialize;

use crate::analysis::{modes, statics};
use crate::beam::supports::statically_supported;
use crate::beam::Beam;
use crate::error::Error;
use crate::output::{io_error, plots, write, yaml};
use crate::scene::{BeamScene, Scene};

#[derive(Serialize)]
pub struct ProbeState {
    pub x: f64,
    pub u: f64,
    pub w: f64,
    pub phi: f64,
}

#[derive(Serialize)]
pub struct Reaction {
    pub fx: f64,
    pub fy: f64,
    pub mz: f64,
}

#[derive(Serialize)]
pub struct StaticFile {
    pub scene: String,
    pub probes: BTreeMap<String, ProbeState>,
    /// What each support exerts on the beam, global axes.
    pub reactions: BTreeMap<String, Reaction>,
    pub iterations: usize,
    pub load_steps: usize,
    /// The shear stiffness G·Av (N) the beam is assembled with, where the scene's is held
    /// back as too stiff for round-off ([`crate::beam::shear_rigid_limit`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shear_stiffness: Option<f64>,
}

/// The line saying a beam's shear is held back, where it is.
fn shear_line(beam: &Beam) -> Option<String> {
    beam.shear_given.map(|given| {
        format!(
            "  shear: G Av held at {:.4e} N, the scene's {given:.4e} N being too stiff beside E I for round-off (`check` says why)\n",
            beam.spec.section.gav
        )
    })
}

/// Static equilibrium under the loads active at t = 0, the beam's own weight where the scene
/// puts it on and, with a disk, its weight at s0 (a point force: the static answer does not
/// depend on how the disk rolls).
pub fn statics(scene: &Scene, setup: &BeamScene, dir: &Path) -> Result<String, Error> {
    let sol = static_solution(scene, setup)?;
    let mut text = format!(
        "{}: static equilibrium in {} load steps, {} Newton iterations\n",
        scene.name, sol.load_steps, sol.iterations
    );
    text += &shear_line(&Beam::shared(&setup.beam)).unwrap_or_default();
    for (name, p) in &sol.probes {
        let _ = writeln!(
            text,
            "  {name} (x = {}): u = {:.6e} m, w = {:.6e} m, phi = {:.6e} rad",
            p.x, p.u, p.w, p.phi
        );
    }
    for (end, r) in &sol.reactions {
        let _ = writeln!(
            text,
            "  reaction at `{end}`: fx = {:.6e} N, fy = {:.6e} N, mz = {:.6e} N m",
            r.fx, r.fy, r.mz
        );
    }
    std::fs::create_dir_all(dir).map_err(|e| io_error(dir, e))?;
    write(&dir.join("static.yaml"), &yaml(&sol)?)?;
    let _ = writeln!(text, "  wrote {}", dir.join("static.yaml").display());
    Ok(text)
}

/// Each vehicle wheel on the deck at t = 0 with the load it bears at rest, as `initial:
/// static` has them: a vehicle parked on the deck weighs on it.
fn wheels_standing_on(setup: &BeamScene, length: f64) -> Vec<(f64, [f64; 2], f64)> {
    setup
        .vehicles
        .iter()
        .flat_map(|v| {
            let first = v.travel(0.0).0;
            v.axles
                .iter()
                .zip(&v.static_loads)
                .map(move |(a, &p)| (first - a.x, [0.0, -p], 0.0))
        })
        .filter(|&(x, _, _)| (0.0..=length).contains(&x))
        .collect()
}

/// The static equilibrium of [`statics`], as `static.yaml` holds it.
pub fn static_solution(scene: &Scene, setup: &BeamScene) -> Result<StaticFile, Error> {
    if !statically_supported(setup.beam.supports, setup.beam.bearings.len()) {
        return Err(Error::Input(format!(
            "scene {}: the beam is not supported enough for a static solution (supports {} and {}{} leave it free to move as a rigid body)",
            scene.name,
            setup.beam.supports[0].name(),
            setup.beam.supports[1].name(),
            match setup.beam.bearings.len() {
                0 => String::new(),
                n => format!(" and {n} intermediate bearing(s)"),
            }
        )));
    }
    let beam = Beam::shared(&setup.beam);
    let mut f = vec![0.0; beam.dim()];
    let active: Vec<(f64, [f64; 2], f64)> = setup
        .loads
        .iter()
        .filter(|l| l.active(0.0))
        .map(|l| (l.x, l.force, l.mz))
        .chain(
            setup
                .disks
                .iter()
                .map(|d| (d.s0, [0.0, -d.disk.mass * d.gravity], 0.0)),
        )
        .chain(wheels_standing_on(setup, beam.length))
        .collect();
    for &(x, force, mz) in &active {
        beam.add_point_load(x, force, mz, &mut f);
    }
    beam.add_weight(&mut f);
    let sol = statics::solve(&beam, &f)
        .map_err(|e| Error::Solver(format!("scene {}: {e}", scene.name)))?;
    let r = beam.support_reactions(&sol.q, &active, None);
    let bearings = beam.bearing_reactions(&sol.q, &active, None);
    let reactions: BTreeMap<String, Reaction> =
        [("from".to_string(), r[0]), ("to".to_string(), r[1])]
            .into_iter()
            .chain(
                beam.spec
                    .bearings
                    .iter()
                    .zip(&bearings)
                    .map(|(x, f)| (format!("bearing at x = {x}"), [f[0], f[1], 0.0])),
            )
            .map(|(k, v)| {
                (
                    k,
                    Reaction {
                        fx: v[0],
                        fy: v[1],
                        mz: v[2],
                    },
                )
            })
            .collect();
    let probes: BTreeMap<String, ProbeState> = setup
        .probes
        .iter()
        .map(|p| {
            let d = beam.displacement_at(&sol.q, p.x);
            (
                p.name.clone(),
                ProbeState {
                    x: p.x,
                    u: d.u,
                    w: d.w,
                    phi: d.phi,
                },
            )
        })
        .collect();
    Ok(StaticFile {
        scene: scene.name.clone(),
        probes,
        reactions,
        iterations: sol.iterations,
        load_steps: sol.load_steps,
        shear_stiffness: beam.held_shear(),
    })
}

#[derive(Serialize)]
struct ModesFile {
    scene: String,
    frequencies_hz: Vec<f64>,
    /// Each mode's kind: bending or axial.
    kinds: Vec<modes::ModeKind>,
    /// As in [`StaticFile`].
    #[serde(skip_serializing_if = "Option::is_none")]
    shear_stiffness: Option<f64>,
}

/// Natural frequencies (Hz) and mode shapes, mass-normalised, sampled at `xs`.
pub struct NaturalModes {
    pub hz: Vec<f64>,
    /// Each mode's kind (bending or axial).
    pub kinds: Vec<modes::ModeKind>,
    pub xs: Vec<f64>,
    /// Per mode, u, w and φ at each of `xs`.
    pub shapes: Vec<Vec<crate::beam::PointDisplacement>>,
}

/// How many modes `modes` computes when not told: six, or fewer where a modal beam keeps
/// fewer or the mesh holds fewer.
pub fn default_mode_count(setup: &BeamScene) -> usize {
    let kept = setup.beam.model.modes().unwrap_or(usize::MAX);
    6.min(kept).min(Beam::shared(&setup.beam).dim())
}

/// The lowest `count` natural frequencies and mode shapes about the undeformed state, the
/// shapes at `samples` + 1 evenly spaced points.
pub fn natural_modes(
    scene: &Scene,
    setup: &BeamScene,
    count: usize,
    samples: usize,
) -> Result<NaturalModes, Error> {
    if count == 0 {
        return Err(Error::Input(
            "--count must be at least 1: the number of modes to compute".into(),
        ));
    }
    if let Some(kept) = setup.beam.model.modes().filter(|&kept| count > kept) {
        return Err(Error::Input(format!(
            "--count {count} is more than the modal beam keeps ({kept} modes, `track.beam.modes`); ask for fewer, or use `model: linear` for every mode of the mesh"
        )));
    }
    let beam = Beam::shared(&setup.beam);
    if count > beam.dim() {
        return Err(Error::Input(format!(
            "--count {count} is more than the {} modes the mesh holds (its unknowns); ask for fewer, or refine the mesh (`track.beam.elements`)",
            beam.dim()
        )));
    }
    if beam.dim() > modes::DENSE_LIMIT && count > modes::MAX_SPARSE_MODES {
        return Err(Error::Input(format!(
            "--count {count} is more than the {} modes computed on a mesh this large ({} unknowns); ask for fewer",
            modes::MAX_SPARSE_MODES,
            beam.dim()
        )));
    }
    let m = modes::modes(&beam, count).ok_or_else(|| {
        Error::Solver(format!(
            "scene {}: the mass matrix is not positive definite",
            scene.name
        ))
    })?;
    let hz: Vec<f64> = m.omega.iter().map(|w| w / std::f64::consts::TAU).collect();
    let xs: Vec<f64> = (0..=samples)
        .map(|k| beam.length * k as f64 / samples as f64)
        .collect();
    let shapes = (0..hz.len())
        .map(|k| {
            let shape: Vec<f64> = m.shapes.column(k).iter().copied().collect();
            xs.iter()
                .map(|&x| beam.displacement_at(&shape, x))
                .collect()
        })
        .collect();
    Ok(NaturalModes {
        hz,
        kinds: m.kinds(&beam),
        xs,
        shapes,
    })
}

/// The lowest `count` natural frequencies and mode shapes about the undeformed state.
pub fn modes(scene: &Scene, setup: &BeamScene, count: usize, dir: &Path) -> Result<String, Error> {
    let NaturalModes {
        hz,
        kinds,
        xs,
        shapes,
    } = natural_modes(scene, setup, count, 200)?;
    let beam = Beam::shared(&setup.beam);
    std::fs::create_dir_all(dir).map_err(|e| io_error(dir, e))?;
    write(
        &dir.join("modes.yaml"),
        &yaml(&ModesFile {
            scene: scene.name.clone(),
            frequencies_hz: hz.clone(),
            kinds: kinds.clone(),
            shear_stiffness: beam.held_shear(),
        })?,
    )?;
    let labels: Vec<String> = hz
        .iter()
        .enumerate()
        .map(|(k, f)| format!("mode {} ({f:.3} Hz, {})", k + 1, kinds[k].name()))
        .collect();
    let series: Vec<(&str, Vec<(f64, f64)>)> = (0..hz.len())
        .map(|k| {
            let w: Vec<f64> = shapes[k].iter().map(|d| d.w).collect();
            let peak = w
                .iter()
                .fold(0.0_f64, |a, v| a.max(v.abs()))
                .max(f64::MIN_POSITIVE);
            (
                labels[k].as_str(),
                xs.iter().zip(&w).map(|(x, w)| (*x, w / peak)).collect(),
            )
        })
        .collect();
    plots::line_chart(
        &dir.join("modes.svg"),
        &format!("{}: mode shapes (w, normalised)", scene.name),
        "x (m)",
        "w / max|w|",
        &series,
    )?;
    let mut text = format!("{}: natural frequencies (Hz)\n", scene.name);
    text += &shear_line(&beam).unwrap_or_default();
    for (k, f) in hz.iter().enumerate() {
        let _ = writeln!(text, "  {:>2}: {f:.6} ({})", k + 1, kinds[k].name());
    }
    let _ = writeln!(text, "  wrote {}", dir.join("modes.yaml").display());
    Ok(text)
}

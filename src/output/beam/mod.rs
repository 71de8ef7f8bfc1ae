//! Outputs of a beam run: `summary.yaml`, `history.csv` and figures (probe histories, deformed
//! shapes, envelopes of u, w and φ, the energy budget).

use std::collections::BTreeMap;
use std::path::Path;

use plotters::prelude::*;
use serde::Serialize;

use super::plots::{line_chart, stacked_chart, PALETTE};
use super::{write, yaml};
use crate::error::Error;
use crate::ode::Method;
use crate::run::beam::BeamRun;
pub use figures::{comfort_chart, COMFORT_LEVELS};

mod figures;

#[derive(Serialize)]
struct Summary {
    scene: String,
    stopped: super::summary::Stopped,
    model: Model,
    solver: super::summary::Solver,
    energy: super::summary::Energy,
    #[serde(skip_serializing_if = "Option::is_none")]
    disk: Option<BeamDiskSummary>,
    /// Several disks, each as `disk` is for one.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    disks: Vec<BeamDiskSummary>,
    probes: BTreeMap<String, ProbeSummary>,
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    vehicles: BTreeMap<String, VehicleSummary>,
    envelope: EnvelopeSummary,
    /// What the recorded accelerations count (the cutoff, and the modes below it).
    #[serde(skip_serializing_if = "Option::is_none")]
    acceleration: Option<crate::run::beam::CutoffReport>,
    /// What the results depend on beyond the accuracy asked (`BeamScene::warnings`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    warnings: Vec<String>,
}

/// The disk's final values (where it left the beam, or at the end) and extremes while on it.
#[derive(Serialize)]
struct BeamDiskSummary {
    coupling: &'static str,
    #[serde(flatten)]
    common: super::summary::DiskSummary,
    /// The lowest deflection of the beam under the disk, and when.
    w_under_min: f64,
    w_under_min_t: f64,
    /// The contact force averaged over a period of the acceleration's cutoff: what the
    /// accuracy holds where the instantaneous force rings in a mesh's highest modes.
    #[serde(skip_serializing_if = "Option::is_none")]
    contact_mean: Option<ContactMeanSummary>,
    patch: PatchSummary,
}

#[derive(Serialize)]
struct ContactMeanSummary {
    window_s: f64,
    rn_min: f64,
    rn_max: f64,
    rt_min: f64,
    rt_max: f64,
    /// The largest |R̄_t| / R̄_n while R̄_n > 0; null if the mean never pressed.
    mu_needed_max: Option<f64>,
}

/// The contact patch and how much the results depend on it (`coupling::patch`).
#[derive(Serialize)]
struct PatchSummary {
    half_width: f64,
    depth: f64,
    kink_angle: f64,
    deflection_sensitivity: f64,
    contact_force_sensitivity: f64,
}

/// Whether disk k lifted off while rolling ([`crate::run::lifted_off_rolling`]): its flights
/// say so, or the run stopped at its loss of contact (not at another disk's).
fn lifted_off_rolling(r: &BeamRun, k: usize) -> bool {
    let stop = match r.header.stop {
        crate::run::Stop::Event(crate::disk::StopReason::ContactLost)
            if r.stopped_disk != Some(k) =>
        {
            crate::run::Stop::End
        }
        stop => stop,
    };
    crate::run::lifted_off_rolling(&flights_of(r, k), stop)
}

/// Disk k's flights.
fn flights_of(r: &BeamRun, k: usize) -> Vec<crate::run::FlightRecord> {
    r.flights.iter().filter(|f| f.disk == k).copied().collect()
}

fn disk_summary(r: &BeamRun, k: usize) -> Option<BeamDiskSummary> {
    let spec = r.setup.disks.get(k)?;
    let last = r
        .rows
        .iter()
        .filter_map(|row| row.disks.get(k).copied().flatten())
        .last()?;
    let [rn, rt, mu, w_under] = (*r.extremes.disks.get(k)?)?;
    let mu_needed_max = (mu.seen() && !lifted_off_rolling(r, k)).then_some(mu.max);
    Some(BeamDiskSummary {
        coupling: spec.coupling.name(),
        common: super::summary::DiskSummary {
            s: last.s,
            x: last.x,
            y: last.y,
            vx: last.vx,
            vy: last.vy,
            omega: last.omega,
            rn_min: rn.min,
            rn_max: rn.max,
            rt_min: rt.min,
            rt_max: rt.max,
            mu_needed_max,
            left_track_t: r.disks_left_t.get(k).copied().flatten(),
            flights: flights_of(r, k),
        },
        w_under_min: w_under.min,
        w_under_min_t: w_under.min_t,
        contact_mean: r
            .extremes
            .contact_means
            .get(k)
            .copied()
            .flatten()
            .zip(r.acceleration.as_ref())
            .map(|([rn, rt, mu], cutoff)| ContactMeanSummary {
                window_s: 1.0 / cutoff.cutoff_hz,
                rn_min: rn.min,
                rn_max: rn.max,
                rt_min: rt.min,
                rt_max: rt.max,
                mu_needed_max: mu.seen().then_some(mu.max),
            }),
        patch: {
            let s = r.setup.patch_sensitivity_of(spec);
            PatchSummary {
                half_width: spec.patch,
                depth: r.setup.beam.depth,
                kink_angle: s.kink_angle,
                deflection_sensitivity: s.deflection,
                contact_force_sensitivity: s.contact_force,
            }
        },
    })
}

/// Extremes over time and over the whole beam, and where along it they occur.
#[derive(Serialize)]
struct EnvelopeSummary {
    w_min: f64,
    w_min_x: f64,
    w_max: f64,
    w_max_x: f64,
    u_min: f64,
    u_max: f64,
    phi_min: f64,
    phi_min_x: f64,
    phi_max: f64,
    phi_max_x: f64,
    /// Largest length of the deformed axis minus L.
    stretch_max: f64,
    /// The largest |vertical acceleration| over the beam, where and when.
    a_max: f64,
    a_max_x: f64,
    a_max_t: f64,
}

fn envelope_summary(r: &BeamRun) -> EnvelopeSummary {
    let e = &r.envelope;
    let arg = |values: Vec<f64>, lowest: bool| {
        values.iter().zip(&e.x).fold(
            (
                if lowest {
                    f64::INFINITY
                } else {
                    f64::NEG_INFINITY
                },
                0.0,
            ),
            |(v, x), (&w, &xx)| {
                if (lowest && w < v) || (!lowest && w > v) {
                    (w, xx)
                } else {
                    (v, x)
                }
            },
        )
    };
    let (w_min, w_min_x) = arg(e.min.iter().map(|d| d.w).collect(), true);
    let (w_max, w_max_x) = arg(e.max.iter().map(|d| d.w).collect(), false);
    let (phi_min, phi_min_x) = arg(e.min.iter().map(|d| d.phi).collect(), true);
    let (phi_max, phi_max_x) = arg(e.max.iter().map(|d| d.phi).collect(), false);
    let u_min = e.min.iter().map(|d| d.u).fold(f64::INFINITY, f64::min);
    let u_max = e.max.iter().map(|d| d.u).fold(f64::NEG_INFINITY, f64::max);
    EnvelopeSummary {
        w_min,
        w_min_x,
        w_max,
        w_max_x,
        u_min,
        u_max,
        phi_min,
        phi_min_x,
        phi_max,
        phi_max_x,
        stretch_max: e.stretch_max,
        a_max: e.a_max.0,
        a_max_x: e.a_max.1,
        a_max_t: e.a_max.2,
    }
}

#[derive(Serialize)]
struct Model {
    track: &'static str,
    /// The beam model: exact, linear or modal.
    beam: &'static str,
    /// The modes a modal beam keeps.
    #[serde(skip_serializing_if = "Option::is_none")]
    modes: Option<usize>,
    /// Rayleigh damping: α (1/s) and β (s).
    #[serde(skip_serializing_if = "Option::is_none")]
    damping: Option<crate::beam::damping::Rayleigh>,
    unknowns: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    coupling: Option<&'static str>,
    elements: usize,
    order: usize,
    quadrature: &'static str,
    length: f64,
    /// The shear stiffness G·Av (N) a small-displacement beam is assembled with where the
    /// scene's is stiffer than round-off lets the bending beside it be kept
    /// ([`crate::beam::shear_rigid_limit`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    shear_stiffness: Option<f64>,
    /// What was chosen from `solver.accuracy` because the scene left it out, and why.
    #[serde(skip_serializing_if = "Option::is_none")]
    chosen: Option<Chosen>,
}

#[derive(Serialize)]
struct Chosen {
    accuracy: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    beam: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mesh: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rtol: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    atol: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rho_inf: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    method: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    free_vibration: Option<String>,
}

#[derive(Serialize)]
struct ProbeSummary {
    x: f64,
    w_min: f64,
    w_min_t: f64,
    w_max: f64,
    w_max_t: f64,
    u_min: f64,
    u_max: f64,
    phi_min: f64,
    phi_max: f64,
    /// Half the range of w after the last load left the beam (the disk, or a train's last
    /// axle): the residual vibration.
    #[serde(skip_serializing_if = "Option::is_none")]
    w_amplitude_after_exit: Option<f64>,
    /// The largest |vertical acceleration| and when.
    a_max: f64,
    a_max_t: f64,
}

fn probe_summary(r: &BeamRun, k: usize) -> ProbeSummary {
    let [u, w, phi, a] = r.extremes.probes[k];
    let (a_max, a_max_t) = a.largest_magnitude();
    ProbeSummary {
        x: r.setup.probes[k].x,
        w_min: w.min,
        w_min_t: w.min_t,
        w_max: w.max,
        w_max_t: w.max_t,
        u_min: u.min,
        u_max: u.max,
        phi_min: phi.min,
        phi_max: phi.max,
        w_amplitude_after_exit: r.amplitude_after_exit(k),
        a_max,
        a_max_t,
    }
}

/// A vehicle's extremes from the time it came onto the deck, located on the solution.
#[derive(Serialize)]
struct VehicleSummary {
    bodies: BTreeMap<String, BodySummary>,
    axles: BTreeMap<String, AxleSummary>,
    /// When its last wheel left the deck, if it did.
    #[serde(skip_serializing_if = "Option::is_none")]
    left_t: Option<f64>,
    /// When it stopped, braking, if it did.
    #[serde(skip_serializing_if = "Option::is_none")]
    stopped_t: Option<f64>,
    /// The axle whose wheel lost contact and stopped the run.
    #[serde(skip_serializing_if = "Option::is_none")]
    contact_lost: Option<String>,
}

/// A body's largest |vertical acceleration| of its centre of mass, when, and its root mean
/// square (m/s²); absent while the vehicle never came onto the deck.
#[derive(Serialize)]
struct BodySummary {
    a_max: f64,
    a_max_t: f64,
    a_rms: f64,
}

#[derive(Serialize)]
struct AxleSummary {
    rn_min: f64,
    rn_min_t: f64,
    rn_max: f64,
    rn_max_t: f64,
    /// A disk wheel's flights, where it flew.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    flights: Vec<crate::run::beam::AxleFlight>,
}

fn vehicle_summaries(r: &BeamRun) -> BTreeMap<String, VehicleSummary> {
    r.vehicles
        .iter()
        .map(|v| {
            let bodies = v
                .bodies
                .iter()
                .filter(|(_, range, _)| range.seen())
                .map(|(name, range, rms)| {
                    let (a_max, a_max_t) = range.largest_magnitude();
                    let body = BodySummary {
                        a_max,
                        a_max_t,
                        a_rms: *rms,
                    };
                    (name.clone(), body)
                })
                .collect();
            let axles = v
                .axles
                .iter()
                .zip(&v.flights)
                .filter(|((_, range), _)| range.seen())
                .map(|((name, range), flights)| {
                    let axle = AxleSummary {
                        rn_min: range.min,
                        rn_min_t: range.min_t,
                        rn_max: range.max,
                        rn_max_t: range.max_t,
                        flights: flights.clone(),
                    };
                    (name.clone(), axle)
                })
                .collect();
            let summary = VehicleSummary {
                bodies,
                axles,
                left_t: v.left_t,
                stopped_t: v.stopped_t,
                contact_lost: v.lost_contact.clone(),
            };
            (v.name.clone(), summary)
        })
        .collect()
}

pub fn write_all(r: &BeamRun, dir: &Path, with_figures: bool) -> Result<(), Error> {
    write(&dir.join("history.csv"), &csv(r))?;
    if with_figures {
        figures::write_all(r, dir)?;
    }
    write(&dir.join("summary.yaml"), &summary_yaml(r)?)
}

/// The text of `summary.yaml`.
pub fn summary_yaml(r: &BeamRun) -> Result<String, Error> {
    let summary = Summary {
        scene: r.header.scene.name.clone(),
        stopped: super::summary::Stopped {
            disk: r
                .stopped_disk
                .filter(|_| r.setup.disks.len() > 1)
                .map(|k| r.setup.disk_names()[k].clone()),
            ..super::summary::Stopped::of(&r.header)
        },
        model: Model {
            track: "beam",
            beam: r.beam.spec.model.name(),
            modes: r.beam.spec.model.modes(),
            damping: r.damping,
            unknowns: r.header.unknowns,
            // Several disks share a coupling here only where they all have it; each disk's
            // summary names its own.
            coupling: r
                .setup
                .disk()
                .map(|d| d.coupling)
                .filter(|c| r.setup.disks.iter().all(|d| d.coupling == *c))
                .map(|c| c.name()),
            elements: r.beam.spec.elements,
            order: r.beam.spec.order,
            quadrature: r.beam.spec.quadrature.name(),
            length: r.beam.length,
            shear_stiffness: r.beam.held_shear(),
            chosen: chosen(r),
        },
        solver: super::summary::Solver::of(&r.header),
        energy: super::summary::Energy::of(&r.header),
        disk: (r.setup.disks.len() == 1)
            .then(|| disk_summary(r, 0))
            .flatten(),
        disks: if r.setup.disks.len() > 1 {
            (0..r.setup.disks.len())
                .filter_map(|k| disk_summary(r, k))
                .collect()
        } else {
            Vec::new()
        },
        probes: (0..r.setup.probes.len())
            .map(|k| (r.setup.probes[k].name.clone(), probe_summary(r, k)))
            .collect(),
        vehicles: vehicle_summaries(r),
        envelope: envelope_summary(r),
        acceleration: r.acceleration.clone(),
        warnings: r.warnings(),
    };
    yaml(&summary)
}

/// The disk's columns of history.csv, after `disk.` (`disk1.`, `disk2.`, … for several).
const DISK_COLUMNS: [&str; 10] = [
    "s",
    "x",
    "y",
    "vx",
    "vy",
    "omega",
    "rt",
    "rn",
    "mu_needed",
    "gap",
];

/// The text of `history.csv`.
pub fn csv(r: &BeamRun) -> String {
    let mut head = vec!["t".to_string()];
    let disks = r.setup.disks.len();
    for name in r.setup.disk_names() {
        head.extend(DISK_COLUMNS.iter().map(|c| format!("{name}.{c}")));
    }
    for p in &r.setup.probes {
        head.extend(["u", "w", "phi", "a"].map(|c| format!("{}.{c}", p.name)));
    }
    for v in &r.setup.vehicles {
        head.push(format!("{}.x", v.name));
        for b in &v.bodies {
            head.extend(["y", "a"].map(|c| format!("{}.{}.{c}", v.name, b.name)));
            if b.pitches() {
                head.push(format!("{}.{}.theta", v.name, b.name));
            }
        }
        head.extend(v.axles.iter().map(|a| format!("{}.{}.rn", v.name, a.name)));
    }
    head.extend(
        [
            "energy.kinetic",
            "energy.strain",
            "energy.potential",
            "energy.work",
            "energy.dissipated",
            "energy.impact",
            "energy.total",
        ]
        .map(String::from),
    );
    for end in ["from", "to"] {
        head.extend(["fx", "fy", "mz"].map(|c| format!("reaction.{end}.{c}")));
    }
    let mut out = head.join(",");
    out.push('\n');
    for row in &r.rows {
        let mut v = vec![row.t];
        for k in 0..disks {
            // After a disk has left the beam its columns stay empty.
            v.extend(
                row.disks
                    .get(k)
                    .copied()
                    .flatten()
                    .map_or([f64::NAN; 10], |d| {
                        [
                            d.s,
                            d.x,
                            d.y,
                            d.vx,
                            d.vy,
                            d.omega,
                            d.rt,
                            d.rn,
                            d.mu_needed().unwrap_or(f64::NAN),
                            if row.flying == Some(k) { row.gap } else { 0.0 },
                        ]
                    }),
            );
        }
        for (d, a) in row.probes.iter().zip(&row.accelerations) {
            v.extend([d.u, d.w, d.phi, *a]);
        }
        if let Some(obs) = &row.vehicles {
            for (i, veh) in r.setup.vehicles.iter().enumerate() {
                v.push(obs.x[i]);
                for (b, body) in veh.bodies.iter().enumerate() {
                    let [y, theta, a] = obs.bodies[i][b];
                    v.extend([y, a]);
                    if body.pitches() {
                        v.push(theta);
                    }
                }
                v.extend(&obs.rn[i]);
            }
        }
        // The potential is the disk's alone: the beam's own weight, where the scene puts it
        // on (erratum 6 leaves it out), is a load, whose work is in `work`.
        v.extend([
            row.kinetic,
            row.strain,
            row.potential,
            row.work,
            row.dissipated,
            row.impact,
            row.total(),
        ]);
        v.extend(row.reactions.iter().flatten());
        super::push_row(&mut out, &v);
    }
    out
}

fn chosen(r: &BeamRun) -> Option<Chosen> {
    let mesh = r.setup.discretisation.as_ref().map(|d| d.why.clone());
    // The planner's reasons hold where the run kept what it chose: an rtol given on the
    // command line replaces the chosen one, and the chosen atol follows it.
    let solver = &r.header.scene.solver;
    let rtol = solver
        .rtol_chosen
        .as_ref()
        .filter(|_| r.header.rtol == solver.rtol)
        .map(|why| format!("{}, {why}", super::tolerance(r.header.rtol)));
    let atol = solver
        .atol_chosen
        .as_ref()
        .filter(|_| {
            solver
                .atol_scale
                .is_some_and(|size| r.header.atol == r.header.rtol * size)
        })
        .map(|why| format!("{}, {why}", super::tolerance(r.header.atol)));
    let beam = r.setup.model_choice.clone();
    let rho_inf = r
        .setup
        .rho_inf_chosen
        .clone()
        .filter(|_| r.header.method == Method::GenAlpha);
    let method = solver
        .method_chosen
        .clone()
        .filter(|_| r.header.method == solver.method);
    let free_vibration = solver
        .free_vibration_chosen
        .clone()
        .filter(|_| r.header.method == solver.method);
    (beam.is_some()
        || mesh.is_some()
        || rtol.is_some()
        || atol.is_some()
        || rho_inf.is_some()
        || method.is_some()
        || free_vibration.is_some())
    .then(|| Chosen {
        accuracy: r.setup.accuracy,
        beam,
        mesh,
        rtol,
        atol,
        rho_inf,
        method,
        free_vibration,
    })
}

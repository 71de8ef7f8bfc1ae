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
    patch: PatchSummary,
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

/// Whether disk k lifted off while rolling ([`crate::run::lifted_off_rolling`]): of several
/// disks, a lift-off stops the run, and the one lifting is the one whose normal force is least.
fn lifted_off_rolling(r: &BeamRun, k: usize) -> bool {
    if !crate::run::lifted_off_rolling(&r.flights, r.header.stop) {
        return false;
    }
    let last_rn = |j: usize| {
        r.rows
            .iter()
            .rev()
            .find_map(|row| row.disks.get(j).copied().flatten())
            .map_or(f64::INFINITY, |d| d.rn)
    };
    (0..r.setup.disks.len()).all(|j| last_rn(k) <= last_rn(j))
}

/// Disk k's summary, if it was ever observed on or over the beam.
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
            flights: r.flights.clone(),
        },
        w_under_min: w_under.min,
        w_under_min_t: w_under.min_t,
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
        figures(r, dir)?;
    }
    write(&dir.join("summary.yaml"), &summary_yaml(r)?)
}

/// The text of `summary.yaml`.
pub fn summary_yaml(r: &BeamRun) -> Result<String, Error> {
    let summary = Summary {
        scene: r.header.scene.name.clone(),
        stopped: super::summary::Stopped::of(&r.header),
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
        warnings: r.setup.warnings(),
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
                            row.gap,
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

/// EN 1990 Annex A2 (A2.4.4.3.2): the body's vertical acceleration at the levels of comfort
/// very good, good and acceptable (m/s²).
pub const COMFORT_LEVELS: [(f64, &str); 3] = [
    (1.0, "very good (EN 1990 A2)"),
    (1.3, "good"),
    (2.0, "acceptable"),
];

/// The bodies' largest vertical accelerations against a swept value (each series a body's
/// points), with the comfort levels: very good always, the others where a body reaches them.
pub fn comfort_chart(
    path: &Path,
    title: &str,
    x_desc: &str,
    bodies: &[(String, Vec<(f64, f64)>)],
) -> Result<(), Error> {
    let (from, to) = bodies
        .iter()
        .flat_map(|(_, p)| p.iter())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.0), hi.max(p.0))
        });
    if !(from <= to) {
        return Ok(());
    }
    let axes = (x_desc, "max |a| of a body (m/s²)");
    with_comfort_levels(path, title, axes, bodies, (from, to), true)
}

/// Series of body accelerations with EN 1990's comfort levels drawn across `span`: those the
/// series reach, and very good always where `always_very_good`.
fn with_comfort_levels(
    path: &Path,
    title: &str,
    (x_desc, y_desc): (&str, &str),
    series: &[(String, Vec<(f64, f64)>)],
    (from, to): (f64, f64),
    always_very_good: bool,
) -> Result<(), Error> {
    let largest = series
        .iter()
        .flat_map(|(_, s)| s.iter())
        .fold(0.0_f64, |m, p| m.max(p.1.abs()));
    let levels: Vec<(&str, Vec<(f64, f64)>)> = COMFORT_LEVELS
        .iter()
        .enumerate()
        .filter(|(k, (level, _))| (*k == 0 && always_very_good) || *level <= largest)
        .map(|(_, (level, label))| (*label, vec![(from, *level), (to, *level)]))
        .collect();
    let series: Vec<(&str, Vec<(f64, f64)>)> = series
        .iter()
        .map(|(n, p)| (n.as_str(), p.clone()))
        .collect();
    super::plots::line_chart_with_references(path, title, x_desc, y_desc, &series, &levels)
}

/// The vehicles' body accelerations against time, with the comfort levels where they reach
/// them, and their wheels' contact forces.
fn vehicle_figures(r: &BeamRun, dir: &Path) -> Result<(), Error> {
    let name = &r.header.scene.name;
    let mut bodies: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    let mut wheels: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for (i, v) in r.setup.vehicles.iter().enumerate() {
        let of = |f: &dyn Fn(&crate::coupling::vehicles::VehicleObservation) -> f64| {
            r.rows
                .iter()
                .filter_map(|row| row.vehicles.as_ref().map(|o| (row.t, f(o))))
                .collect::<Vec<_>>()
        };
        for (b, body) in v.bodies.iter().enumerate() {
            bodies.push((
                format!("{} {}", v.name, body.name),
                of(&|o| o.bodies[i][b][2]),
            ));
        }
        for (a, axle) in v.axles.iter().enumerate() {
            wheels.push((format!("{} {}", v.name, axle.name), of(&|o| o.rn[i][a])));
        }
    }
    let t_end = r.rows.last().map_or(0.0, |row| row.t);
    with_comfort_levels(
        &dir.join("vehicles.svg"),
        &format!("{name}: vertical acceleration of the vehicles' bodies"),
        ("t (s)", "a (m/s²)"),
        &bodies,
        (0.0, t_end),
        false,
    )?;
    let wheels: Vec<(&str, Vec<(f64, f64)>)> = wheels
        .iter()
        .map(|(n, p)| (n.as_str(), p.clone()))
        .collect();
    line_chart(
        &dir.join("wheels.svg"),
        &format!("{name}: the wheels' contact forces"),
        "t (s)",
        "R (N)",
        &wheels,
    )
}

fn figures(r: &BeamRun, dir: &Path) -> Result<(), Error> {
    let name = &r.header.scene.name;
    if !r.setup.vehicles.is_empty() {
        vehicle_figures(r, dir)?;
    }
    let probes: Vec<(String, Vec<(f64, f64)>)> = r
        .setup
        .probes
        .iter()
        .enumerate()
        .map(|(k, p)| {
            (
                format!("{} (x = {} m)", p.name, p.x),
                r.rows.iter().map(|row| (row.t, row.probes[k].w)).collect(),
            )
        })
        .collect();
    let borrowed: Vec<(&str, Vec<(f64, f64)>)> = probes
        .iter()
        .map(|(n, v)| (n.as_str(), v.clone()))
        .collect();
    line_chart(
        &dir.join("probes.svg"),
        &format!("{name}: vertical displacement w at the probes"),
        "t (s)",
        "w (m)",
        &borrowed,
    )?;
    let e = &r.rows;
    line_chart(
        &dir.join("energy.svg"),
        &format!("{name}: energy budget"),
        "t (s)",
        "energy (J)",
        &[
            ("kinetic", e.iter().map(|r| (r.t, r.kinetic)).collect()),
            ("strain", e.iter().map(|r| (r.t, r.strain)).collect()),
            (
                "potential (disk)",
                e.iter().map(|r| (r.t, r.potential)).collect(),
            ),
            (
                "work of the loads",
                e.iter().map(|r| (r.t, r.work)).collect(),
            ),
            (
                "total: kinetic + strain + potential − work",
                e.iter().map(|r| (r.t, r.total())).collect(),
            ),
        ],
    )?;
    line_chart(
        &dir.join("reactions.svg"),
        &format!("{name}: vertical support reactions"),
        "t (s)",
        "R_Y (N)",
        &[
            (
                "at `from` (x = 0)",
                e.iter().map(|r| (r.t, r.reactions[0][1])).collect(),
            ),
            (
                "at `to` (x = L)",
                e.iter().map(|r| (r.t, r.reactions[1][1])).collect(),
            ),
        ],
    )?;
    envelopes(r, dir)?;
    if r.setup.disk().is_some() {
        disk_figures(r, dir)?;
    }
    shapes(r, &dir.join("shapes.svg"))
}

/// The envelopes of u, w and φ along the beam.
fn envelopes(r: &BeamRun, dir: &Path) -> Result<(), Error> {
    let name = &r.header.scene.name;
    let env = &r.envelope;
    for (file, label, pick) in [
        (
            "envelope-u.svg",
            "u (m)",
            (|d: &crate::beam::PointDisplacement| d.u)
                as fn(&crate::beam::PointDisplacement) -> f64,
        ),
        ("envelope-w.svg", "w (m)", |d| d.w),
        ("envelope-phi.svg", "φ (rad)", |d| d.phi),
    ] {
        line_chart(
            &dir.join(file),
            &format!(
                "{name}: envelope of {}",
                label.split(' ').next().unwrap_or(label)
            ),
            "x (m)",
            label,
            &[
                (
                    "max over time",
                    env.x
                        .iter()
                        .zip(&env.max)
                        .map(|(x, d)| (*x, pick(d)))
                        .collect(),
                ),
                (
                    "min over time",
                    env.x
                        .iter()
                        .zip(&env.min)
                        .map(|(x, d)| (*x, pick(d)))
                        .collect(),
                ),
            ],
        )?;
    }
    Ok(())
}

/// The disks' quantities while they are on the beam (thesis figures 31, 34, 38, 42), each
/// disk's series named after it where there are several.
fn disk_figures(r: &BeamRun, dir: &Path) -> Result<(), Error> {
    let name = &r.header.scene.name;
    let names = r.setup.disk_names();
    let series = |f: fn(&crate::disk::DiskObservation) -> f64, label: &str| {
        names
            .iter()
            .enumerate()
            .map(|(k, disk)| {
                let label = if names.len() == 1 {
                    label.to_string()
                } else {
                    format!("{disk} {label}")
                };
                let points = r
                    .rows
                    .iter()
                    .filter_map(|row| row.disks.get(k).copied().flatten().map(|d| (row.t, f(&d))))
                    .collect::<Vec<_>>();
                (label, points)
            })
            .collect::<Vec<_>>()
    };
    let velocities = [series(|d| d.vx, "v_X"), series(|d| d.vy, "v_Y")].concat();
    line_chart(
        &dir.join("disk-velocity.svg"),
        &format!("{name}: centre velocity of the disk"),
        "t (s)",
        "v (m/s)",
        &borrowed(&velocities),
    )?;
    line_chart(
        &dir.join("disk-omega.svg"),
        &format!("{name}: angular velocity of the disk"),
        "t (s)",
        "Ω (1/s)",
        &borrowed(&series(|d| d.omega, "Ω")),
    )?;
    let forces = [
        series(|d| d.rn, "R_n (normal)"),
        series(|d| d.rt, "R_t (tangential)"),
    ]
    .concat();
    let forces = borrowed(&forces);
    let gap = [(
        "gap",
        r.rows
            .iter()
            .filter(|row| row.disks.first().is_some_and(Option::is_some))
            .map(|row| (row.t, row.gap))
            .collect::<Vec<_>>(),
    )];
    let title = format!("{name}: contact force on the disk");
    let gap_title = format!("{name}: gap between the disk and the beam (0 while it rolls)");
    let mut panels: Vec<(&str, &str, &[(&str, Vec<(f64, f64)>)])> =
        vec![(&title, "R (N)", &forces)];
    if !r.flights.is_empty() {
        panels.push((&gap_title, "gap (m)", &gap));
    }
    stacked_chart(&dir.join("disk-forces.svg"), "t (s)", &panels)
}

/// Named series as the charts take them.
fn borrowed(v: &[(String, Vec<(f64, f64)>)]) -> Vec<(&str, Vec<(f64, f64)>)> {
    v.iter().map(|(l, p)| (l.as_str(), p.clone())).collect()
}

/// Where the disk stood on the magnified axis at time t: its centre in plot coordinates.
fn disk_in_plot(r: &BeamRun, t: f64, along: &[crate::beam::PointDisplacement]) -> Option<[f64; 2]> {
    let row = r.rows.iter().find(|row| (row.t - t).abs() < 1e-9)?;
    let s = row.disks.first().copied().flatten()?.s;
    let gap = row.gap;
    let xs = &r.envelope.x;
    let k = xs.partition_point(|&x| x < s).clamp(1, xs.len() - 1);
    let f = ((s - xs[k - 1]) / (xs[k] - xs[k - 1])).clamp(0.0, 1.0);
    let (u, w) = (
        along[k - 1].u + f * (along[k].u - along[k - 1].u),
        along[k - 1].w + f * (along[k].w - along[k - 1].w),
    );
    let p = r.beam.reference_point(s);
    let mag = r.setup.magnify;
    let a = r.setup.disk()?.disk.radius;
    let (sn, cs) = r.beam.angle.sin_cos();
    // A flying disk's gap is a displacement from the track: magnified with it.
    let lift = a + mag * gap;
    Some([p[0] + mag * u - lift * sn, p[1] + mag * w + lift * cs])
}

/// The deformed axis at the requested times, displacements magnified, over the undeformed axis.
/// The vehicles' wheels on the deck at shape time t, on the magnified shape `disp` over the
/// axis points `axis` (at the envelope's stations).
fn wheels_in_plot(
    r: &BeamRun,
    t: f64,
    disp: &[crate::beam::PointDisplacement],
    axis: &[[f64; 2]],
    mag: f64,
) -> Vec<(f64, f64)> {
    let Some(obs) = r
        .rows
        .iter()
        .find(|row| (row.t - t).abs() < 1e-9)
        .and_then(|row| row.vehicles.as_ref())
    else {
        return Vec::new();
    };
    let (xs, length) = (&r.envelope.x, r.beam.length);
    if xs.len() < 2 {
        return Vec::new();
    }
    r.setup
        .vehicles
        .iter()
        .enumerate()
        .flat_map(|(i, v)| v.axles.iter().map(move |a| obs.x[i] - a.x))
        .filter(|x| (0.0..=length).contains(x))
        .map(|x| {
            let k = xs.partition_point(|s| *s < x).clamp(1, xs.len() - 1);
            let f = (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
            let lerp = |a: f64, b: f64| a + f * (b - a);
            (
                lerp(axis[k - 1][0], axis[k][0]) + mag * lerp(disp[k - 1].u, disp[k].u),
                lerp(axis[k - 1][1], axis[k][1]) + mag * lerp(disp[k - 1].w, disp[k].w),
            )
        })
        .collect()
}

fn shapes(r: &BeamRun, path: &Path) -> Result<(), Error> {
    let err =
        |e: &dyn std::fmt::Display| Error::Output(format!("cannot draw {}: {e}", path.display()));
    let mag = r.setup.magnify;
    let xs = &r.envelope.x;
    let axis: Vec<[f64; 2]> = xs.iter().map(|&x| r.beam.reference_point(x)).collect();
    let lines: Vec<(String, Vec<(f64, f64)>)> = r
        .shapes
        .iter()
        .map(|(t, disp)| {
            (
                format!("t = {t} s"),
                axis.iter()
                    .zip(disp)
                    .map(|(p, d)| (p[0] + mag * d.u, p[1] + mag * d.w))
                    .collect(),
            )
        })
        .collect();
    let radius = r.setup.disk().map_or(0.0, |d| d.disk.radius);
    let disks: Vec<Option<[f64; 2]>> = r
        .shapes
        .iter()
        .map(|(t, disp)| disk_in_plot(r, *t, disp))
        .collect();
    let wheels: Vec<Vec<(f64, f64)>> = r
        .shapes
        .iter()
        .map(|(t, disp)| wheels_in_plot(r, *t, disp, &axis, mag))
        .collect();
    let circle = |c: [f64; 2]| circle(c, radius);
    let all = axis
        .iter()
        .map(|p| (p[0], p[1]))
        .chain(lines.iter().flat_map(|l| l.1.iter().copied()))
        .chain(disks.iter().flatten().flat_map(|c| circle(*c)));
    let Frame {
        w,
        h,
        scale,
        centre: (cx, cy),
    } = Frame::around(all);
    super::plots::svg(path, (w as u32 + 90, h as u32 + 80), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!(
                    "{}: deformed shapes, displacements × {mag}",
                    r.header.scene.name
                ),
                ("sans-serif", 22),
            )
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(
                cx - scale * w / 2.0..cx + scale * w / 2.0,
                cy - scale * h / 2.0..cy + scale * h / 2.0,
            )
            .map_err(|e| err(&e))?;
        let (x, y) = (
            format!("X (m), displacements × {mag}"),
            format!("Y (m), displacements × {mag}"),
        );
        super::plots::plane_mesh(&mut chart, &x, &y).map_err(|e| err(&e))?;
        chart
            .draw_series(LineSeries::new(
                axis.iter().map(|p| (p[0], p[1])),
                BLACK.mix(0.5).stroke_width(1),
            ))
            .map_err(|e| err(&e))?
            .label("undeformed")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.mix(0.5)));
        for (i, (label, pts)) in lines.iter().enumerate() {
            let color = PALETTE[i % PALETTE.len()];
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
                .map_err(|e| err(&e))?
                .label(label.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            if let Some(c) = disks[i] {
                chart
                    .draw_series(LineSeries::new(circle(c), color.stroke_width(2)))
                    .map_err(|e| err(&e))?;
            }
            chart
                .draw_series(wheels[i].iter().map(|&p| Circle::new(p, 4, color.filled())))
                .map_err(|e| err(&e))?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&e))?;
        Ok(())
    })
}

/// A circle of `radius` about c, as a closed line.
fn circle(c: [f64; 2], radius: f64) -> Vec<(f64, f64)> {
    (0..=48)
        .map(|k| {
            let th = 2.0 * std::f64::consts::PI * k as f64 / 48.0;
            (c[0] + radius * th.cos(), c[1] + radius * th.sin())
        })
        .collect()
}

/// A plot's area (pixels) and its metres per pixel, equal along both axes so that a magnified
/// shape is seen as drawn, about the centre of the points it frames.
struct Frame {
    w: f64,
    h: f64,
    scale: f64,
    centre: (f64, f64),
}

impl Frame {
    fn around(points: impl Iterator<Item = (f64, f64)>) -> Frame {
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for (x, y) in points {
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
        let span = (x1 - x0).max(y1 - y0).max(1e-9);
        let pad = 0.05 * span;
        let (w, h) = (
            900.0,
            (900.0 * ((y1 - y0) + 2.0 * pad) / ((x1 - x0) + 2.0 * pad)).clamp(250.0, 700.0),
        );
        Frame {
            w,
            h,
            scale: (((x1 - x0) + 2.0 * pad) / w).max(((y1 - y0) + 2.0 * pad) / h),
            centre: (0.5 * (x0 + x1), 0.5 * (y0 + y1)),
        }
    }
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

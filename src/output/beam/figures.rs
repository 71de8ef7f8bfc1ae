//! The figures of a beam run: probe histories, the energy budget, envelopes of u, w and φ,
//! the disk's quantities, the deformed shapes, and the vehicles' bodies against comfort.

use super::*;

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
    crate::output::plots::line_chart_with_references(path, title, x_desc, y_desc, &series, &levels)
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

/// Every figure of the run, written into `dir`.
pub(super) fn write_all(r: &BeamRun, dir: &Path) -> Result<(), Error> {
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
    crate::output::plots::svg(path, (w as u32 + 90, h as u32 + 80), |root| {
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
        crate::output::plots::plane_mesh(&mut chart, &x, &y).map_err(|e| err(&e))?;
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

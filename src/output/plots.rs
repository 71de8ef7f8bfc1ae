//! SVG figures of a run: the disk drawn on the track at a few times (thesis figure 7) and the
//! disk quantities against time (figures 8–11), plus the energy error.

use std::path::Path;

use plotters::prelude::*;

use crate::error::Error;
use crate::run::{RollingRun, Row};

type Series<'a> = (&'a str, Vec<(f64, f64)>);

/// Ten distinct colours (matplotlib's tab10, reordered), so that the ten HSLM trains of a
/// sweep each get their own.
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(188, 189, 34),
    RGBColor(127, 127, 127),
];

/// Pens of the reference lines drawn over a chart's series (an envelope, a code limit): black,
/// which no series is, the first thick and the second thin, so that neither is taken for a
/// series (the palette's grey) or for the other.
const REFERENCE_PENS: [(RGBColor, u32); 2] = [(RGBColor(0, 0, 0), 3), (RGBColor(0, 0, 0), 1)];

fn plot_error(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Output(format!("cannot draw {}: {e}", path.display()))
}

/// An SVG figure of `size` pixels drawn by `draw` in memory, then written as every output file
/// is ([`super::write`]).
pub(crate) fn svg(
    path: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<SVGBackend<'_>, plotters::coord::Shift>) -> Result<(), Error>,
) -> Result<(), Error> {
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_error(path, e))?;
        draw(&root)?;
        root.present().map_err(|e| plot_error(path, e))?;
    }
    super::write(path, &text)
}

/// Padded range of all y values of the series.
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let pad = ((hi - lo) * 0.05).max(1e-12 + 1e-9 * hi.abs().max(lo.abs()));
    (lo - pad, hi + pad)
}

/// One chart with several named lines against a shared x axis.
pub fn line_chart(
    path: &Path,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[Series],
) -> Result<(), Error> {
    stacked_chart(path, x_desc, &[(title, y_desc, series)])
}

/// One chart of named series with reference lines drawn over them in their own pens (an
/// envelope, a limit), against a shared x axis.
pub fn line_chart_with_references(
    path: &Path,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[Series],
    references: &[Series],
) -> Result<(), Error> {
    draw(path, x_desc, &[(title, y_desc, series, references)])
}

/// Charts one above the other over a shared x quantity: (title, y description, lines) each.
pub fn stacked_chart(
    path: &Path,
    x_desc: &str,
    panels: &[(&str, &str, &[Series])],
) -> Result<(), Error> {
    let plain: Vec<Panel> = panels.iter().map(|&(t, y, s)| (t, y, s, &[][..])).collect();
    draw(path, x_desc, &plain)
}

/// A panel: title, y description, its series, and the reference lines drawn over them.
type Panel<'a, 'b> = (&'a str, &'a str, &'a [Series<'b>], &'a [Series<'b>]);

/// Panels one above the other over a shared x quantity, into one SVG file.
fn draw(path: &Path, x_desc: &str, panels: &[Panel]) -> Result<(), Error> {
    let err = |e: &dyn std::fmt::Display| plot_error(path, e);
    svg(path, (900, 520 * panels.len() as u32), |root| {
        for (area, (title, y_desc, series, references)) in
            root.split_evenly((panels.len(), 1)).iter().zip(panels)
        {
            panel(area, title, x_desc, y_desc, series, references).map_err(|e| err(&e))?;
        }
        Ok(())
    })
}

/// The grid of a figure drawn to scale in the plane: X and Y in metres, labelled lines only.
/// The axes of a drawing in the plane, labelled `x` and `y`.
pub(crate) fn plane_mesh<DB: DrawingBackend>(
    chart: &mut ChartContext<
        '_,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    x: &str,
    y: &str,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    chart
        .configure_mesh()
        .light_line_style(TRANSPARENT)
        .x_desc(x)
        .y_desc(y)
        .draw()
}

fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[Series],
    references: &[Series],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let all = || series.iter().chain(references);
    let (x0, x1) = range(all().flat_map(|s| s.1.iter().map(|p| p.0)));
    let (y0, y1) = range(all().flat_map(|s| s.1.iter().map(|p| p.1)));
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        // Only the labelled grid lines: the light ones between them were nine in ten of a
        // figure's elements and a quarter of the time it took to draw.
        .light_line_style(TRANSPARENT)
        .x_desc(x_desc)
        .y_desc(y_desc)
        .draw()?;
    let pens = (0..series.len())
        .map(|i| (PALETTE[i % PALETTE.len()], 2))
        .chain((0..references.len()).map(|j| REFERENCE_PENS[j % REFERENCE_PENS.len()]));
    for ((name, pts), (color, width)) in all().zip(pens) {
        chart
            .draw_series(LineSeries::new(
                pts.iter().copied(),
                color.stroke_width(width),
            ))?
            .label(*name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(width))
            });
    }
    if series.len() + references.len() > 1 {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(legend_corner(all().flat_map(|s| s.1.iter()), x0, x1))
            .draw()?;
    }
    Ok(())
}

/// The upper corner whose outer two-fifths of the x range the lines reach least high, so
/// that the legend hides as little as it can.
fn legend_corner<'p>(
    points: impl Iterator<Item = &'p (f64, f64)>,
    x0: f64,
    x1: f64,
) -> SeriesLabelPosition {
    let (mut left, mut right) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
    for &(x, y) in points.filter(|p| p.1.is_finite()) {
        if x < x0 + 0.4 * (x1 - x0) {
            left = left.max(y);
        } else if x > x1 - 0.4 * (x1 - x0) {
            right = right.max(y);
        }
    }
    if right > left {
        SeriesLabelPosition::UpperLeft
    } else {
        SeriesLabelPosition::UpperRight
    }
}

fn series<'a>(rows: &[Row], name: &'a str, f: impl Fn(&Row) -> f64) -> Series<'a> {
    (name, rows.iter().map(|r| (r.t, f(r))).collect())
}

/// The track with the disk drawn at `count` evenly spaced output times, equal axis scales.
pub fn track_figure(r: &RollingRun, path: &Path, count: usize) -> Result<(), Error> {
    let err = |e: &dyn std::fmt::Display| plot_error(path, e);
    let rolling = &r.setup.rolling;
    let a = rolling.disk.radius;
    let (s_lo, s_hi) = r
        .rows
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), row| {
            (lo.min(row.disk.s), hi.max(row.disk.s))
        });
    let span = (s_hi - s_lo).max(4.0 * a);
    let (mut lo, mut hi) = (s_lo - 0.1 * span, s_hi + 0.1 * span);
    if let Some((d_lo, d_hi)) = rolling.curve.domain() {
        lo = lo.max(d_lo);
        hi = hi.min(d_hi);
    }
    let track: Vec<(f64, f64)> = (0..=400)
        .map(|i| {
            let p = rolling.curve.at(lo + (hi - lo) * i as f64 / 400.0);
            (p.r[0], p.r[1])
        })
        .collect();
    let picks: Vec<&Row> = (0..count)
        .map(|k| &r.rows[k * (r.rows.len() - 1) / (count - 1).max(1)])
        .collect();
    let xs = track.iter().map(|p| p.0).chain(
        picks
            .iter()
            .flat_map(|row| [row.disk.x - a, row.disk.x + a]),
    );
    let ys = track.iter().map(|p| p.1).chain(
        picks
            .iter()
            .flat_map(|row| [row.disk.y - a, row.disk.y + a]),
    );
    let (mut x0, mut x1) = range(xs);
    let (mut y0, mut y1) = range(ys);
    // Equal scales on both axes so the disk stays round.
    let (w, h) = (900.0, 620.0);
    let scale = ((x1 - x0) / w).max((y1 - y0) / h);
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    (x0, x1) = (cx - scale * w / 2.0, cx + scale * w / 2.0);
    (y0, y1) = (cy - scale * h / 2.0, cy + scale * h / 2.0);

    svg(path, (900 + 90, 620 + 80), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!("{}: the disk at {count} times", r.header.scene.name),
                ("sans-serif", 22),
            )
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| err(&e))?;
        plane_mesh(&mut chart, "X (m)", "Y (m)").map_err(|e| err(&e))?;
        chart
            .draw_series(LineSeries::new(track, BLACK.stroke_width(2)))
            .map_err(|e| err(&e))?;
        if !r.flights.is_empty() {
            // The centre's path, so that a flight's parabola stands out from the rolling.
            chart
                .draw_series(LineSeries::new(
                    r.rows.iter().map(|row| (row.disk.x, row.disk.y)),
                    RGBColor(150, 150, 150).stroke_width(1),
                ))
                .map_err(|e| err(&e))?;
        }
        for (k, row) in picks.iter().enumerate() {
            let color = PALETTE[k % PALETTE.len()];
            let d = &row.disk;
            let rim: Vec<(f64, f64)> = (0..=72)
                .map(|i| {
                    let th = i as f64 * std::f64::consts::TAU / 72.0;
                    (d.x + a * th.cos(), d.y + a * th.sin())
                })
                .collect();
            chart
                .draw_series(LineSeries::new(rim, color.stroke_width(2)))
                .map_err(|e| err(&e))?;
            // A spoke fixed in the disk: at φ = 0 it points to the contact point.
            let tangent = rolling.curve.at(d.s).tangent();
            let angle = tangent[1].atan2(tangent[0]) - std::f64::consts::FRAC_PI_2 + d.phi;
            let spoke = vec![(d.x, d.y), (d.x + a * angle.cos(), d.y + a * angle.sin())];
            chart
                .draw_series(LineSeries::new(spoke, color.stroke_width(2)))
                .map_err(|e| err(&e))?;
            chart
                .draw_series(std::iter::once(Text::new(
                    format!("{:.2} s", row.t),
                    (d.x, d.y + 1.25 * a),
                    ("sans-serif", 14).into_font().color(&color),
                )))
                .map_err(|e| err(&e))?;
        }
        Ok(())
    })
}

/// Every figure of a rigid-track run.
pub fn all(r: &RollingRun, dir: &Path) -> Result<(), Error> {
    let rows = &r.rows;
    let name = &r.header.scene.name;
    track_figure(r, &dir.join("track.svg"), 8)?;
    line_chart(
        &dir.join("velocities.svg"),
        &format!("{name}: centre velocity"),
        "t (s)",
        "v (m/s)",
        &[
            series(rows, "vx", |r| r.disk.vx),
            series(rows, "vy", |r| r.disk.vy),
        ],
    )?;
    line_chart(
        &dir.join("omega.svg"),
        &format!("{name}: angular velocity"),
        "t (s)",
        "Ω (1/s)",
        &[series(rows, "Ω", |r| r.disk.omega)],
    )?;
    let forces = [
        series(rows, "R_t (tangential)", |r| r.disk.rt),
        series(rows, "R_n (normal)", |r| r.disk.rn),
    ];
    let title = format!("{name}: contact force on the disk");
    let gap = [series(rows, "gap", |r| r.gap)];
    let gap_title = format!("{name}: gap between the disk and the track (0 while it rolls)");
    let mut panels: Vec<(&str, &str, &[Series])> = vec![(&title, "R (N)", &forces)];
    if !r.flights.is_empty() {
        panels.push((&gap_title, "gap (m)", &gap));
    }
    stacked_chart(&dir.join("reactions.svg"), "t (s)", &panels)?;
    let e0 = r.header.energy.initial;
    let scale = r.header.energy.scale.max(f64::MIN_POSITIVE);
    line_chart(
        &dir.join("energy.svg"),
        &format!("{name}: energy error (E(t) − E(0)) / max(|K| + |V|)"),
        "t (s)",
        "relative error",
        &[series(rows, "energy error", |r| (r.energy() - e0) / scale)],
    )
}

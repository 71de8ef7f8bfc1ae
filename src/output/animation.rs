//! `animation.svg` (`rollbeam run --animate`): the disks rolling on the magnified beam, as an
//! SVG that animates itself (SMIL), so any browser plays it with no player or codec. Each
//! frame of the run is one value of a discrete animation: the beam's polyline, each disk's
//! centre and a spoke that shows how far it has turned, and the vehicles' wheels.

use std::fmt::Write;
use std::path::Path;

use super::write;
use crate::error::Error;
use crate::run::beam::BeamRun;

const WIDTH: f64 = 960.0;
const MARGIN: f64 = 30.0;

pub fn write_animation(r: &BeamRun, path: &Path) -> Result<(), Error> {
    let frames = &r.frames;
    if frames.len() < 2 {
        return Err(Error::Output(format!(
            "cannot animate {}: the run has fewer than two frames",
            r.header.scene.name
        )));
    }
    let mag = r.setup.magnify;
    let radii: Vec<f64> = r.setup.disks.iter().map(|d| d.disk.radius).collect();
    let (shapes, disks) = frame_geometry(r);
    let [x0, x1, y0, y1] = bounds(&shapes, &disks, &radii);
    let k = (WIDTH - 2.0 * MARGIN) / (x1 - x0).max(1e-9);
    let height = (y1 - y0) * k + 2.0 * MARGIN + 30.0;
    let to_svg = |p: [f64; 2]| (MARGIN + (p[0] - x0) * k, MARGIN + 30.0 + (y1 - p[1]) * k);
    let duration = frames.last().map_or(1.0, |f| f.t).max(1e-9);
    let key_times: Vec<String> = frames
        .iter()
        .map(|f| format!("{:.5}", f.t / duration))
        .collect();
    let key_times = key_times.join(";");
    let animate = |attr: &str, values: &[String]| {
        format!(
            r#"<animate attributeName="{attr}" dur="{duration}s" repeatCount="indefinite" calcMode="discrete" keyTimes="{key_times}" values="{}"/>"#,
            values.join(";")
        )
    };
    let points: Vec<String> = shapes
        .iter()
        .map(|pts| {
            pts.iter()
                .map(|&p| {
                    let (x, y) = to_svg(p);
                    format!("{x:.1},{y:.1}")
                })
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{height:.0}" viewBox="0 0 {WIDTH} {height:.0}">"#
    );
    let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        svg,
        r#"<text x="{MARGIN}" y="20" font-family="sans-serif" font-size="15">{}: displacements × {mag}, disk to scale, {duration:.3} s of motion per loop</text>"#,
        r.header.scene.name
    );
    let reference: Vec<String> = [0.0, r.beam.length]
        .iter()
        .map(|&x| {
            let (a, b) = to_svg(r.beam.reference_point(x));
            format!("{a:.1},{b:.1}")
        })
        .collect();
    let _ = writeln!(
        svg,
        r##"<polyline points="{}" fill="none" stroke="#999" stroke-dasharray="4 4"/>"##,
        reference.join(" ")
    );
    let _ = writeln!(
        svg,
        r##"<polyline points="{}" fill="none" stroke="#1f77b4" stroke-width="3">{}</polyline>"##,
        points[0],
        animate("points", &points)
    );
    for (disk, &radius) in disks.iter().zip(&radii) {
        let held = held(disk, [x0, y0]);
        let coord = |f: fn((f64, f64)) -> f64| -> Vec<String> {
            held.iter()
                .map(|(c, _, _)| format!("{:.1}", f(to_svg(*c))))
                .collect()
        };
        let rim = |f: fn((f64, f64)) -> f64| -> Vec<String> {
            held.iter()
                .map(|(c, turned, _)| {
                    let p = [
                        c[0] + radius * (turned + 0.5 * std::f64::consts::PI).cos(),
                        c[1] + radius * (turned + 0.5 * std::f64::consts::PI).sin(),
                    ];
                    format!("{:.1}", f(to_svg(p)))
                })
                .collect()
        };
        let opacity: Vec<String> = held
            .iter()
            .map(|(_, _, on)| if *on { "1" } else { "0.25" }.to_string())
            .collect();
        disk_group(&mut svg, (&coord, &rim), &opacity, radius * k, &animate);
    }
    wheel_dots(&mut svg, r, &shapes, &to_svg, &animate, [x0, y0]);
    svg.push_str("</svg>\n");
    write(path, &svg)
}

/// A column of an animation: the attribute's values, frame by frame.
type Values = Vec<String>;

/// The disk: a circle at its centre and a spoke to its rim, frame by frame (`coord` and `rim`
/// give the x or y values of each), faded while it flies (`opacity`).
fn disk_group(
    svg: &mut String,
    (coord, rim): (
        &dyn Fn(fn((f64, f64)) -> f64) -> Values,
        &dyn Fn(fn((f64, f64)) -> f64) -> Values,
    ),
    opacity: &[String],
    r_px: f64,
    animate: &dyn Fn(&str, &[String]) -> String,
) {
    let (cx, cy) = (coord(|p| p.0), coord(|p| p.1));
    let (rx, ry) = (rim(|p| p.0), rim(|p| p.1));
    // The first frame as plain attributes, for viewers that do not animate.
    let _ = writeln!(
        svg,
        r##"<g>{}<circle r="{r_px:.1}" cx="{}" cy="{}" fill="#f2c14e" stroke="#333" stroke-width="2">{}{}</circle><line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#333" stroke-width="2">{}{}{}{}</line></g>"##,
        animate("opacity", &opacity),
        cx[0],
        cy[0],
        animate("cx", &cx),
        animate("cy", &cy),
        cx[0],
        cy[0],
        rx[0],
        ry[0],
        animate("x1", &cx),
        animate("y1", &cy),
        animate("x2", &rx),
        animate("y2", &ry),
    );
}

/// Each wheel a dot on the magnified axis `shapes` while it is on the deck; `fallback` where
/// one never is.
fn wheel_dots(
    svg: &mut String,
    r: &BeamRun,
    shapes: &[Vec<[f64; 2]>],
    to_svg: &dyn Fn([f64; 2]) -> (f64, f64),
    animate: &dyn Fn(&str, &[String]) -> String,
    fallback: [f64; 2],
) {
    let frames = &r.frames;
    let wheels = frames.first().map_or(0, |f| f.wheels.len());
    for j in 0..wheels {
        let at: Vec<Option<[f64; 2]>> = frames
            .iter()
            .zip(shapes)
            .map(|(f, pts)| on_axis(&r.envelope.x, pts, r.beam.length, f.wheels[j]))
            .collect();
        let first = at.iter().flatten().next().copied().unwrap_or(fallback);
        let placed: Vec<(f64, f64)> = at.iter().map(|p| to_svg(p.unwrap_or(first))).collect();
        let cx: Vec<String> = placed.iter().map(|p| format!("{:.1}", p.0)).collect();
        let cy: Vec<String> = placed.iter().map(|p| format!("{:.1}", p.1)).collect();
        let shown: Vec<String> = at
            .iter()
            .map(|p| if p.is_some() { "1" } else { "0" }.to_string())
            .collect();
        let _ = writeln!(
            svg,
            r##"<circle r="5" cx="{}" cy="{}" fill="#333" opacity="{}">{}{}{}</circle>"##,
            cx[0],
            cy[0],
            shown[0],
            animate("cx", &cx),
            animate("cy", &cy),
            animate("opacity", &shown),
        );
    }
}

/// The point of the magnified axis `pts` (at the stations `xs`) at material point x, while x
/// is on a beam of `length`.
fn on_axis(xs: &[f64], pts: &[[f64; 2]], length: f64, x: f64) -> Option<[f64; 2]> {
    if !(0.0..=length).contains(&x) || xs.len() < 2 {
        return None;
    }
    let k = xs.partition_point(|&s| s < x).clamp(1, xs.len() - 1);
    let g = ((x - xs[k - 1]) / (xs[k] - xs[k - 1])).clamp(0.0, 1.0);
    Some([
        pts[k - 1][0] + g * (pts[k][0] - pts[k - 1][0]),
        pts[k - 1][1] + g * (pts[k][1] - pts[k - 1][1]),
    ])
}

/// A disk's centre and turned angle in each frame, while it is on or over the beam.
type DiskFrames = Vec<Option<([f64; 2], f64)>>;

/// The magnified axis in each frame, and each disk's centre and turned angle on it (or over
/// it, in flight) while it is on or over the beam.
fn frame_geometry(r: &BeamRun) -> (Vec<Vec<[f64; 2]>>, Vec<DiskFrames>) {
    let frames = &r.frames;
    let mag = r.setup.magnify;
    let xs = &r.envelope.x;
    let (sn, cs) = r.beam.angle.sin_cos();
    let shape = |along: &[crate::beam::PointDisplacement]| -> Vec<[f64; 2]> {
        xs.iter()
            .zip(along)
            .map(|(&x, d)| {
                let p = r.beam.reference_point(x);
                [p[0] + mag * d.u, p[1] + mag * d.w]
            })
            .collect()
    };
    let shapes: Vec<Vec<[f64; 2]>> = frames.iter().map(|f| shape(&f.along)).collect();
    let disks = r
        .setup
        .disks
        .iter()
        .enumerate()
        .map(|(k, d)| {
            frames
                .iter()
                .zip(&shapes)
                .map(|(f, pts)| {
                    f.disks[k].map(|(s, turned, gap)| {
                        let p = on_axis(xs, pts, f64::INFINITY, s.max(0.0)).unwrap_or(pts[0]);
                        // A flying disk's gap is a displacement from the track: magnified
                        // with it.
                        let lift = d.disk.radius + mag * gap;
                        ([p[0] - lift * sn, p[1] + lift * cs], turned)
                    })
                })
                .collect()
        })
        .collect();
    (shapes, disks)
}

/// [x0, x1, y0, y1] of the smallest box holding every frame's axis and disks.
fn bounds(shapes: &[Vec<[f64; 2]>], disks: &[DiskFrames], radii: &[f64]) -> [f64; 4] {
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for p in shapes.iter().flatten() {
        (x0, x1, y0, y1) = (x0.min(p[0]), x1.max(p[0]), y0.min(p[1]), y1.max(p[1]));
    }
    for (disk, radius) in disks.iter().zip(radii) {
        for (c, _) in disk.iter().flatten() {
            (x0, x1) = (x0.min(c[0] - radius), x1.max(c[0] + radius));
            (y0, y1) = (y0.min(c[1] - radius), y1.max(c[1] + radius));
        }
    }
    [x0, x1, y0, y1]
}

/// The disk in every frame: where it is while on the beam; off it, held where it was last on
/// it (before its first frame there, where it last is), and marked off so that it is drawn
/// faded.
fn held(disks: &[Option<([f64; 2], f64)>], corner: [f64; 2]) -> Vec<([f64; 2], f64, bool)> {
    let last_disk = disks.iter().flatten().last().copied();
    disks
        .iter()
        .scan(None, |prev: &mut Option<([f64; 2], f64)>, d| {
            if d.is_some() {
                *prev = *d;
            }
            Some(prev.or(last_disk).map(|(c, a)| (c, a, d.is_some())))
        })
        .map(|d| d.unwrap_or((corner, 0.0, false)))
        .collect()
}

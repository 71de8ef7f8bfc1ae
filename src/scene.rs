//! The scene file (see SCENE-FORMAT in the README): read with locations, checked, and turned
//! into the model it names, and only that. Every problem is reported as one sentence with the
//! file, the line and the key.

use std::path::Path;

use serde::de::IgnoredAny;
use serde::Deserialize;
use serde_saphyr::Spanned;

use crate::curve::expr::Formula;
use crate::curve::spline::Spline;
use crate::curve::Curve;
use crate::disk::Disk;
use crate::error::Error;
use crate::ode::Method;
use crate::rolling::Rolling;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    name: Option<String>,
    gravity: Option<Spanned<f64>>,
    duration: Spanned<f64>,
    track: Spanned<TrackFile>,
    disk: Option<Spanned<DiskFile>>,
    loads: Option<Spanned<IgnoredAny>>,
    solver: Option<SolverFile>,
    output: Option<OutputFile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TrackFile {
    curve: Option<Spanned<CurveFile>>,
    beam: Option<Spanned<IgnoredAny>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CurveFile {
    parabola: Option<ParabolaFile>,
    line: Option<LineFile>,
    expr: Option<ExprFile>,
    points: Option<Spanned<Vec<Spanned<[f64; 2]>>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ParabolaFile {
    k: Spanned<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LineFile {
    from: Spanned<[f64; 2]>,
    to: Spanned<[f64; 2]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ExprFile {
    x: Spanned<String>,
    y: Spanned<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DiskFile {
    mass: Spanned<f64>,
    radius: Spanned<f64>,
    s0: Option<Spanned<f64>>,
    omega0: Option<Spanned<f64>>,
    coupling: Option<Spanned<String>>,
    formulation: Option<Spanned<String>>,
    mu: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SolverFile {
    method: Option<Spanned<String>>,
    rtol: Option<Spanned<f64>>,
    atol: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct OutputFile {
    interval: Option<Spanned<f64>>,
    probes: Option<Spanned<IgnoredAny>>,
    shapes: Option<Spanned<IgnoredAny>>,
    magnify: Option<Spanned<IgnoredAny>>,
}

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
}

/// A checked scene: everything the run needs, nothing it does not.
#[derive(Clone, Debug)]
pub struct Scene {
    pub name: String,
    pub duration: f64,
    pub rolling: Rolling,
    pub formulation: Formulation,
    pub solver: SolverSettings,
    /// Time between rows of history.csv.
    pub interval: f64,
}

pub const DEFAULT_GRAVITY: f64 = 9.81;

/// Reports problems as "FILE line N: KEY ...".
struct Checker<'a> {
    file: &'a str,
}

impl Checker<'_> {
    fn err<T>(&self, line: u64, key: &str, msg: impl std::fmt::Display) -> Result<T, Error> {
        Err(Error::Input(format!(
            "{} line {line}: `{key}` {msg}",
            self.file
        )))
    }

    fn finite(&self, v: &Spanned<f64>, key: &str) -> Result<f64, Error> {
        if !v.value.is_finite() {
            return self.err(
                v.referenced.line(),
                key,
                format!("must be a finite number, not {}", v.value),
            );
        }
        Ok(v.value)
    }

    fn positive(&self, v: &Spanned<f64>, key: &str) -> Result<f64, Error> {
        let x = self.finite(v, key)?;
        if x <= 0.0 {
            return self.err(
                v.referenced.line(),
                key,
                format!("must be positive (got {x})"),
            );
        }
        Ok(x)
    }

    fn pair(&self, v: &Spanned<[f64; 2]>, key: &str) -> Result<[f64; 2], Error> {
        if v.value.iter().any(|x| !x.is_finite()) {
            return self.err(
                v.referenced.line(),
                key,
                format!("must hold finite numbers, not {:?}", v.value),
            );
        }
        Ok(v.value)
    }
}

impl Scene {
    pub fn load(path: &Path) -> Result<Scene, Error> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::Input(format!("cannot read scene file {}: {e}", path.display())))?;
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        Scene::parse(&text, &path.display().to_string(), &stem)
    }

    /// `file` names the source in messages; `stem` is the default scene name.
    pub fn parse(text: &str, file: &str, stem: &str) -> Result<Scene, Error> {
        let raw: SceneFile = serde_saphyr::from_str(text).map_err(|e| {
            let msg = e.to_string();
            let first = msg
                .lines()
                .next()
                .unwrap_or("not a valid scene")
                .trim()
                .trim_start_matches("error: ")
                .to_string();
            Error::Input(format!("{file} is not a valid scene: {first}"))
        })?;
        let c = Checker { file };

        let gravity = match &raw.gravity {
            Some(g) => c.finite(g, "gravity")?,
            None => DEFAULT_GRAVITY,
        };
        let duration = c.positive(&raw.duration, "duration")?;

        let track = &raw.track;
        let curve_file = match (&track.value.curve, &track.value.beam) {
            (Some(_), Some(_)) | (None, None) => {
                return c.err(
                    track.referenced.line(),
                    "track",
                    "must name exactly one of `curve` or `beam`",
                )
            }
            (None, Some(b)) => return c.err(
                b.referenced.line(),
                "track.beam",
                "flexible beam tracks are not implemented yet in this version; use a rigid `curve`",
            ),
            (Some(curve), None) => curve,
        };
        if let Some(loads) = &raw.loads {
            return c.err(
                loads.referenced.line(),
                "loads",
                "apply to beam tracks only; a rigid curve carries no loads",
            );
        }
        let curve = build_curve(&c, curve_file)?;

        let Some(disk_file) = &raw.disk else {
            return c.err(
                track.referenced.line(),
                "disk",
                "is missing: a rigid curve needs a disk to roll on it",
            );
        };
        let d = &disk_file.value;
        let disk = Disk {
            mass: c.positive(&d.mass, "disk.mass")?,
            radius: c.positive(&d.radius, "disk.radius")?,
        };
        let s0 = match &d.s0 {
            Some(s) => c.finite(s, "disk.s0")?,
            None => 0.0,
        };
        let omega0 = match &d.omega0 {
            Some(w) => c.finite(w, "disk.omega0")?,
            None => 0.0,
        };
        let mu = match &d.mu {
            Some(m) => Some(c.positive(m, "disk.mu")?),
            None => None,
        };
        if let Some(cp) = &d.coupling {
            return c.err(
                cp.referenced.line(),
                "disk.coupling",
                "applies to beam tracks only; on a rigid curve choose `formulation`",
            );
        }
        let formulation = match &d.formulation {
            None => Formulation::Minimal,
            Some(f) => match f.value.as_str() {
                "minimal" => Formulation::Minimal,
                "thesis" => Formulation::Thesis,
                other => {
                    return c.err(
                        f.referenced.line(),
                        "disk.formulation",
                        format!("is '{other}'; use minimal or thesis"),
                    )
                }
            },
        };
        if let Some((lo, hi)) = curve.domain() {
            if !(lo..=hi).contains(&s0) {
                let line =
                    d.s0.as_ref()
                        .map_or(disk_file.referenced.line(), |s| s.referenced.line());
                return c.err(
                    line,
                    "disk.s0",
                    format!(
                        "= {s0} is off the track: the {} runs over s in [{lo}, {hi}]",
                        curve.kind()
                    ),
                );
            }
        }
        let rolling = Rolling::new(curve, disk, gravity, s0, omega0, mu);
        if let Some(s) = rolling.first_unfit_point() {
            let kappa = rolling.curve.at(s).curvature();
            return c.err(
                d.radius.referenced.line(),
                "disk.radius",
                format!(
                    "= {} does not fit the curve at s = {s:.4}, which the disk can reach: the radius of curvature there is {:.4} m (the disk needs radius × curvature < 1)",
                    disk.radius,
                    1.0 / kappa
                ),
            );
        }

        let mut solver = SolverSettings {
            method: Method::Dopri5,
            rtol: 1e-6,
            atol: 1e-9,
        };
        if let Some(s) = &raw.solver {
            if let Some(m) = &s.method {
                solver.method = Method::from_name(&m.value).map_or_else(
                    || {
                        c.err(
                            m.referenced.line(),
                            "solver.method",
                            format!("is '{}'; use one of {}", m.value, method_names()),
                        )
                    },
                    Ok,
                )?;
            }
            if let Some(r) = &s.rtol {
                solver.rtol = c.positive(r, "solver.rtol")?;
            }
            if let Some(a) = &s.atol {
                solver.atol = c.positive(a, "solver.atol")?;
            }
        }

        let mut interval = duration / 500.0;
        if let Some(o) = &raw.output {
            if let Some(i) = &o.interval {
                interval = c.positive(i, "output.interval")?;
            }
            for (v, key) in [
                (&o.probes, "output.probes"),
                (&o.shapes, "output.shapes"),
                (&o.magnify, "output.magnify"),
            ] {
                if let Some(v) = v {
                    return c.err(v.referenced.line(), key, "applies to beam tracks only");
                }
            }
        }

        Ok(Scene {
            name: raw.name.unwrap_or_else(|| stem.to_string()),
            duration,
            rolling,
            formulation,
            solver,
            interval,
        })
    }
}

pub fn method_names() -> String {
    Method::ALL.map(|m| m.name()).join(", ")
}

fn build_curve(c: &Checker, file: &Spanned<CurveFile>) -> Result<Curve, Error> {
    let f = &file.value;
    let count = [
        f.parabola.is_some(),
        f.line.is_some(),
        f.expr.is_some(),
        f.points.is_some(),
    ]
    .iter()
    .filter(|&&b| b)
    .count();
    if count != 1 {
        return c.err(
            file.referenced.line(),
            "track.curve",
            "must name exactly one of parabola, line, expr or points",
        );
    }
    if let Some(p) = &f.parabola {
        let k = c.finite(&p.k, "track.curve.parabola.k")?;
        if k == 0.0 {
            return c.err(
                p.k.referenced.line(),
                "track.curve.parabola.k",
                "is 0: that is a straight line; use `line`",
            );
        }
        return Ok(Curve::Parabola { k });
    }
    if let Some(l) = &f.line {
        let from = c.pair(&l.from, "track.curve.line.from")?;
        let to = c.pair(&l.to, "track.curve.line.to")?;
        if from == to {
            return c.err(
                l.to.referenced.line(),
                "track.curve.line.to",
                "equals `from`: the line has zero length",
            );
        }
        return Ok(Curve::Line { from, to });
    }
    if let Some(e) = &f.expr {
        let parse = |v: &Spanned<String>, key: &str| {
            Formula::parse(&v.value)
                .or_else(|m| c.err(v.referenced.line(), key, format!("does not parse: {m}")))
        };
        return Ok(Curve::Expr {
            x: parse(&e.x, "track.curve.expr.x")?,
            y: parse(&e.y, "track.curve.expr.y")?,
        });
    }
    let pts = f.points.as_ref().expect("one kind is present");
    if pts.value.len() < 4 {
        return c.err(
            pts.referenced.line(),
            "track.curve.points",
            format!(
                "has {} points; a C2 spline needs at least 4",
                pts.value.len()
            ),
        );
    }
    let mut xy = Vec::with_capacity(pts.value.len());
    for (i, p) in pts.value.iter().enumerate() {
        let q = c.pair(p, "track.curve.points")?;
        if let Some(prev) = xy.last().map(|p: &[f64; 2]| p[0]) {
            if q[0] <= prev {
                return c.err(
                    p.referenced.line(),
                    "track.curve.points",
                    format!(
                        "must have X increasing, but point {} has X = {} after {prev}",
                        i + 1,
                        q[0]
                    ),
                );
            }
        }
        xy.push(q);
    }
    Ok(Curve::Points(Spline::new(&xy)))
}

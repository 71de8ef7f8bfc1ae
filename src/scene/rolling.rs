//! A disk on a rigid curve: the curve, the disk, and what happens where contact is lost.

use super::*;

/// `disk.contact_loss` and `disk.restitution`, checked; `None` where the scene gives neither.
pub(super) fn contact_loss(
    c: &Checker,
    d: &DiskFile,
    at: &str,
) -> Result<Option<ContactLoss>, Error> {
    let restitution = match &d.restitution {
        Some(e) => {
            let v = c.finite(e, &format!("{at}.restitution"))?;
            if !(0.0..=1.0).contains(&v) {
                return c.err(
                    e.referenced.line(),
                    &format!("{at}.restitution"),
                    format!("= {v} is outside [0, 1]: the share of the normal speed a landing gives back (0 plastic, 1 elastic)"),
                );
            }
            Some((v, e.referenced.line()))
        }
        None => None,
    };
    match (&d.contact_loss, restitution) {
        (None, None) => Ok(None),
        (None, Some((e, _))) => Ok(Some(ContactLoss::Fly { restitution: e })),
        (Some(k), e) => match k.value.as_str() {
            "fly" => Ok(Some(ContactLoss::Fly {
                restitution: e.map_or(0.0, |e| e.0),
            })),
            "stop" => match e {
                Some((_, line)) => c.err(
                    line,
                    &format!("{at}.restitution"),
                    "acts at a landing, and with `contact_loss: stop` the disk never lands; leave it out or fly",
                ),
                None => Ok(Some(ContactLoss::Stop)),
            },
            other => c.err(
                k.referenced.line(),
                &format!("{at}.contact_loss"),
                format!("is {}; use fly or stop", quote(other)),
            ),
        },
    }
}

pub(super) fn rolling_scene(
    c: &Checker,
    raw: &SceneFile,
    curve_file: &Spanned<CurveFile>,
    gravity: f64,
) -> Result<RollingScene, Error> {
    let track = &raw.track;
    refuse_beam_keys(c, raw)?;
    let curve = build_curve(c, curve_file)?;
    let Some(disk_file) = &raw.disk else {
        return c.err(
            track.referenced.line(),
            "disk",
            "is missing: a rigid curve needs a disk to roll on it",
        );
    };
    let d = &disk_file.value;
    let disk = c.disk(d, gravity, "disk")?;
    let s0 = match &d.s0 {
        Some(s) => c.finite(s, "disk.s0")?,
        None => 0.0,
    };
    let omega0 = match &d.omega0 {
        Some(w) => c.finite(w, "disk.omega0")?,
        None => 0.0,
    };
    if let Some(w) = &d.omega0 {
        c.speed(w.referenced.line(), "disk.omega0", disk.radius * omega0)?;
    }
    let mu = match &d.mu {
        Some(m) => Some(c.positive(m, "disk.mu")?),
        None => None,
    };
    refuse_beam_disk_keys(c, d)?;
    let formulation = formulation(c, d)?;
    let s0_line =
        d.s0.as_ref()
            .map_or(disk_file.referenced.line(), |s| s.referenced.line());
    if let Some((lo, hi)) = curve.domain() {
        if !(lo..=hi).contains(&s0) {
            return c.err(
                s0_line,
                "disk.s0",
                format!(
                    "= {s0} is off the track: the {} runs over s in [{lo}, {hi}]",
                    curve.kind()
                ),
            );
        }
    }
    let mut rolling = Rolling::new(curve, disk, gravity, s0, omega0, mu);
    rolling.contact_loss =
        contact_loss(c, d, "disk")?.unwrap_or(ContactLoss::Fly { restitution: 0.0 });
    disk_fits(c, &rolling, curve_file, d)?;
    start_is_finite(c, &rolling, s0_line)?;
    Ok(RollingScene {
        rolling,
        formulation,
    })
}

/// A disk's keys that only a beam track takes.
fn refuse_beam_disk_keys(c: &Checker, d: &DiskFile) -> Result<(), Error> {
    if let Some(cp) = &d.coupling {
        return c.err(
            cp.referenced.line(),
            "disk.coupling",
            "applies to beam tracks only; on a rigid curve choose `formulation`",
        );
    }
    if let Some(p) = &d.patch {
        return c.err(
            p.referenced.line(),
            "disk.patch",
            "applies to beam tracks only; on a rigid curve the contact is a point",
        );
    }
    Ok(())
}

fn formulation(c: &Checker, d: &DiskFile) -> Result<Formulation, Error> {
    match &d.formulation {
        None => Ok(Formulation::Minimal),
        Some(f) => match f.value.as_str() {
            "minimal" => Ok(Formulation::Minimal),
            "thesis" => Ok(Formulation::Thesis),
            other => c.err(
                f.referenced.line(),
                "disk.formulation",
                format!("is {}; use minimal or thesis", quote(other)),
            ),
        },
    }
}

/// The disk fits the curve wherever it can reach: radius × curvature < 1, the curvature finite.
fn disk_fits(
    c: &Checker,
    rolling: &Rolling,
    curve_file: &Spanned<CurveFile>,
    d: &DiskFile,
) -> Result<(), Error> {
    let Some(s) = rolling.first_unfit_point() else {
        return Ok(());
    };
    let kappa = rolling.curve.at(s).curvature();
    if !kappa.is_finite() {
        return c.err(
            curve_file.referenced.line(),
            "track.curve",
            format!("has no finite tangent or curvature at s = {s:.4}, where the disk can reach (r' = 0 or a derivative is infinite there)"),
        );
    }
    c.err(
        d.radius.referenced.line(),
        "disk.radius",
        format!(
            "= {} does not fit the curve at s = {s:.4}, which the disk can reach: the radius of curvature there is {:.4} m (the disk needs radius × curvature < 1)",
            rolling.disk.radius,
            1.0 / kappa
        ),
    )
}

/// The start in numbers: a finite point can still lie where the curve's coordinates, or the
/// energy measured from them, overflow.
fn start_is_finite(c: &Checker, rolling: &Rolling, s0_line: u64) -> Result<(), Error> {
    let s0 = rolling.s0;
    let start = rolling.curve.at(s0);
    let centre = rolling.centre(&start);
    let (kinetic, potential) = rolling.energies(rolling.v0(), rolling.omega0, centre[1]);
    for (v, what) in [
        (centre[0], "the centre's X at the start"),
        (centre[1], "the centre's Y at the start"),
        (start.speed(), "the curve's speed |r'| at the start"),
        (kinetic + potential, "the initial energy"),
    ] {
        if !v.is_finite() {
            return c.err(
                s0_line,
                "disk.s0",
                format!(
                    "= {s0} makes {what} infinite or undefined; start the disk where the curve's numbers are finite"
                ),
            );
        }
    }
    Ok(())
}

pub(super) fn build_curve(c: &Checker, file: &Spanned<CurveFile>) -> Result<Curve, Error> {
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

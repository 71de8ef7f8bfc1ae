//! How a run is scored against the reference: its headline quantities, its history and its
//! probes' windowed means, each as a largest relative error.

use super::*;

/// One quantity a user reads off a run, and the family whose largest value scales its error.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Headline {
    pub name: String,
    pub value: f64,
    pub(super) family: String,
}

/// The headline quantities of a run.
pub fn headlines(r: &Run) -> Vec<Headline> {
    let h = |name: String, value: f64, family: &str| Headline {
        name,
        value,
        family: family.to_string(),
    };
    let mut out = Vec::new();
    match r {
        Run::Beam(b) => {
            for (k, p) in b.setup.probes.iter().enumerate() {
                let (lo, hi) = b
                    .rows
                    .iter()
                    .map(|row| row.probes[k].w)
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), w| {
                        (l.min(w), u.max(w))
                    });
                out.push(h(format!("{}.w_min", p.name), lo, "w"));
                out.push(h(format!("{}.w_max", p.name), hi, "w"));
            }
        }
        Run::Rolling(rr) => {
            let d = rr.last.disk;
            out.push(h("disk.x_end".into(), d.x, "position"));
            out.push(h("disk.y_end".into(), d.y, "position"));
            let (lo, hi) = rr
                .rows
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), row| {
                    (l.min(row.disk.rn), u.max(row.disk.rn))
                });
            out.push(h("disk.rn_min".into(), lo, "rn"));
            out.push(h("disk.rn_max".into(), hi, "rn"));
        }
    }
    out.push(h("t_end".into(), r.header().t_end, "t"));
    out
}

/// max |a − b| / (largest |b| of the same family), over the headlines.
pub fn headline_error(a: &[Headline], reference: &[Headline]) -> f64 {
    let scale = |family: &str| {
        reference
            .iter()
            .filter(|h| h.family == family)
            .fold(0.0_f64, |m, h| m.max(h.value.abs()))
            .max(f64::MIN_POSITIVE)
    };
    a.iter()
        .zip(reference)
        .map(|(x, r)| (x.value - r.value).abs() / scale(&r.family))
        .fold(0.0, |m, e| if e.is_nan() { f64::NAN } else { m.max(e) })
}

/// The history a run is compared on: per output time, the probes' deflections (beam) or the
/// disk centre (rigid curve).
pub fn history(r: &Run) -> Vec<(f64, Vec<f64>)> {
    match r {
        Run::Beam(b) => b
            .rows
            .iter()
            .map(|row| (row.t, row.probes.iter().map(|p| p.w).collect()))
            .collect(),
        Run::Rolling(rr) => rr
            .rows
            .iter()
            .map(|row| (row.t, vec![row.disk.x, row.disk.y]))
            .collect(),
    }
}

/// max over the reference's output times of |a − b| at the same time, relative to the largest
/// |b|; a reference time the run did not reach (it ended before) counts as wholly wrong. Rows
/// are matched by time: a run also records the times of its scene's shapes.
pub fn history_error(a: &[(f64, Vec<f64>)], reference: &[(f64, Vec<f64>)]) -> f64 {
    let scale = reference
        .iter()
        .flat_map(|(_, v)| v.iter())
        .fold(0.0_f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let same_time = |x: f64, y: f64| (x - y).abs() <= 1e-9 * (1.0 + y.abs());
    let mut rows = a.iter().peekable();
    let mut worst = 0.0_f64;
    for (t, r) in reference {
        while rows
            .next_if(|(ta, _)| *ta < *t && !same_time(*ta, *t))
            .is_some()
        {}
        match rows.peek() {
            Some((ta, x)) if same_time(*ta, *t) => {
                worst = x
                    .iter()
                    .zip(r)
                    .map(|(p, q)| (p - q).abs())
                    .fold(worst, f64::max);
            }
            _ => return 1.0,
        }
    }
    worst / scale
}

/// max |a − b| / scale over the windows; a run that did not cover the reference's windows
/// counts as wholly wrong.
pub fn mean_error(a: &[f64], reference: &MeansReference) -> f64 {
    if a.len() != reference.values.len() {
        return 1.0;
    }
    a.iter()
        .zip(&reference.values)
        .map(|(x, r)| (x - r).abs() / reference.scale)
        .fold(0.0, |m, e| if e.is_nan() { f64::NAN } else { m.max(e) })
}

/// The windowed means of a beam run (none on a rigid curve).
pub fn windowed_means(r: &Run) -> Option<&[f64]> {
    match r {
        Run::Beam(b) => Some(&b.windowed_means),
        Run::Rolling(_) => None,
    }
}

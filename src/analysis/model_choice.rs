//! The beam model a scene gets when it leaves `track.beam.model` out, and the number of modes
//! of a modal beam that leaves `track.beam.modes` out, chosen from the accuracy ε it asks for.
//!
//! 1. Geometric nonlinearity, measured: the exact and the linear static response of the
//!    scene's mesh under the largest load the scene applies (all its loads together, with the
//!    disk's weight, or the most a span's length of a train's axles weighs, standing at each
//!    probe in turn), compared in the deflection across the
//!    undeformed axis, which the accuracy is asked of. Where the two differ at a probe by more
//!    than ε/4 of the largest deflection, what the linear models leave out is visible at the
//!    accuracy asked, and the beam is `exact`; otherwise it is `modal`. (The shortening of
//!    the chord a sagging beam pulls in at a roller is second order in the deflection and
//!    is not a deflection: it does not count.)
//! 2. The modes: as the mesh is chosen (`discretisation.rs`), the static deflection at the
//!    probes under the loads that change during the run is expanded in the modes; the loading
//!    excites up to the last mode that adds more than ε/4 of the peak, K. One refinement
//!    confirms it: modes K+1 … 2K together must add less than ε/4, or K doubles (ε/8 both,
//!    where a load is switched during the run: each mode it excites swings by its whole
//!    static part about it, undamped). On a mesh past 400 nodes the estimate is made on
//!    the finest one within them. The
//!    static correction of the modes left out (`beam/modal.rs`) holds their quasi-static
//!    part, so what the count must carry is the dynamics: where moving forces at speed v are
//!    all that changes, each mode's part counts by how far they set it vibrating about it,
//!    min(1, 2 v κ/ω) ([`ModeShares::count`]). Never fewer modes than lie below the deck
//!    acceleration's cutoff, which the accelerations are made of.

use crate::analysis::discretisation::{weight_drops, MAX_NODES};
use crate::analysis::modes::modes;
use crate::analysis::statics;
use crate::beam::load::{BeamStart, PointLoad};
use crate::beam::supports::statically_supported;
use crate::beam::{response_scale, Beam, BeamModel, BeamSpec};
use crate::linalg::SparseLu;

/// The part of the accuracy each check of the choice may take.
pub const SHARE: f64 = 0.25;

/// The model chosen, and why (one sentence for `check` and the summary).
pub struct Choice {
    pub model: BeamModel,
    pub why: String,
    /// For a modal beam whose count was chosen, what it was chosen from and the reason before
    /// it: a scene whose moving forces' speed changes (a sweep's cases) counts again from them.
    pub recount: Option<Recount>,
    /// Where the loads are more than the beam carries, why the scene is refused.
    pub uncarried: Option<String>,
    /// Where the beam is linear or modal: the static deflection the nonlinearity was measured
    /// at (m) and the exact beam's gap from it, of it.
    pub static_gap: Option<(f64, f64)>,
}

impl Choice {
    /// The model, with nothing to recount or refuse and no static gap kept.
    fn plain(model: BeamModel, why: String) -> Choice {
        Choice {
            model,
            why,
            recount: None,
            uncarried: None,
            static_gap: None,
        }
    }
}

/// What a modal beam's count of modes is chosen from, for any speed of its moving forces.
#[derive(Clone, Debug)]
pub struct Recount {
    pub shares: ModeShares,
    /// Why the beam is modal, which the count's reason follows.
    pub why_modal: String,
    pub accuracy: f64,
}

impl Recount {
    /// The modal beam for moving forces passing at `speed` (`None`: loads that do not move
    /// at a speed), and why.
    pub fn at(&self, speed: Option<f64>) -> (BeamModel, String) {
        let (modes, why) = self.shares.count(self.accuracy, speed);
        (
            BeamModel::Modal { modes },
            format!("{}{why}", self.why_modal),
        )
    }
}

/// Every load as (x, global force, moment).
type Pattern = Vec<(f64, [f64; 2], f64)>;

/// Why the exact beam's static response could not be measured.
enum Unmeasured {
    /// A mechanism, a load it buckles under, or no response at the probes.
    Nothing,
    /// Loads that the linear beam says would deflect it past its own span, under which the
    /// exact beam finds no equilibrium: the sentence that refuses them.
    Uncarried(String),
}

/// The largest linear and exact static response at the probes, and their largest difference,
/// over the load cases.
fn nonlinearity(spec: &BeamSpec, cases: &[Pattern], xs: &[f64]) -> Result<(f64, f64), Unmeasured> {
    // Each probe's deflection across the axis and its rotation as a length.
    let across = |beam: &Beam, q: &[f64]| -> Vec<[f64; 2]> {
        (xs.iter())
            .map(|&x| {
                let d = beam.displacement_at(q, x);
                [
                    beam.to_local([d.u, d.w])[1],
                    d.phi * beam.spec.rotation_as_length(1.0),
                ]
            })
            .collect()
    };
    let exact = Beam::shared(&BeamSpec {
        model: BeamModel::Exact,
        ..spec.clone()
    });
    // The linear beam's own stiffness, which may hold a stiff shear back from the exact one's
    // (`beam::shear_rigid_limit`): its deflection is the one a linear or modal run would have.
    let small = Beam::shared(&BeamSpec {
        model: BeamModel::Linear,
        ..spec.clone()
    });
    let n = exact.dim();
    let lu = SparseLu::factor(&small.tangent(&vec![0.0; n]), None).ok_or(Unmeasured::Nothing)?;
    // The largest deflection and rotation, and their largest changes.
    let (mut size, mut gap) = ([0.0_f64; 2], [0.0_f64; 2]);
    for case in cases {
        let mut f = vec![0.0; n];
        exact.add_weight(&mut f);
        for &(x, force, mz) in case {
            exact.add_point_load(x, force, mz, &mut f);
        }
        let mut linear = f.clone();
        lu.solve_in_place(&mut linear);
        let a = across(&exact, &linear);
        let Ok(solved) = statics::solve(&exact, &f) else {
            let deflections: Vec<f64> = a.iter().map(|l| l[0]).collect();
            return Err(uncarried(spec, case, &deflections, exact.length));
        };
        let b = across(&exact, &solved.q);
        for (l, e) in a.iter().zip(&b) {
            for c in 0..2 {
                size[c] = size[c].max(l[c].abs());
                gap[c] = gap[c].max((l[c] - e[c]).abs());
            }
        }
    }
    let by_rotation = response_scale(size[0], size[1]) != size[0];
    let (size, gap) = if by_rotation {
        (size[1], gap[1])
    } else {
        (size[0], gap[0])
    };
    if size.is_finite() && size > 0.0 {
        Ok((size, gap))
    } else {
        Err(Unmeasured::Nothing)
    }
}

/// Why a load case the exact beam finds no equilibrium under is refused, where the beam is
/// held against moving as a body and the linear beam's deflection `linear` at the probes under
/// it reaches past the span; `Nothing` where it does not (a load it may buckle under, which a
/// run may follow, or a mechanism, whose tangent factors only to round-off).
fn uncarried(spec: &BeamSpec, case: &Pattern, linear: &[f64], span: f64) -> Unmeasured {
    let deepest = linear.iter().fold(0.0_f64, |m, w| m.max(w.abs()));
    let held = statically_supported(spec.supports, spec.bearings.len());
    if !(held && deepest > span) {
        return Unmeasured::Nothing;
    }
    let total: f64 = case.iter().map(|(_, f, _)| f[0].hypot(f[1])).sum();
    Unmeasured::Uncarried(format!(
        "the beam does not carry the scene's loads statically: under {total:.3e} N in all the linear beam would deflect {deepest:.3e} m at the probes, {} times its span, and the exact beam finds no equilibrium: the plan has no response to choose from, and a run follows the beam folding by metres in microsecond steps (a sprung mass 10⁶ times Biggs': 2 million steps, 4 minutes). Lighten the loads or stiffen the beam, or name `track.beam.model` to run it anyway",
        match deepest / span {
            times if times < 1e6 => format!("{times:.0}"),
            times => format!("{times:.1e}"),
        }
    ))
}

/// Each mode's part of the static deflection at the probes under the loads that change during
/// the run, and how far a load passing over the mode's shape makes it vibrate about that part:
/// what the count of modes is chosen from, at any speed of the loads.
#[derive(Clone, Debug)]
pub struct ModeShares {
    /// Per mode, in ascending frequency, the (u, w) it adds at each probe, and its rotation
    /// there times l/π, l the longest span (a first sine mode's rotation so turns into its
    /// deflection).
    parts: Vec<Vec<[f64; 3]>>,
    /// Per mode, κ/ω: the steepest slope of its deflection over its largest deflection, over
    /// its circular frequency. A force entering the span at speed v, where the shape is 0 and
    /// its slope κ times its largest value, sets the mode vibrating about its static part by
    /// v κ/ω of that part, and as much again as it leaves.
    passing: Vec<f64>,
    /// Per mode, its deflection at the ends where no support holds w, over its largest: a
    /// force leaving (or entering) there drops off (or on) at once, and sets the mode
    /// vibrating by that share of its static part whatever the speed (a cantilever's tip).
    stepping: Vec<f64>,
    /// The largest static deflection at a probe, all modes together.
    scale: f64,
    /// How many modes lie at or below the deck acceleration's cutoff: the accelerations are
    /// made of them.
    below_cutoff: usize,
    /// The most modes a modal beam may keep on this mesh.
    limit: usize,
    /// The loads switch on or off during the run (the beam's weight dropping included).
    switched: bool,
    /// Something rides on the beam (a disk, a vehicle's wheels, moving masses): it follows
    /// the kept modes (a vehicle's point wheels get the static correction of those left out
    /// under their static loads alone).
    riding: bool,
}

/// The modes the loading excites on the scene's mesh, or why they cannot be counted.
fn mode_shares(
    spec: &BeamSpec,
    excite: &Pattern,
    weight_drops: bool,
    xs: &[f64],
    switched: bool,
    riding: bool,
    cutoff: Option<f64>,
) -> Result<ModeShares, (usize, String)> {
    // The estimate is dense: as for the mesh's own choice, no mesh past MAX_NODES nodes is
    // analysed; a finer mesh is estimated on the coarsest one within it.
    let elements = if spec.elements * spec.order < MAX_NODES {
        spec.elements
    } else {
        ((MAX_NODES - 1) / spec.order).max(1)
    };
    let beam = Beam::shared(&BeamSpec {
        model: BeamModel::Linear,
        elements,
        ..spec.clone()
    });
    let n = beam.dim();
    let limit = n.min(crate::beam::modal::MAX_MODES);
    let fallback = |why: &str| (limit.min(12), why.to_string());
    let Some(m) = modes(&beam, limit) else {
        return Err(fallback("12 modes (or as many as the mesh has): the natural modes could not be computed for an estimate"));
    };
    let mut f = vec![0.0; n];
    for &(x, force, mz) in excite {
        beam.add_point_load(x, force, mz, &mut f);
    }
    if weight_drops {
        beam.add_weight(&mut f);
    }
    let stations: Vec<f64> = (0..=PASSING_SAMPLES * elements)
        .map(|i| beam.length * i as f64 / (PASSING_SAMPLES * elements) as f64)
        .collect();
    let mut parts = Vec::with_capacity(m.omega.len());
    let mut passing = Vec::with_capacity(m.omega.len());
    let mut stepping = Vec::with_capacity(m.omega.len());
    let mut total = vec![[0.0; 3]; xs.len()];
    let turned = beam.spec.rotation_as_length(1.0);
    for k in 0..m.omega.len() {
        let shape: Vec<f64> = m.shapes.column(k).iter().copied().collect();
        let w2 = m.omega[k] * m.omega[k];
        let part = if w2 > 0.0 {
            let participation: f64 = shape.iter().zip(&f).map(|(a, b)| a * b).sum();
            let statics: Vec<f64> = shape.iter().map(|s| s * participation / w2).collect();
            (xs.iter())
                .map(|&x| {
                    let d = beam.displacement_at(&statics, x);
                    [d.u, d.w, d.phi * turned]
                })
                .collect()
        } else {
            vec![[0.0; 3]; xs.len()]
        };
        for (t, p) in total.iter_mut().zip(&part) {
            for (tc, pc) in t.iter_mut().zip(p) {
                *tc += pc;
            }
        }
        parts.push(part);
        let (kappa, at_free_ends) = steepness_and_free_ends(&beam, &shape, &stations);
        passing.push(kappa / m.omega[k]);
        stepping.push(at_free_ends);
    }
    let scale = response_scale(
        total.iter().fold(0.0_f64, |s, v| s.max(v[0].hypot(v[1]))),
        total.iter().fold(0.0_f64, |s, v| s.max(v[2].abs())),
    );
    if !(scale > 0.0) {
        return Err(fallback("12 modes (or as many as the mesh has): the loads that change during the run do not deflect the probes"));
    }
    let below_cutoff =
        crate::analysis::modes::acceleration_cutoff(&beam, cutoff).map_or(0, |(hz, _)| {
            m.omega
                .iter()
                .take_while(|w| crate::beam::modal::within_cutoff(**w / std::f64::consts::TAU, hz))
                .count()
        });
    Ok(ModeShares {
        parts,
        passing,
        stepping,
        scale,
        below_cutoff,
        limit,
        switched,
        riding,
    })
}

/// Stations an element the steepest slope of a mode's deflection is sought at.
const PASSING_SAMPLES: usize = 16;

/// κ of one mode: the steepest slope of its deflection across the axis between `stations`
/// over its largest deflection (infinite where it does not deflect the axis: an axial mode,
/// which the loads across it do not excite either); and the larger of its deflections at the
/// ends where no support holds w, over its largest (0 where both ends hold w).
fn steepness_and_free_ends(beam: &Beam, shape: &[f64], stations: &[f64]) -> (f64, f64) {
    let across: Vec<f64> = stations
        .iter()
        .map(|&x| {
            let d = beam.displacement_at(shape, x);
            beam.to_local([d.u, d.w])[1]
        })
        .collect();
    let largest = across.iter().fold(0.0_f64, |m, w| m.max(w.abs()));
    let steepest = across
        .windows(2)
        .zip(stations.windows(2))
        .fold(0.0_f64, |m, (w, x)| {
            m.max((w[1] - w[0]).abs() / (x[1] - x[0]))
        });
    if !(largest > 0.0) {
        return (f64::INFINITY, 0.0);
    }
    let ends = [(false, across.first()), (true, across.last())];
    let at_free_ends = (ends.iter())
        .filter(|(end, _)| !beam.holds_w_at(*end))
        .fold(0.0_f64, |m, (_, w)| m.max(w.map_or(0.0, |w| w.abs())));
    (steepest / largest, at_free_ends / largest)
}

impl ModeShares {
    /// What the modes past the first `count` add together, each whole, to the static
    /// deflection at the probes (or to their rotations times the longest span over π, the
    /// larger), of its peak: the share the static correction of the modes left out holds, and
    /// holds for static loads alone.
    pub fn left_out(&self, count: usize) -> f64 {
        let width = self.parts.first().map_or(0, Vec::len);
        let mut rest = vec![[0.0; 3]; width];
        for part in self.parts.iter().skip(count) {
            for (r, d) in rest.iter_mut().zip(part) {
                for (rc, dc) in r.iter_mut().zip(d) {
                    *rc += dc;
                }
            }
        }
        let largest = rest
            .iter()
            .fold(0.0_f64, |m, r| m.max(r[0].hypot(r[1])).max(r[2].abs()));
        largest / self.scale
    }

    /// How many modes the dynamics asks for at `accuracy`, and why. With `passing` (the speed
    /// of moving forces, the only loads that change), each mode's part counts by how far they
    /// set it vibrating about it, 2 v κ/ω (entering and leaving) and its share at an end where
    /// w is free (dropping off there), at most all of it: the static correction of the modes
    /// left out holds the rest. Otherwise a mode counts whole.
    pub fn count(&self, accuracy: f64, passing: Option<f64>) -> (usize, String) {
        let passing = passing.filter(|_| !self.switched);
        let weight = |k: usize| {
            passing.map_or(1.0, |v| {
                (2.0 * v * self.passing[k] + self.stepping[k]).min(1.0)
            })
        };
        // The deflection at the probes after the first k modes, each weighted, for every k.
        let mut after: Vec<Vec<[f64; 3]>> = Vec::with_capacity(self.parts.len());
        let mut partial = vec![[0.0; 3]; self.parts.first().map_or(0, Vec::len)];
        for (k, part) in self.parts.iter().enumerate() {
            for (p, d) in partial.iter_mut().zip(part) {
                for (pc, dc) in p.iter_mut().zip(d) {
                    *pc += weight(k) * dc;
                }
            }
            after.push(partial.clone());
        }
        // The largest change at a probe from the first a modes to the first b, of its
        // deflection (`turned` false) or its rotation times the longest span over π, over the
        // peak deflection.
        let moved = |a: usize, b: usize, turned: bool| -> f64 {
            let none = vec![[0.0; 3]; partial.len()];
            let pa = if a == 0 { &none } else { &after[a - 1] };
            pa.iter().zip(&after[b - 1]).fold(0.0_f64, |m, (x, y)| {
                m.max(if turned {
                    (x[2] - y[2]).abs()
                } else {
                    (x[0] - y[0]).hypot(x[1] - y[1])
                })
            }) / self.scale
        };
        // A load switched on or off sets every mode it excites swinging by up to its whole
        // static part (twice it at the peak), undamped: the share is halved.
        let tol = SHARE * accuracy * if self.switched { 0.5 } else { 1.0 };
        let counted_by = |turned: bool| {
            let single = (1..=after.len())
                .rev()
                .find(|&k| moved(k - 1, k, turned) > tol)
                .unwrap_or(1);
            let mut count = single;
            while 2 * count <= after.len() && moved(count, 2 * count, turned) > tol {
                count *= 2;
            }
            (single, count)
        };
        // The probes' rotations are counted beside their deflections, and the larger count
        // kept: the summary reports both, and a cantilever's tip turns in its higher modes
        // more than it deflects.
        let (by_deflection, by_rotation) = (counted_by(false), counted_by(true));
        let turned = by_rotation.1 > by_deflection.1;
        let (single, count) = if turned { by_rotation } else { by_deflection };
        let confirm = if 2 * count <= after.len() {
            format!(
                "modes {}–{} together add {:.1e}",
                count + 1,
                2 * count,
                moved(count, 2 * count, turned)
            )
        } else {
            format!("the mesh has {} modes", after.len())
        };
        let what = if turned {
            "of the peak static deflection at the probes (in their rotations times the longest span over π)"
        } else {
            "of the peak static deflection at the probes"
        };
        let counted = match passing {
            Some(v) => format!(
                "each adds more than {tol:.1e} {what} in its vibration about its static part, which forces passing at {v} m/s make up to 2 v κ/ω of it (κ its shape's steepest slope over its largest deflection), the static correction holding the rest"
            ),
            None if self.riding => format!(
                "each adds more than {tol:.1e} {what}, whole: what rides on the beam moves with the kept modes, the static correction of those left out reaching only a vehicle's point wheels, under their static loads"
            ),
            None => format!("each adds more than {tol:.1e} {what}"),
        };
        let cutoff = if self.below_cutoff > count.min(self.limit) {
            format!(
                "; {} lie below the deck acceleration's cutoff, which the accelerations are made of",
                self.below_cutoff
            )
        } else {
            String::new()
        };
        let count = count.max(self.below_cutoff).min(self.limit);
        (
            count,
            format!("{count} modes: the loads excite {single} ({counted}); {confirm}{cutoff}"),
        )
    }
}

/// The largest load the scene applies: all its loads together, with what rides on the beam
/// standing at each probe in turn.
fn largest_loads(loads: &[PointLoad], weight: Option<f64>, xs: &[f64]) -> Vec<Pattern> {
    let all: Pattern = loads.iter().map(|l| (l.x, l.force, l.mz)).collect();
    match weight {
        None => vec![all],
        Some(weight) => xs
            .iter()
            .map(|&x| {
                let mut c = all.clone();
                c.push((x, [0.0, -weight], 0.0));
                c
            })
            .collect(),
    }
}

/// How far the beam's static response under the largest load the scene applies is from
/// linear: the largest difference of the linear and the exact deflection at the probes, over
/// the largest deflection; `None` where the exact beam cannot be solved statically.
pub fn nonlinearity_of(
    spec: &BeamSpec,
    loads: &[PointLoad],
    weight: Option<f64>,
    xs: &[f64],
) -> Option<f64> {
    nonlinearity(spec, &largest_loads(loads, weight, xs), xs)
        .ok()
        .map(|(size, gap)| gap / size)
}

/// Whether a nonlinearity measured by [`nonlinearity_of`] is invisible at the accuracy asked.
pub fn linear_enough(nonlinearity: f64, accuracy: f64) -> bool {
    nonlinearity <= SHARE * accuracy
}

/// Everything the choice of a beam model weighs: a planner keeps each choice under these
/// inputs' text, so that a sweep's cases that differ in any of them choose again.
#[derive(Debug)]
pub struct ModelInputs<'a> {
    pub spec: &'a BeamSpec,
    /// The model the scene names, if it names one (a modal beam with `modes: 0` has its count
    /// chosen).
    pub given: Option<BeamModel>,
    pub loads: &'a [PointLoad],
    /// The largest weight one rider or axle puts on the beam, stood at each probe in turn: the
    /// load the modes' shares are counted under.
    pub weight: Option<f64>,
    /// The most what rides on the beam puts on it at once (a train's axles a span's length
    /// apart together), stood at each probe in turn: the load the nonlinearity is measured
    /// under, which grows with the load where the modes' shares do not.
    pub at_once: Option<f64>,
    /// Whether a rider follows the kept modes (a disk that is not a moving force, a vehicle's
    /// wheels, moving masses): the static correction of those left out reaches only a
    /// vehicle's point wheels, under their static loads.
    pub followers: bool,
    /// The probes' places, where the deflections are weighed.
    pub xs: &'a [f64],
    pub accuracy: f64,
    pub start: BeamStart,
    /// A disk has the thesis coupling, whose equations are written for the exact beam.
    pub thesis_coupling: bool,
    /// The deck acceleration's cutoff the scene gives (Hz).
    pub cutoff: Option<f64>,
}

/// Choose what the scene left out of its beam model.
pub fn choose(inputs: &ModelInputs) -> Choice {
    let &ModelInputs {
        spec,
        given,
        loads,
        weight,
        at_once,
        followers,
        xs,
        accuracy,
        start,
        thesis_coupling,
        cutoff,
    } = inputs;
    let cases = largest_loads(loads, at_once, xs);
    let switching: Vec<&PointLoad> = loads
        .iter()
        .filter(|l| !(start == BeamStart::Static && l.active(0.0) && l.until == f64::INFINITY))
        .collect();
    let drops = weight_drops(spec, start);
    let switched = !switching.is_empty() || drops;
    let mut excite: Pattern = switching.iter().map(|l| (l.x, l.force, l.mz)).collect();
    if let Some(weight) = weight {
        excite.extend(xs.iter().map(|&x| (x, [0.0, -weight], 0.0)));
    }
    let modal =
        |why: String| match mode_shares(spec, &excite, drops, xs, switched, followers, cutoff) {
            Ok(shares) => {
                let recount = Recount {
                    shares,
                    why_modal: why,
                    accuracy,
                };
                let (model, why) = recount.at(None);
                Choice {
                    model,
                    why,
                    recount: Some(recount),
                    uncarried: None,
                    static_gap: None,
                }
            }
            Err((modes, count_why)) => {
                Choice::plain(BeamModel::Modal { modes }, format!("{why}{count_why}"))
            }
        };
    if given == Some(BeamModel::Modal { modes: 0 }) {
        return modal(String::new());
    }
    if thesis_coupling {
        return Choice::plain(BeamModel::Exact, "exact: the thesis coupling is the thesis' equations, which are written for the exact beam".into());
    }
    let tol = SHARE * accuracy;
    match nonlinearity(spec, &cases, xs) {
        Err(Unmeasured::Nothing) => Choice::plain(BeamModel::Exact, "exact: the beam has no static response to measure its nonlinearity by (the supports leave a mechanism, or it does not carry the load statically)".into()),
        Err(Unmeasured::Uncarried(why)) => Choice {
            uncarried: Some(why.clone()),
            ..Choice::plain(BeamModel::Exact, format!("exact: {why}"))
        },
        Ok((size, gap)) if !linear_enough(gap / size, accuracy) => Choice::plain(
            BeamModel::Exact,
            format!(
                "exact: under the largest load the scene applies the linear beam's static deflection at the probes is off the exact one by {:.1e} of it, more than {tol:.1e}",
                gap / size
            ),
        ),
        Ok((size, gap)) => {
            // What a run foresees of its growth is measured from one rider's or axle's static
            // deflection (`BeamRun::nonlinear_gap_foreseen`), the response a train builds up
            // from.
            let one = if at_once == weight {
                Ok((size, gap))
            } else {
                nonlinearity(spec, &largest_loads(loads, weight, xs), xs)
            };
            Choice {
                static_gap: one.ok().map(|(s, g)| (s, g / s)),
                ..modal(format!(
                    "modal: under the largest load the scene applies the linear and the exact static deflections at the probes differ by {:.1e} of them (within {tol:.1e}); ",
                    gap / size
                ))
            }
        }
    }
}

//! The mesh and tolerance a beam scene gets when it leaves them out, chosen from the accuracy
//! it asks for (`solver.accuracy`, relative, of the peak deflection; default 1e-3).
//!
//! A priori: the loads excite the modes their static deflection is made of. On an estimation
//! mesh the static deflection at the probes under every load of the scene that changes during
//! the run (all of them from rest; from a static start, not those carried throughout) and the
//! disk's weight at each probe is expanded in the natural modes, u = Σ φ_k φ_kᵀ f / ω_k², and the
//! loading is taken to excite modes up to the last one that adds more than ε/4 of the peak to
//! it (the tail as a whole converges slowly under a point load, through the shear kink the
//! elements hold exactly at their nodes, so it is the single modes that count). A mesh of
//! degree-4 elements is started with one element per two of those modes' half-waves, and
//! confirmed by one refinement: it is kept once mode K's frequency and the static deflection
//! at the probes change by less than ε/4 when the element count doubles, and doubled
//! otherwise. Loads moving along the span read the modes' shapes everywhere along it, not at
//! the nodes or the probes alone, and turn with their slopes, which the elements' shapes
//! carry with a jump at every node; shapes between the nodes converge far more slowly than
//! the frequencies (as h⁵ against h⁸ at degree 4), slopes more slowly still: the mesh is kept
//! only once the shapes of the modes the loads read (below the acceleration's cutoff; under
//! vehicles every excited mode too) and the slopes of those below the cutoff (of every excited
//! mode on an exact beam that responds off linear, which the plan meshes again once it has
//! chosen the model) also move by less than ε/4. A load switched during the run leaves every
//! mode ringing with its static share, and the probes report rotations beside deflections: the
//! modes are counted, and the static response checked, in the rotations at the probes too.
//! The tolerances the integrator is asked for are the plan's (`plan/tolerances.rs`), from the
//! same accuracy and from the response's size ([`response_size`]).

use serde::Serialize;

use crate::analysis::modes::{acceleration_cutoff, modes, projected, ModeKind};
use crate::beam::load::{BeamStart, PointLoad};
use crate::beam::modal::within_cutoff;
use crate::beam::supports::statically_supported;
use crate::beam::{response_scale, Beam, BeamSpec};
use crate::linalg::{Sparse, SparseLu};

/// The accuracy a beam scene asks for when it does not say.
pub const DEFAULT_ACCURACY: f64 = 1e-3;
/// Degree of the Lagrange elements when the scene does not say: at degree 4 the frequencies
/// converge as h⁸, so few elements hold many modes.
pub const DEFAULT_ORDER: usize = 4;
/// Elements when no estimate can be made (a beam free at both ends has no static deflection).
const FALLBACK_ELEMENTS: usize = 10;
/// Elements of the mesh the modal estimate is made on.
const ESTIMATION_ELEMENTS: usize = 16;
/// The confirming refinement stops doubling past this many nodes (the modal check is dense).
pub(crate) const MAX_NODES: usize = 400;

/// Points per element of the coarser mesh at which [`shapes_move`] compares two meshes' mode
/// shapes: eight per element of the finer, enough to see a shape's error between its nodes.
const SHAPE_POINTS_PER_ELEMENT: usize = 16;

/// Whether a load is switched on or off during the run (rather than carried throughout from a
/// static start): it then excites the modes.
fn excites(l: &PointLoad, start: BeamStart) -> bool {
    !(start == BeamStart::Static && l.active(0.0) && l.until == f64::INFINITY)
}

/// Whether any load is switched on or off during the run.
pub fn jumps(loads: &[PointLoad], start: BeamStart) -> bool {
    loads.iter().any(|l| excites(l, start))
}

/// Whether the beam's own weight, where the scene puts it on, comes on at t = 0 (a beam that
/// starts undeformed drops under it) rather than being carried from a static start.
pub fn weight_drops(spec: &BeamSpec, start: BeamStart) -> bool {
    spec.self_weight.is_some() && start != BeamStart::Static
}

/// The size of the displacements a beam scene's loads cause: the largest static |(u, w)| at a
/// probe (or its rotation, where the loads only turn the probes: [`response_scale`]), under
/// the scene's loads together or one at a time, or under the disk's weight standing on that
/// probe, each with the beam's own weight where the scene puts it on; `None` when the supports
/// leave a rigid-body motion; and whether it is that rotation. An automatic
/// atol is rtol times this, so that a step's error is measured against the response and not
/// against the current displacement, which a vibration takes through zero twice a period
/// (where rtol |q| alone asks for steps of round-off size and spends most of a run there).
pub fn response_size(
    spec: &BeamSpec,
    loads: &[PointLoad],
    weight: Option<f64>,
    probes: &[f64],
) -> Option<(f64, bool)> {
    let beam = Beam::shared(spec);
    let n = beam.dim();
    let lu = SparseLu::factor(&beam.tangent(&vec![0.0; n]), None)?;
    let mut cases: Vec<Vec<[f64; 4]>> = loads
        .iter()
        .map(|l| vec![[l.x, l.force[0], l.force[1], l.mz]])
        .collect();
    if loads.len() > 1 {
        cases.push(cases.concat());
    }
    if let Some(weight) = weight {
        cases.extend(probes.iter().map(|&x| vec![[x, 0.0, -weight, 0.0]]));
    }
    if cases.is_empty() {
        cases.push(Vec::new());
    }
    let (mut size, mut turned) = (0.0_f64, 0.0_f64);
    for case in cases {
        let mut q = vec![0.0; n];
        beam.add_weight(&mut q);
        for l in &case {
            beam.add_point_load(l[0], [l[1], l[2]], l[3], &mut q);
        }
        lu.solve_in_place(&mut q);
        for &x in probes {
            let d = beam.displacement_at(&q, x);
            let (r, t) = (d.u.hypot(d.w), spec.rotation_as_length(d.phi));
            if !(r.is_finite() && t.is_finite()) {
                return None;
            }
            size = size.max(r);
            turned = turned.max(t);
        }
    }
    let scale = response_scale(size, turned);
    let (size, by_rotation) = (scale, scale != size);
    // A near-singular stiffness (a mechanism) passes the factorisation with a displacement
    // no beam under its loads has: larger than the beam itself.
    let length = (spec.to[0] - spec.from[0]).hypot(spec.to[1] - spec.from[1]);
    (size > 0.0 && size < length).then_some((size, by_rotation))
}

/// The share of the static response a beam keeps after loads that are on it for only
/// `crossing` seconds: a crossing far shorter than the first mode's period is an impulse,
/// F ∫φ dt = F T 2/π on a half-sine mode, which leaves an amplitude F T (2/π)/(M ω₁), the
/// static F/(M ω₁²) times (2/π) ω₁ T, ω₁ the beam's [`lowest_omega`]. At most 1.
pub fn passage_share(lowest_omega: f64, crossing: f64) -> f64 {
    (2.0 / std::f64::consts::PI * lowest_omega * crossing).min(1.0)
}

/// The beam's lowest circular frequency (rad/s); `None` where its first mode is not found.
pub fn lowest_omega(spec: &BeamSpec) -> Option<f64> {
    let beam = Beam::shared(spec);
    modes(&beam, 1)?.omega.first().copied().filter(|&w| w > 0.0)
}

/// What was chosen, and why, for the summary.
#[derive(Clone, Debug, Serialize)]
pub struct Discretisation {
    pub accuracy: f64,
    pub elements: usize,
    pub order: usize,
    pub excited_modes: usize,
    pub why: String,
    /// Where the refinement stopped at [`MAX_NODES`] before the last two meshes agreed: what
    /// they differ by, a warning's sentence.
    #[serde(skip)]
    pub unconfirmed: Option<String>,
}

/// Linear static deflection and the modes of `spec` meshed into `elements`: the probes'
/// displacement magnitudes |(u, w)| statically, and after the first k modes for every k; the
/// same of their rotations where a load is switched; the circular frequencies.
#[derive(Clone)]
struct Estimate {
    static_at_probes: Vec<f64>,
    /// The probes' static rotations |φ|, and the largest as a length
    /// ([`BeamSpec::rotation_as_length`]).
    rotation_at_probes: Vec<f64>,
    turned: f64,
    omega: Vec<f64>,
    truncated: Vec<Vec<f64>>,
    /// The rotations after the first k modes for every k, where a load is switched. A load
    /// switched on an undamped beam leaves every mode ringing with its static share, and a
    /// mode's share of a rotation falls more slowly with its order than its share of a
    /// deflection. Counted by the deflections alone, C1's 12 elements read the rotation rows
    /// 1.5·10⁻³ of their largest off 64 elements' (the 16 counted by the rotations too:
    /// 8.9·10⁻⁴), and B1's 12 elements 3.2·10⁻³ off a run asked for a tenth of the accuracy
    /// (its 24: 8.0·10⁻⁴).
    truncated_rotations: Option<Vec<Vec<f64>>>,
}

/// `loads` make the static deflection; those flagged `true` change during the run and so
/// excite the modes (a load carried from a static start excites none). The beam's own weight,
/// where the scene puts it on, makes it too, and excites the modes where `weight_drops`.
fn estimate(
    spec: &BeamSpec,
    elements: usize,
    loads: &[([f64; 4], bool)],
    weight_drops: bool,
    probes: &[f64],
    rotations: bool,
) -> Option<Estimate> {
    let beam = Beam::shared(&BeamSpec {
        elements,
        ..spec.clone()
    });
    let n = beam.dim();
    let mut all = vec![0.0; n];
    let mut f = vec![0.0; n];
    for (l, excites) in loads {
        beam.add_point_load(l[0], [l[1], l[2]], l[3], &mut all);
        if *excites {
            beam.add_point_load(l[0], [l[1], l[2]], l[3], &mut f);
        }
    }
    beam.add_weight(&mut all);
    if weight_drops {
        beam.add_weight(&mut f);
    }
    // Each mode's share of the static deflection at a probe needs only the projections of
    // the loads and of the probe's u and w rows on its shape (and of its φ row after them).
    let mut vectors = vec![f];
    for &x in probes {
        for direction in [[1.0, 0.0], [0.0, 1.0]] {
            let mut row = vec![0.0; n];
            beam.add_point_load(x, direction, 0.0, &mut row);
            vectors.push(row);
        }
    }
    let first_rotation = vectors.len();
    if rotations {
        for &x in probes {
            let mut row = vec![0.0; n];
            beam.add_point_load(x, [0.0, 0.0], 1.0, &mut row);
            vectors.push(row);
        }
    }
    let k = beam.tangent(&vec![0.0; n]);
    let (omega, shares) = modal_shares(&beam, &k, &vectors)?;
    // A rigid-body motion leaves no static deflection, whatever a factorisation of the
    // near-singular stiffness returns. The supports say whether there is one: next to the
    // highest mode the lowest can look like one where shear and stretch are far stiffer than
    // bending (Biggs' bridge, made Euler–Bernoulli by a shear stiffness of 10¹⁵ N, spans ω
    // by 1:10⁷ on 76 elements).
    let supported = statically_supported(spec.supports, spec.bearings.len());
    if !supported || !omega.first().is_some_and(|&w| w > 0.0) {
        return None;
    }
    let mut q = all;
    SparseLu::factor(&k, None)?.solve_in_place(&mut q);
    // `partial` holds the load's entry first, then each probe's u and w, then the rotations.
    let at_probes = |partial: &[f64]| -> Vec<f64> {
        partial[1..first_rotation]
            .chunks_exact(2)
            .map(|u_w| u_w[0].hypot(u_w[1]))
            .collect()
    };
    let mut partial = vec![0.0; vectors.len()];
    let mut truncated = Vec::with_capacity(omega.len());
    let mut truncated_rotations = Vec::new();
    for k in 0..omega.len() {
        let w2 = omega[k] * omega[k];
        if w2 > 0.0 {
            for (p, share) in partial.iter_mut().zip(&shares).skip(1) {
                *p += share[k] * shares[0][k] / w2;
            }
        }
        truncated.push(at_probes(&partial));
        if rotations {
            truncated_rotations.push(partial[first_rotation..].iter().map(|r| r.abs()).collect());
        }
    }
    let displaced = probes.iter().map(|&x| beam.displacement_at(&q, x));
    let rotation_at_probes: Vec<f64> = displaced.clone().map(|d| d.phi.abs()).collect();
    Some(Estimate {
        static_at_probes: displaced.map(|d| d.u.hypot(d.w)).collect(),
        turned: spec.rotation_as_length(largest(&rotation_at_probes)),
        rotation_at_probes,
        omega,
        truncated,
        truncated_rotations: rotations.then_some(truncated_rotations),
    })
}

/// Every mode's circular frequency and the projection of each of `vectors` on its shape
/// (row per vector, column per mode): from the projected eigenproblem, or where that fails
/// from the modes themselves.
fn modal_shares(
    beam: &Beam,
    k: &Sparse,
    vectors: &[Vec<f64>],
) -> Option<(Vec<f64>, Vec<Vec<f64>>)> {
    if let Some((lambda, p)) = projected(k, beam.mass(), vectors) {
        return Some((lambda.iter().map(|l| l.sqrt()).collect(), p));
    }
    let m = modes(beam, beam.dim())?;
    let p = vectors
        .iter()
        .map(|v| {
            (0..m.omega.len())
                .map(|k| m.shapes.column(k).iter().zip(v).map(|(a, b)| a * b).sum())
                .collect()
        })
        .collect();
    Some((m.omega, p))
}

/// How far the shapes of the bending modes among the lowest `count` move from `elements` to
/// twice as many, each as its largest displacement against the finer mesh's, read along the
/// whole span; and the slopes of those among the lowest `sloped`, each as its largest
/// slope against the finer mesh's steepest (see [`ShapesMoved::slopes`]). A wheel riding the
/// beam samples the shapes everywhere: a 10 t body on an 8 Hz suspension over a 20 m concrete
/// span, at 6 to 40 m/s on 8, 12, 16 and 24 elements, read its largest acceleration up to
/// 5.4·10⁻³, 1.5·10⁻³, 2.4·10⁻⁴ and 1.7·10⁻⁵ off, where the eighth mode's shape (the last the
/// loads excite) moves by 4·10⁻³, 5·10⁻⁴, 10⁻⁴ and 2·10⁻⁵, and its frequency by 1.4·10⁻⁴
/// already on 8. `None` where either mesh's modes are not found.
fn shapes_move(
    spec: &BeamSpec,
    elements: usize,
    (count, sloped): (usize, usize),
) -> Option<ShapesMoved> {
    let length = (spec.to[0] - spec.from[0]).hypot(spec.to[1] - spec.from[1]);
    let samples = SHAPE_POINTS_PER_ELEMENT * elements;
    let points: Vec<f64> = (0..=samples)
        .map(|i| length * i as f64 / samples as f64)
        .collect();
    let shapes = |elements: usize| -> Option<Vec<(usize, Vec<[f64; 2]>)>> {
        let beam = Beam::shared(&BeamSpec {
            elements,
            ..spec.clone()
        });
        let m = modes(&beam, count)?;
        let kinds = m.kinds(&beam);
        let bending = (0..m.omega.len()).filter(|&k| kinds[k] == ModeKind::Bending);
        Some(
            bending
                .map(|k| {
                    let q: Vec<f64> = m.shapes.column(k).iter().copied().collect();
                    let along = (points.iter())
                        .map(|&x| {
                            let d = beam.displacement_at(&q, x);
                            [d.u, d.w]
                        })
                        .collect();
                    (k, along)
                })
                .collect(),
        )
    };
    let (coarse, fine) = (shapes(elements)?, shapes(2 * elements)?);
    let spacing = length / samples as f64;
    let slopes = |d: &[[f64; 2]]| -> Vec<[f64; 2]> {
        (d.windows(2))
            .map(|p| [(p[1][0] - p[0][0]) / spacing, (p[1][1] - p[0][1]) / spacing])
            .collect()
    };
    let mut moved = ShapesMoved::default();
    for ((k, c), (_, f)) in coarse.iter().zip(&fine) {
        let along: f64 = c
            .iter()
            .zip(f)
            .map(|(a, b)| a[0] * b[0] + a[1] * b[1])
            .sum();
        let sign = if along < 0.0 { -1.0 } else { 1.0 };
        let c: Vec<[f64; 2]> = c.iter().map(|a| [sign * a[0], sign * a[1]]).collect();
        moved.shapes = moved.shapes.max(largest_apart(&c, f));
        if *k < sloped {
            moved.slopes = moved.slopes.max(largest_apart(&slopes(&c), &slopes(f)));
        }
    }
    Some(moved)
}

/// How far two meshes' modes lie apart as [`shapes_move`] measures them.
#[derive(Clone, Copy, Debug, Default)]
struct ShapesMoved {
    /// The largest displacement apart, of each mode's largest.
    shapes: f64,
    /// The largest slope apart (the secants over pieces a sixteenth of the coarser mesh's
    /// element long, which no node of either mesh splits), of each mode's steepest. A mode's quasi-static part under a force P moving at
    /// v, P φ(vt)/ω², turns with the slope φ' under it, and where the slope turns sharply the
    /// mode cannot follow and vibrates on with an acceleration of P v Δφ'/ω. The elements'
    /// slopes jump at every node, kicks the beam itself has not, which a slow load over a
    /// stiff deck reads as much as the deck's own small accelerations: eight forces at 10 to
    /// 40 m/s over a 30 m clamped-roller HEB 360 beam read its largest accelerations 8·10⁻⁴ to
    /// 9.5·10⁻⁴ off on the 10 elements the shapes and frequencies chose (the fourth mode's
    /// slopes 8.4·10⁻⁴ apart from 20's, its shape 9.5·10⁻⁵).
    slopes: f64,
}

impl ShapesMoved {
    fn worst(&self) -> f64 {
        self.shapes.max(self.slopes)
    }
}

/// The largest distance between the points of `coarse` and `fine`, of the largest of `fine`'s;
/// 0 where `fine` is all zero.
fn largest_apart(coarse: &[[f64; 2]], fine: &[[f64; 2]]) -> f64 {
    let top = fine.iter().fold(0.0_f64, |m, b| m.max(b[0].hypot(b[1])));
    let apart = (coarse.iter().zip(fine))
        .fold(0.0_f64, |m, (a, b)| m.max((a[0] - b[0]).hypot(a[1] - b[1])));
    if top > 0.0 {
        apart / top
    } else {
        0.0
    }
}

/// Loads that move along the span (a disk, a train's axles, a vehicle's wheels): each reads
/// every mode's shape wherever it stands, and the deck's accelerations read the modes up to
/// their cutoff, `cutoff_hz` as the scene gives it (EN 1991-2's otherwise). A vehicle's
/// wheels hand the deck's motion under them to its bodies: they read every mode the loads
/// excite.
#[derive(Clone, Copy, Debug)]
pub struct MovingLoads {
    pub vehicles: bool,
    pub cutoff_hz: Option<f64>,
    /// The exact beam bends visibly from linear under the loads: the slopes of every mode they
    /// excite count, not only those below the cutoff. Each node a load crosses kicks the modes
    /// above the cutoff too, which the accelerations leave out by projecting on the unloaded
    /// beam's modes; bent, the beam rings in its own modes, which that projection no longer
    /// separates, and the kicks' ringing leaks into the accelerations, shrinking with the
    /// slopes' jumps as h². A 40 t moving force at 40 m/s over a 15 m HEB-like steel beam of
    /// 1.1 t, sagging 12 % of its span: the quarter point's largest acceleration 356.56,
    /// 355.42, 355.15, 355.06 m/s² on 16 (the shapes' and slopes' below the cutoff), 32 (every
    /// excited mode's slopes), 64 and 128 elements; at a hundredth of the load, 16 within
    /// 4·10⁻⁵ of 64.
    pub bent: bool,
}

/// Choose what the scene left out (`elements` and/or `order` are `None`), for the loads, the
/// disk's weight standing at each of the probes `xs`, and the accuracy; where loads are
/// `moving` along the span, also for the shapes they read ([`shapes_move`]). Every
/// element count tried is a multiple of `multiple`, which puts a node at each intermediate
/// bearing.
#[allow(clippy::too_many_arguments)]
pub fn choose(
    spec: &BeamSpec,
    elements: Option<usize>,
    order: Option<usize>,
    loads: &[PointLoad],
    weight: Option<f64>,
    xs: &[f64],
    accuracy: f64,
    multiple: usize,
    start: BeamStart,
    moving: Option<MovingLoads>,
) -> Discretisation {
    let order = order.unwrap_or(DEFAULT_ORDER);
    let admissible = |n: usize| n.div_ceil(multiple) * multiple;
    let chosen = |elements: usize, excited_modes: usize, why: String| Discretisation {
        accuracy,
        elements,
        order,
        excited_modes,
        why,
        unconfirmed: None,
    };
    let fallback = |why: &str| {
        let n = elements.unwrap_or(admissible(FALLBACK_ELEMENTS));
        chosen(n, 0, format!("elements {n} of degree {order}: {why}"))
    };
    let spec = BeamSpec {
        order,
        ..spec.clone()
    };
    let pattern = load_pattern(loads, weight, xs, start);
    // The modal estimate is dense: no mesh past MAX_NODES is ever analysed, however many
    // bearings or modes ask for one.
    let nodes = |elements: usize| elements * order + 1;
    let estimation_elements = admissible(ESTIMATION_ELEMENTS);
    if nodes(estimation_elements) > MAX_NODES {
        let n = elements.unwrap_or(multiple);
        return chosen(n, 0, format!(
            "elements {n} of degree {order}: a node at every bearing leaves a mesh too large for the modal estimate (more than {MAX_NODES} nodes), so one element per span"
        ));
    }
    let drops = weight_drops(&spec, start);
    let switched = drops || jumps(loads, start);
    let Some(est) = estimate(&spec, estimation_elements, &pattern, drops, xs, switched) else {
        return fallback(NO_STATIC);
    };
    let tol = accuracy / 4.0;
    let Some((excited, scale)) = excited_modes(&est, tol) else {
        return fallback("the loads do not deflect the probes (default mesh)");
    };
    if let Some(n) = elements {
        return chosen(
            n,
            excited,
            format!("elements {n} as the scene gives, of degree {order}"),
        );
    }
    // The estimation mesh is often one of those the refinement visits.
    let on = |elements: usize| {
        if elements == estimation_elements {
            Some(est.clone())
        } else {
            estimate(&spec, elements, &pattern, drops, xs, switched)
        }
    };
    let largest = (MAX_NODES - 1) / order / 2 / multiple * multiple;
    let first = admissible(excited.div_ceil(2).max(2)).min(largest.max(multiple));
    let (read, sloped) = moving.map_or((0, 0), |m| {
        shapes_read(&spec, estimation_elements, &est, excited, m)
    });
    let shapes = |n: usize| {
        if read > 0 {
            shapes_move(&spec, n, (read, sloped))
        } else {
            Some(ShapesMoved::default())
        }
    };
    let static_tol = [tol * scale[0], tol * scale[1]];
    match refine(on, (shapes, (read, sloped)), first, excited, (tol, static_tol), nodes) {
        Some(Refined { elements: n, reason, unconfirmed }) => Discretisation {
            unconfirmed,
            ..chosen(n, excited, format!(
                "elements {n} of degree {order}: the loads excite {excited} modes (each adds more than {tol:.1e} of the peak static {} at the probes); {reason}",
                if scale[1] > 0.0 { "deflection or rotation" } else { "deflection" }
            ))
        },
        None => fallback(NO_STATIC),
    }
}

/// How many of the lowest modes moving loads read the shapes of: every mode up to the deck
/// acceleration's cutoff, and under vehicles every mode the loads excite too. A 500 kg force
/// at 60 m/s over a 30 m HEB 360 cantilever read the tip's largest acceleration 3.4·10⁻³ off on
/// the 4 elements the frequencies alone chose, and within 1.4·10⁻⁵ once the shapes of the five
/// modes below the 30 Hz cutoff settled (16 elements). A moving force reads a mode's shape
/// error in proportion to what the mode adds to a headline, which above the cutoff is its
/// small share of the deflection: HSLM's 810 trains over the 15 m bridge on 10 elements (the
/// shapes of its nine excited modes settled on 20) lie within 4·10⁻⁶ of each headline's scale
/// of the run on 20, where the steps, which end at every node an axle crosses, double.
fn shapes_read(
    spec: &BeamSpec,
    elements: usize,
    est: &Estimate,
    excited: usize,
    moving: MovingLoads,
) -> (usize, usize) {
    let beam = Beam::shared(&BeamSpec {
        elements,
        ..spec.clone()
    });
    let below = acceleration_cutoff(&beam, moving.cutoff_hz).map_or(0, |(cutoff, _)| {
        (est.omega.iter())
            .filter(|&&w| within_cutoff(w / std::f64::consts::TAU, cutoff))
            .count()
    });
    if moving.bent {
        (excited.max(below), excited.max(below))
    } else if moving.vehicles {
        (excited.max(below), below)
    } else {
        (below, below)
    }
}

/// What of the static response at the probes the mesh is checked on.
fn statics_read(rotations: bool) -> &'static str {
    if rotations {
        "deflection and rotation"
    } else {
        "deflection"
    }
}

const NO_STATIC: &str = "the supports leave a rigid-body motion, so no static deflection to estimate from (default mesh)";

/// The loads as [`estimate`] takes them, each flagged where it excites the modes; the weight
/// riding on the beam stands at each probe.
fn load_pattern(
    loads: &[PointLoad],
    weight: Option<f64>,
    xs: &[f64],
    start: BeamStart,
) -> Vec<([f64; 4], bool)> {
    let mut pattern: Vec<([f64; 4], bool)> = loads
        .iter()
        .map(|l| ([l.x, l.force[0], l.force[1], l.mz], excites(l, start)))
        .collect();
    if let Some(weight) = weight {
        pattern.extend(xs.iter().map(|&x| ([x, 0.0, -weight, 0.0], true)));
    }
    pattern
}

/// Whether each of a and b's entries are within `tol` of the other's.
fn within(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

/// How many modes the loads excite (the last whose share of the static deflection at a probe,
/// or of its rotation where the estimate holds them, passes `tol` of the largest), and the
/// largest deflection and rotation (0 where the rotations, times the span over π, are within
/// `tol` of the deflection: nothing to hold them to); `None` where the loads do not deflect
/// the probes.
fn excited_modes(est: &Estimate, tol: f64) -> Option<(usize, [f64; 2])> {
    let scale = response_scale(largest(&est.static_at_probes), est.turned);
    if !(scale > 0.0) {
        return None;
    }
    let last_adding = |truncated: &[Vec<f64>], scale: f64| {
        let none = vec![0.0; truncated.first().map_or(0, Vec::len)];
        (0..truncated.len())
            .rev()
            .find(|&k| {
                let before = if k == 0 { &none } else { &truncated[k - 1] };
                !within(&truncated[k], before, tol * scale)
            })
            .map_or(1, |k| k + 1)
    };
    let deflected = last_adding(&est.truncated, scale);
    let Some(truncated_rotations) = &est.truncated_rotations else {
        return Some((deflected, [scale, 0.0]));
    };
    if est.turned <= tol * scale {
        return Some((deflected, [scale, 0.0]));
    }
    let turned = largest(&est.rotation_at_probes);
    Some((
        deflected.max(last_adding(truncated_rotations, turned)),
        [scale, turned],
    ))
}

/// The largest of `v`'s entries, 0 for none.
fn largest(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(*x))
}

/// The mesh [`refine`] settled on, and whether the last two meshes it compared agreed.
struct Refined {
    elements: usize,
    reason: String,
    unconfirmed: Option<String>,
}

/// Double the mesh from `n` elements until the highest excited mode's frequency moves by
/// less than `tol` relative, the probes' static deflection and rotation (where the estimates
/// hold them) by less than `limits` and the shapes of the lowest `read` modes (`shapes`, 0 where no load moves) by less than `tol`, or
/// a further doubling would pass [`MAX_NODES`]; there the finer of the last two meshes is kept,
/// which the coarser did not match. `None` where a mesh has no static deflection.
///
/// Kept at the coarser, a 30 m pinned steel beam 4.7 cm deep under five 40 t axles at 5 m/s
/// (its exact static deflection twice the linear one) read midspan's largest acceleration
/// 9.2·10⁻⁴ of the envelope's off 128 elements on 32; on the finer 64, 6.8·10⁻⁵.
fn refine(
    on: impl Fn(usize) -> Option<Estimate>,
    (shapes, (read, sloped)): (impl Fn(usize) -> Option<ShapesMoved>, (usize, usize)),
    mut n: usize,
    excited: usize,
    (tol, limits): (f64, [f64; 2]),
    nodes: impl Fn(usize) -> usize,
) -> Option<Refined> {
    let mut coarse = on(n)?;
    loop {
        let Some(fine) = on(2 * n) else {
            let failed = format!(
                "the modes of {} elements could not be computed, so the mesh of {n} is not confirmed within the accuracy",
                2 * n
            );
            return Some(Refined {
                elements: n,
                reason: format!("{failed}: it is kept, the finest analysed"),
                unconfirmed: Some(format!(
                    "{failed}; a run with `track.beam.elements` doubled shows what a scene's numbers move by"
                )),
            });
        };
        let k = excited.min(coarse.omega.len()) - 1;
        let df = (coarse.omega[k] - fine.omega[k]).abs() / fine.omega[k];
        let largest_change = |a: &[f64], b: &[f64]| {
            a.iter()
                .zip(b)
                .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()))
        };
        let dw = largest_change(&coarse.static_at_probes, &fine.static_at_probes);
        let dphi = match (&coarse.truncated_rotations, &fine.truncated_rotations) {
            (Some(_), Some(_)) => {
                largest_change(&coarse.rotation_at_probes, &fine.rotation_at_probes)
            }
            _ => 0.0,
        };
        // A rotation the check does not hold (`limits[1]` 0) moves the mesh nowhere.
        let settled = df <= tol && dw <= limits[0] && (limits[1] == 0.0 || dphi <= limits[1]);
        // Where a mesh's modes are not found the shapes cannot be compared: the frequencies
        // and the static deflection decide, as without wheels.
        let moved = if settled {
            shapes(n).unwrap_or_default()
        } else {
            ShapesMoved::default()
        };
        let along = if moved.worst() > 0.0 {
            format!(
                ", the shapes of modes 1–{read} along the span, which the loads read, by {:.1e}, the slopes of modes 1–{sloped} by {:.1e}",
                moved.shapes, moved.slopes
            )
        } else {
            String::new()
        };
        let f_hz = fine.omega[k] / std::f64::consts::TAU;
        let statics = statics_read(limits[1] > 0.0);
        if settled && moved.worst() <= tol {
            return Some(Refined {
                elements: n,
                reason: format!(
                    "on {} elements mode {} ({f_hz:.4} Hz) moves by {df:.1e} and the static {statics} at the probes by less than {tol:.1e}{along}",
                    2 * n,
                    k + 1,
                ),
                unconfirmed: None,
            });
        }
        if nodes(4 * n) > MAX_NODES {
            let apart = format!(
                "from {n} to {} elements mode {} ({f_hz:.4} Hz) moves by {df:.1e}, the static {statics} at the probes by {:.1e} of the largest{along}, more than {tol:.1e}",
                2 * n,
                k + 1,
                if limits[1] > 0.0 {
                    (dw / limits[0]).max(dphi / limits[1]) * tol
                } else {
                    dw / limits[0] * tol
                },
            );
            return Some(Refined {
                elements: 2 * n,
                reason: format!(
                    "{apart}: the finer is kept, unconfirmed, for a further doubling would pass the {MAX_NODES} nodes the dense modal check takes"
                ),
                unconfirmed: Some(format!(
                    "the mesh of {} elements is the finest the plan's check reaches ({MAX_NODES} nodes) and is not confirmed within the accuracy: {apart}; a run with `track.beam.elements` doubled shows what a scene's numbers move by",
                    2 * n
                )),
            });
        }
        n *= 2;
        coarse = fine;
    }
}

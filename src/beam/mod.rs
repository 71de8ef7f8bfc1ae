//! The geometrically exact planar (Reissner) beam of thesis chapter 4, discretised by Galerkin
//! finite elements with Lagrange polynomials of degree 1..10.
//!
//! The beam is computed in its own frame: x along the undeformed axis from `from` to `to`,
//! displacements (u, w) along and across it, so an inclined beam is the horizontal one turned
//! rigidly by its angle; loads are turned into this frame and results back. Each step of the
//! method lives in its own file: `quadrature`, `basis`, `element` (kinematics, resultants,
//! internal force, tangent, mass), `supports`, and the assembly below.
//!
//! The same mesh serves three models of the beam ([`BeamModel`]): the geometrically exact
//! one; its linearisation about the undeformed state (constant stiffness K₀, assembled here);
//! and the lowest modes of that linear beam (`modal.rs`), whose amplitudes replace the
//! mesh's unknowns in the equations of motion while the mesh still gives every displacement.

pub mod basis;
pub mod damping;
pub mod dynamics;
pub mod element;
pub mod load;
pub mod modal;
pub mod quadrature;
pub mod supports;
pub mod train;

use basis::Lagrange;
use element::{ElementKernels, Section, Tabulated};
use supports::Support;

use crate::linalg::{Assembly, AssemblyPattern, Sparse};
use crate::recent::SharedRecent;
use std::sync::{Arc, OnceLock};

/// Which rule integrates the stiffness. Reduced Gauss (p points for degree p) is free of
/// shear locking and of spurious zero-energy modes for this element (3p constraints on
/// 3(p + 1) − 3 deformation modes); full Gauss (p + 1) locks for thin beams at low degree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quadrature {
    Reduced,
    Full,
    Lobatto,
}

impl Quadrature {
    pub fn name(self) -> &'static str {
        match self {
            Quadrature::Reduced => "reduced",
            Quadrature::Full => "full",
            Quadrature::Lobatto => "lobatto",
        }
    }

    pub fn from_name(name: &str) -> Option<Quadrature> {
        [Quadrature::Reduced, Quadrature::Full, Quadrature::Lobatto]
            .into_iter()
            .find(|q| q.name() == name)
    }

    fn rule(self, degree: usize) -> quadrature::Rule {
        match self {
            Quadrature::Reduced => quadrature::gauss(degree),
            Quadrature::Full => quadrature::gauss(degree + 1),
            Quadrature::Lobatto => quadrature::lobatto(degree + 1),
        }
    }
}

/// How the beam's deformation is modelled.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BeamModel {
    /// The geometrically exact Reissner beam.
    Exact,
    /// Small displacements: the exact beam's stiffness and mass about the undeformed state.
    Linear,
    /// The lowest `modes` natural modes of the linear beam.
    Modal { modes: usize },
}

impl BeamModel {
    pub fn name(self) -> &'static str {
        match self {
            BeamModel::Exact => "exact",
            BeamModel::Linear => "linear",
            BeamModel::Modal { .. } => "modal",
        }
    }

    /// The number of modes of a modal beam.
    pub fn modes(self) -> Option<usize> {
        match self {
            BeamModel::Modal { modes } => Some(modes),
            _ => None,
        }
    }
}

/// The beam as the scene describes it.
#[derive(Clone, Debug)]
pub struct BeamSpec {
    pub from: [f64; 2],
    pub to: [f64; 2],
    pub section: Section,
    /// The section's depth (m): how far a wheel's load spreads before it reaches the axis
    /// (see `coupling::patch`).
    pub depth: f64,
    pub supports: [Support; 2],
    /// Material points x of intermediate bearings, which hold w there; each lies on an
    /// element boundary (see [`supports::mesh_multiple`]).
    pub bearings: Vec<f64>,
    pub elements: usize,
    pub order: usize,
    pub quadrature: Quadrature,
    pub model: BeamModel,
    /// Rayleigh damping, as the scene gives it.
    pub damping: Option<damping::DampingSpec>,
    /// Gravity's acceleration (m/s², acting in −Y) on the beam's own mass, where the scene
    /// puts its self-weight on it.
    pub self_weight: Option<f64>,
}

/// The stiffest shear G·Av a beam is assembled with. Its stiffness matrix adds the shear's
/// G Av/h and the bending's E I/h³ into the same entries, and where the first dwarfs the second
/// the bending survives only to round-off times their ratio: a linear beam's deflection errs by
/// up to C ε R (30 + n²) of itself, R = G Av L²/(E I) on n elements, C ≈ p²/10 for degree p
/// (measured against Timoshenko's closed forms on simply supported, clamped and cantilevered
/// beams of degree 2 to 10 on 2 to 128 elements at R = 10¹¹ and 10¹³: the largest C per degree
/// 0.35, 0.81, 1.39, 2.59 and 8.9 for p = 2, 3, 4, 6, 10). A stiffer shear takes about 12/R off
/// the deflection, so past the R where the two are equal a larger G Av only loses digits; a
/// small-displacement beam's limit is that R, where each is √(12 C ε (30 + n²)): 7·10⁻⁷ of the
/// deflection on 10 elements of degree 4. The exact beam's internal forces come from its
/// strains, so its Newton iteration settles on the deflection whatever its tangent loses, as
/// long as the tangent keeps it contracting: its limit is where the tangent's error reaches
/// 10⁻² (12/R then about 10⁻¹¹); past it, a static cantilever took 53 Newton iterations at
/// R = 4·10¹¹, 159 at 4·10¹², and found no equilibrium at 4·10¹⁴.
pub fn shear_rigid_limit(spec: &BeamSpec, length: f64) -> f64 {
    shear_rigid_ratio(spec) * spec.section.ei / (length * length)
}

impl BeamSpec {
    /// Whether supports hold u at both ends, so that the axis cannot draw its ends in as it
    /// bends.
    pub fn holds_u_at_both_ends(&self) -> bool {
        self.supports
            .iter()
            .all(|s| s.held_components().contains(&0))
    }

    /// The longest stretch between the ends and the intermediate bearings.
    pub fn longest_span(&self) -> f64 {
        let length = (self.to[0] - self.from[0]).hypot(self.to[1] - self.from[1]);
        let mut ends = vec![0.0];
        ends.extend(self.bearings.iter().copied());
        ends.push(length);
        ends.windows(2).fold(0.0, |m, w| m.max(w[1] - w[0]))
    }

    /// A rotation φ at a probe as a length, φ times the longest span over π: the deflection of
    /// the half sine that turns by φ at its ends.
    pub fn rotation_as_length(&self, phi: f64) -> f64 {
        phi.abs() * self.longest_span() / std::f64::consts::PI
    }
}

/// Below this share of their rotation as a length ([`BeamSpec::rotation_as_length`]) the
/// probes' deflection is taken as no response: the loads only turn them. A moment at the
/// middle of a simply supported beam, probed there, deflects it by round-off (10⁻¹³ m against
/// a rotation of 3.5 mm as a length); measured by that, the exact and the linear statics
/// differ by all of it, and an atol of rtol times it (4·10⁻¹⁹) is below the round-off of the
/// state it bounds.
const ONLY_TURNED: f64 = 1e-3;

/// The size of the static response at the probes, whose largest deflection is `deflection`
/// and largest rotation as a length `turned`: the deflection, unless the loads only turn the
/// probes ([`ONLY_TURNED`]); then the rotation.
pub fn response_scale(deflection: f64, turned: f64) -> f64 {
    if deflection < ONLY_TURNED * turned {
        turned
    } else {
        deflection
    }
}

/// [`shear_rigid_limit`] as the ratio R = G Av L²/(E I) it holds.
pub fn shear_rigid_ratio(spec: &BeamSpec) -> f64 {
    let (n, p) = (spec.elements as f64, spec.order as f64);
    let loss = 0.1 * p * p * f64::EPSILON * (30.0 + n * n);
    match spec.model {
        BeamModel::Exact => 1e-2 / loss,
        BeamModel::Linear | BeamModel::Modal { .. } => (12.0 / loss).sqrt(),
    }
}

/// Material points prepared for repeated reading (see [`Beam::stations`]): per point, the
/// first node of the element that holds it and the element's shape functions there. A reading
/// spreads q over the nodes once ([`Beam::nodal`]), so each point sums contiguous nodes.
#[derive(Clone, Debug)]
pub struct Stations {
    first: Vec<usize>,
    /// The shape values of every point, `per` each, point after point.
    shape: Vec<f64>,
    per: usize,
}

impl Stations {
    /// (u, w, φ) in the beam frame at each point, from the nodal field.
    fn read<'a>(&'a self, nodal: &'a [[f64; 3]]) -> impl Iterator<Item = [f64; 3]> + 'a {
        self.first
            .iter()
            .zip(self.shape.chunks_exact(self.per))
            .map(move |(&first, n)| interpolate(n, nodal[first..first + self.per].iter().copied()))
    }
}

/// A node's (u, w, φ) in q; a held unknown is zero.
fn node_value(eq: &[Option<usize>], q: &[f64]) -> [f64; 3] {
    [0, 1, 2].map(|c| eq[c].map_or(0.0, |i| q[i]))
}

/// Σ_a N_a d_a: the (u, w, φ) that shape values `n` make of their element's nodal values.
fn interpolate(n: &[f64], nodes: impl Iterator<Item = [f64; 3]>) -> [f64; 3] {
    let mut v = [0.0; 3];
    for (na, d) in n.iter().zip(nodes) {
        v[0] += na * d[0];
        v[1] += na * d[1];
        v[2] += na * d[2];
    }
    v
}

/// Highest Lagrange degree of an element (the scene reader refuses more): the shape functions
/// at a point then fit on the stack.
pub const MAX_ORDER: usize = 10;

/// The shape functions' values at one material point, held on the stack: a moving load reads
/// them at every force evaluation, for every axle of a train.
#[derive(Clone, Copy)]
struct ShapeValues {
    n: [f64; MAX_ORDER + 1],
    len: usize,
}

impl std::ops::Deref for ShapeValues {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        &self.n[..self.len]
    }
}

/// A displacement state at one material point, in global axes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointDisplacement {
    pub u: f64,
    pub w: f64,
    pub phi: f64,
}

/// What the track a contact patch averages is past an end where nothing holds w.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PastFreeEnd {
    /// The undisplaced axis, as past a support: the track a train or a vehicle runs on
    /// beyond the deck, stepped by the tip's deflection.
    Slab,
    /// The end's tangent carried on: a disk leaves the beam at its end, and nothing lies
    /// beyond it. As an undisplaced slab, a cantilever's tip
    /// sunk 43 mm under a 150 kg disk was a step the patch met at 40 times the disk's weight.
    CarriedOn,
}

/// One node's free unknowns (`None` where a support holds it) and its weight at a point with
/// the weight's first three derivatives in x.
#[derive(Clone, Copy, Debug)]
pub struct NodeBasis {
    pub u: Option<usize>,
    pub w: Option<usize>,
    pub phi: Option<usize>,
    pub d: [f64; 4],
}

/// ∂r/∂q of the axis point whose node weights are `basis`: the X and the Y component (beam
/// frame) of its displacement as rows over the free unknowns. What rides on the axis (a
/// disk's contact, a moving mass) adds its inertia through these.
pub fn position_rows(basis: &[NodeBasis]) -> [Vec<(usize, f64)>; 2] {
    let mut gx = Vec::with_capacity(basis.len());
    let mut gy = Vec::with_capacity(basis.len());
    for nb in basis {
        if let Some(i) = nb.u {
            gx.push((i, nb.d[0]));
        }
        if let Some(i) = nb.w {
            gy.push((i, nb.d[0]));
        }
    }
    [gx, gy]
}

/// The discretised beam: mesh, equation numbering with supports applied, constant mass matrix.
#[derive(Clone, Debug)]
pub struct Beam {
    pub spec: BeamSpec,
    pub length: f64,
    /// Angle of the undeformed axis to the global X axis.
    pub angle: f64,
    /// (sin, cos) of the angle: every result is turned by it.
    turn: (f64, f64),
    basis: Lagrange,
    stiff: Tabulated,
    /// Integrates a contact-patch kernel (degree 8) times a shape function (degree p) exactly.
    patch_rule: quadrature::Rule,
    h: f64,
    /// Equation number of each global unknown (3 per node), `None` where a support holds it.
    eq: Vec<Option<usize>>,
    n_free: usize,
    mass: Sparse,
    /// Mass on every unknown, supports included: the inertia the supports carry.
    full_mass: Sparse,
    /// The tangent's pattern, found at its first assembly.
    tangent_pattern: OnceLock<AssemblyPattern>,
    /// K₀ on the free unknowns and on all of them (the supports' reactions), for the linear
    /// and modal models, whose internal force is K₀ q.
    linear: Option<(Sparse, Sparse)>,
    /// The beam's own weight as a load on the free unknowns and on all of them: M g, the
    /// consistent mass times gravity's acceleration on every node's displacements.
    weight: Option<(Vec<f64>, Vec<f64>)>,
    /// The scene's shear stiffness G·Av, where the beam is assembled with less
    /// ([`shear_rigid_limit`]; `spec.section.gav` holds what it is assembled with).
    pub shear_given: Option<f64>,
}

/// Beams kept assembled for the specs last asked: planning a scene and running it assemble the
/// same mesh several times, and a sweep's cases share their beam.
const KEPT_BEAMS: usize = 8;
/// Largest beam (unknowns) kept: a long-lived process (Python) holds what it keeps.
const KEPT_BEAM_LIMIT: usize = 2000;

/// The beams kept, each by its spec's text.
static KEPT: SharedRecent<Arc<Beam>> = SharedRecent::new(KEPT_BEAMS);

impl Beam {
    /// The beam of `spec`, assembled once for every caller that asks for the same spec while
    /// it is among the last [`KEPT_BEAMS`] asked: the same matrices [`Beam::new`] assembles.
    pub fn shared(spec: &BeamSpec) -> Arc<Beam> {
        let key = format!("{spec:?}");
        if let Some(hit) = KEPT.get(&key) {
            return hit;
        }
        let beam = Arc::new(Beam::new(spec.clone()));
        if beam.dim() <= KEPT_BEAM_LIMIT {
            KEPT.keep(key, beam.clone());
        }
        beam
    }

    /// The shear stiffness G·Av the beam is assembled with, where it holds the scene's back.
    pub fn held_shear(&self) -> Option<f64> {
        self.shear_given.map(|_| self.spec.section.gav)
    }

    pub fn new(mut spec: BeamSpec) -> Beam {
        assert!(
            (1..=MAX_ORDER).contains(&spec.order),
            "the scene reader bounds the degree"
        );
        let length = (spec.to[0] - spec.from[0]).hypot(spec.to[1] - spec.from[1]);
        // A bending stiffness near the smallest double leaves no limit to hold the shear at.
        let limit = shear_rigid_limit(&spec, length);
        let shear_given = (limit.is_normal() && spec.section.gav > limit)
            .then(|| std::mem::replace(&mut spec.section.gav, limit));
        let angle = (spec.to[1] - spec.from[1]).atan2(spec.to[0] - spec.from[0]);
        let basis = Lagrange::new(spec.order);
        let h = length / spec.elements as f64;
        let stiff = Tabulated::new(&basis, &spec.quadrature.rule(spec.order), h);
        let patch_rule = quadrature::gauss((spec.order + 10) / 2);
        let nodes = spec.elements * spec.order + 1;
        let mut held = vec![false; 3 * nodes];
        for (end, support) in spec.supports.iter().enumerate() {
            let node = if end == 0 { 0 } else { nodes - 1 };
            for c in support.held_components() {
                held[3 * node + c] = true;
            }
        }
        for &x in &spec.bearings {
            let node = (x / h).round() as usize * spec.order;
            held[3 * node + 1] = true;
        }
        let mut next = 0;
        let eq = held
            .iter()
            .map(|&h| {
                (!h).then(|| {
                    next += 1;
                    next - 1
                })
            })
            .collect();
        let mut beam = Beam {
            spec,
            length,
            angle,
            turn: angle.sin_cos(),
            basis,
            stiff,
            patch_rule,
            h,
            eq,
            n_free: next,
            mass: Sparse::try_new_from_triplets(0, 0, &[]).expect("empty"),
            full_mass: Sparse::try_new_from_triplets(0, 0, &[]).expect("empty"),
            tangent_pattern: OnceLock::new(),
            linear: None,
            weight: None,
            shear_given,
        };
        (beam.mass, beam.full_mass) = beam.assemble_mass();
        if let Some(g) = beam.spec.self_weight {
            beam.weight = Some(beam.assemble_weight(g));
        }
        if beam.spec.model != BeamModel::Exact {
            beam.linear = Some(beam.assemble_initial_stiffness());
        }
        beam
    }

    /// M g on the free unknowns and on all, for gravity's acceleration g acting in −Y.
    fn assemble_weight(&self, g: f64) -> (Vec<f64>, Vec<f64>) {
        let local = self.to_local([0.0, -g]);
        let accel: Vec<f64> = (0..3 * self.nodes())
            .map(|dof| match dof % 3 {
                2 => 0.0,
                c => local[c],
            })
            .collect();
        let mut full = vec![0.0; accel.len()];
        crate::linalg::mul(&self.full_mass, &accel, &mut full);
        let mut free = vec![0.0; self.n_free];
        for (dof, eq) in self.eq.iter().enumerate() {
            if let Some(i) = eq {
                free[*i] = full[dof];
            }
        }
        (free, full)
    }

    /// Add the beam's own weight (on the free unknowns) to f, where the scene puts it on.
    pub fn add_weight(&self, f: &mut [f64]) {
        if let Some((free, _)) = &self.weight {
            f.iter_mut().zip(free).for_each(|(a, b)| *a += b);
        }
    }

    /// The beam's own weight on the free unknowns, where the scene puts it on.
    pub fn weight(&self) -> Option<&[f64]> {
        self.weight.as_ref().map(|(free, _)| free.as_slice())
    }

    /// The exact beam's tangent at the undeformed state, on the free unknowns and on all.
    fn assemble_initial_stiffness(&self) -> (Sparse, Sparse) {
        let k = 3 * (self.spec.order + 1);
        let qe = vec![0.0; k];
        let mut ke = vec![0.0; k * k];
        let kernels = ElementKernels {
            section: &self.spec.section,
            stiff: &self.stiff,
        };
        let mut free = Assembly::new(self.n_free);
        let mut full = Assembly::new(3 * self.nodes());
        for e in 0..self.spec.elements {
            kernels.tangent(&qe, &mut ke);
            self.scatter_matrix(e, &ke, &mut free);
            for (i, r) in self.element_dofs(e).enumerate() {
                for (j, c) in self.element_dofs(e).enumerate() {
                    full.add(r, c, ke[i * k + j]);
                }
            }
        }
        (free.build(), full.build())
    }

    /// Unknowns after the supports are applied.
    pub fn dim(&self) -> usize {
        self.n_free
    }

    pub fn nodes(&self) -> usize {
        self.spec.elements * self.spec.order + 1
    }

    pub fn mass(&self) -> &Sparse {
        &self.mass
    }

    fn element_dofs(&self, e: usize) -> impl Iterator<Item = usize> + '_ {
        let first = e * self.spec.order;
        (0..3 * (self.spec.order + 1)).map(move |k| 3 * first + k)
    }

    fn gather(&self, e: usize, q: &[f64], qe: &mut [f64]) {
        for (k, dof) in self.element_dofs(e).enumerate() {
            qe[k] = self.eq[dof].map_or(0.0, |i| q[i]);
        }
    }

    /// The consistent mass on the free unknowns, and on all of them.
    fn assemble_mass(&self) -> (Sparse, Sparse) {
        let rule = quadrature::gauss(self.spec.order + 1);
        let tab = Tabulated::new(&self.basis, &rule, self.h);
        let k = 3 * (self.spec.order + 1);
        let mut me = vec![0.0; k * k];
        element::mass(&self.spec.section, &tab, &mut me);
        // The element mass couples no two components (u, w, φ): leaving its zeros out of
        // the pattern takes two thirds off every product with it.
        let mut free = Assembly::new(self.n_free);
        let mut full = Assembly::new(3 * self.nodes());
        for e in 0..self.spec.elements {
            let dofs: Vec<usize> = self.element_dofs(e).collect();
            for (i, &r) in dofs.iter().enumerate() {
                for (j, &c) in dofs.iter().enumerate() {
                    let m = me[i * k + j];
                    if m == 0.0 {
                        continue;
                    }
                    full.add(r, c, m);
                    if let (Some(ri), Some(cj)) = (self.eq[r], self.eq[c]) {
                        free.add(ri, cj, m);
                    }
                }
            }
        }
        (free.build(), full.build())
    }

    fn scatter_matrix(&self, e: usize, ke: &[f64], a: &mut Assembly) {
        let dofs: Vec<Option<usize>> = self.element_dofs(e).map(|d| self.eq[d]).collect();
        let k = dofs.len();
        for (i, ri) in dofs.iter().enumerate() {
            let Some(ri) = ri else { continue };
            for (j, cj) in dofs.iter().enumerate() {
                if let Some(cj) = cj {
                    a.add(*ri, *cj, ke[i * k + j]);
                }
            }
        }
    }

    /// Internal force vector on the free unknowns; returns the strain energy.
    pub fn internal_force(&self, q: &[f64], f: &mut [f64]) -> f64 {
        if let Some((k0, _)) = &self.linear {
            crate::linalg::mul(k0, q, f);
            return 0.5 * f.iter().zip(q).map(|(a, b)| a * b).sum::<f64>();
        }
        f.fill(0.0);
        let k = 3 * (self.spec.order + 1);
        let mut qe = vec![0.0; k];
        let mut fe = vec![0.0; k];
        let kernels = ElementKernels {
            section: &self.spec.section,
            stiff: &self.stiff,
        };
        let mut energy = 0.0;
        for e in 0..self.spec.elements {
            self.gather(e, q, &mut qe);
            energy += kernels.internal_force(&qe, &mut fe);
            for (kk, dof) in self.element_dofs(e).enumerate() {
                if let Some(i) = self.eq[dof] {
                    f[i] += fe[kk];
                }
            }
        }
        energy
    }

    pub fn strain_energy(&self, q: &[f64]) -> f64 {
        let mut f = vec![0.0; self.n_free];
        self.internal_force(q, &mut f)
    }

    /// K₀, the tangent about the undeformed state, on the free unknowns.
    pub fn initial_stiffness(&self) -> Sparse {
        match &self.linear {
            Some((k0, _)) => k0.clone(),
            None => self.assemble_initial_stiffness().0,
        }
    }

    /// Tangent stiffness ∂f_int/∂q on the free unknowns (material + geometric; K₀ where the
    /// model is linear).
    pub fn tangent(&self, q: &[f64]) -> Sparse {
        if let Some((k0, _)) = &self.linear {
            return k0.clone();
        }
        let k = 3 * (self.spec.order + 1);
        let mut qe = vec![0.0; k];
        let mut ke = vec![0.0; k * k];
        let kernels = ElementKernels {
            section: &self.spec.section,
            stiff: &self.stiff,
        };
        let mut a = Assembly::new(self.n_free);
        for e in 0..self.spec.elements {
            self.gather(e, q, &mut qe);
            kernels.tangent(&qe, &mut ke);
            self.scatter_matrix(e, &ke, &mut a);
        }
        self.tangent_pattern.get_or_init(|| a.pattern()).build(&a)
    }

    /// Whether the beam is the linear one, its tangent K₀ at every state.
    pub fn is_linear(&self) -> bool {
        self.linear.is_some()
    }

    /// Element and shape-function values at material point x ∈ [0, L].
    fn locate(&self, x: f64) -> (usize, ShapeValues) {
        // The cast truncates and saturates (a point before the start to element 0): the
        // floor without its call into libm, which a point load pays at every sample.
        let e = ((x / self.h) as usize).min(self.spec.elements - 1);
        let xi = 2.0 * (x - e as f64 * self.h) / self.h - 1.0;
        let len = self.spec.order + 1;
        let mut n = [0.0; MAX_ORDER + 1];
        self.basis.values(xi, &mut n[..len]);
        (e, ShapeValues { n, len })
    }

    /// Equation number of component c (0 u, 1 w, 2 φ) of a node; `None` where a support holds it.
    pub fn eq_of(&self, node: usize, c: usize) -> Option<usize> {
        self.eq[3 * node + c]
    }

    /// The length of one element (the mesh is uniform).
    pub fn element_length(&self) -> f64 {
        self.h
    }

    /// Per element, the coefficients in powers of its ξ of Σ_a row[i_a] N_a(ξ), i_a the
    /// unknown of component c (0 u, 1 w, 2 φ) at its node a: what `row` reads of a unit point
    /// load in that component, as a polynomial along each element; none on an element where
    /// it reads nothing (a level beam's axial modes under vertical loads), which every step
    /// then skips.
    pub fn row_along_elements(&self, row: &[f64], c: usize) -> Vec<Vec<f64>> {
        let monomials = self.basis.monomials();
        let p = self.spec.order;
        (0..self.spec.elements)
            .map(|e| {
                let mut out = vec![0.0; p + 1];
                for (a, n) in monomials.iter().enumerate() {
                    if let Some(i) = self.eq[3 * (e * p + a) + c] {
                        out.iter_mut().zip(n).for_each(|(o, nj)| *o += row[i] * nj);
                    }
                }
                if out.iter().all(|&v| v == 0.0) {
                    out.clear();
                }
                out
            })
            .collect()
    }

    /// A row read along the elements ([`Self::row_along_elements`]) of a point force's two
    /// components, u and w.
    pub fn row_along(&self, row: &[f64]) -> RowAlong {
        [0, 1].map(|c| self.row_along_elements(row, c))
    }

    /// What each of `rows` reads of the vertical forces moving straight over a step, each
    /// path (x0, x1, force), added to that row's polynomial in the step's own time in `out`;
    /// `None` where a path crosses a node, over which no polynomial holds.
    pub fn add_paths_along(
        &self,
        rows: &[RowAlong],
        paths: &[(f64, f64, f64)],
        out: &mut [Vec<f64>],
    ) -> Option<()> {
        let len = self.spec.order + 1;
        let mut powers = vec![0.0; len * len];
        for &(x0, x1, force) in paths {
            let local = self.to_local([0.0, -force]);
            let (e, xi0, xi1) = self.element_path(x0, x1)?;
            powers_along((xi0, xi1 - xi0), len, &mut powers);
            for (components, poly) in rows.iter().zip(out.iter_mut()) {
                for (elements, &f) in components.iter().zip(&local) {
                    if f != 0.0 {
                        add_along(&elements[e], (&powers, len), f, poly);
                    }
                }
            }
        }
        Some(())
    }

    /// The constant polynomial c, with room for what [`Self::add_paths_along`] adds to it.
    pub fn polynomial_along_from(&self, c: f64) -> Vec<f64> {
        let mut p = Vec::with_capacity(self.spec.order + 1);
        p.push(c);
        p
    }

    /// The element a point moving straight from x0 to x1 stays in, and its ξ at either end;
    /// `None` where the path crosses a node.
    pub fn element_path(&self, x0: f64, x1: f64) -> Option<(usize, f64, f64)> {
        let e = self.element_of(0.5 * (x0 + x1));
        let xi = |x: f64| 2.0 * (x - e as f64 * self.h) / self.h - 1.0;
        let (xi0, xi1) = (xi(x0), xi(x1));
        let inside = |xi: f64| xi.abs() <= 1.0 + PATH_SLACK;
        (inside(xi0) && inside(xi1)).then_some((e, xi0, xi1))
    }

    /// The element holding material point x (the end elements extend past the ends).
    pub fn element_of(&self, x: f64) -> usize {
        ((x / self.h).floor().max(0.0) as usize).min(self.spec.elements - 1)
    }

    /// The free unknowns of the nodes under a contact patch of half-width `half` around
    /// material point s, with the weights S_a and their first three derivatives: the axis
    /// averaged over the patch with the smooth kernel K(ξ) = 315/(256 b) (1 − (ξ/b)²)⁴: the weights are
    /// S_a^(k)(s) = ∫ K^(k)(s − x) N_a(x) dx, integrated exactly element by element. Past
    /// an end that holds w the track is the undisplaced extension of the axis, as a bridge's
    /// approach slab: a disk entering at a support loads the beam gradually. Past a free end
    /// the track is what `past` says; carried on, it is the end's tangent, N_a(L) + N_a'(L)
    /// (x − L): a free end bears no moment, so the axis leaves it straight, and the tangent
    /// holds only what converges with the mesh (the end element's polynomial carried on past
    /// its end amplifies the mesh's highest modes by about (1 + 2 b/h)^p: a 200 kg moving mass
    /// leaving a 12 m cantilever under a patch of ±0.77 m left midspan vibrating at 1.80, 1.60
    /// and 0.96·10⁻⁴ m on 12, 24 and 48 elements, where a moving force stays at 1.80 on both).
    /// K and its first three derivatives vanish at the patch's
    /// edges, so the averaged axis has three continuous derivatives in s even though the
    /// elements meet with kinks (and where an end holds the displacement, also as the patch
    /// crosses it).
    pub fn patch_basis_at(&self, s: f64, half: f64, past: PastFreeEnd) -> Vec<NodeBasis> {
        let reach = |end: bool| match past {
            PastFreeEnd::CarriedOn if !self.holds_w_at(end) => half,
            _ => 0.0,
        };
        let (lo, hi) = (
            (s - half).max(-reach(false)),
            (s + half).min(self.length + reach(true)),
        );
        let (inside_lo, inside_hi) = (lo.max(0.0), hi.min(self.length));
        let (e_lo, e_hi) = (self.element_of(inside_lo), self.element_of(inside_hi));
        let p = self.spec.order;
        let first = e_lo * p;
        let mut weights = vec![[0.0; 4]; (e_hi - e_lo) * p + p + 1];
        let rule = &self.patch_rule;
        let mut n = vec![0.0; p + 1];
        let mut dn = vec![0.0; p + 1];
        // K^(k) = 315/256 · b^−(k+1) · f_k(u), u = (s − x)/b, at the rule's points over [a, b].
        let scale: [f64; 4] = std::array::from_fn(|k| 315.0 / 256.0 / half.powi(k as i32 + 1));
        let kernel_over = |a: f64, b: f64| {
            rule.points.iter().zip(&rule.weights).map(move |(xi, w)| {
                let x = 0.5 * (a + b) + 0.5 * (b - a) * xi;
                let jw = 0.5 * (b - a) * w;
                let u = (s - x) / half;
                let v = 1.0 - u * u;
                let f = [
                    v.powi(4),
                    -8.0 * u * v.powi(3),
                    -8.0 * v.powi(3) + 48.0 * u * u * v * v,
                    144.0 * u * v * v - 192.0 * u.powi(3) * v,
                ];
                let kernel: [f64; 4] = std::array::from_fn(|k| f[k] * scale[k] * jw);
                (x, kernel)
            })
        };
        let mut add = |e: usize, n: &[f64], kernel: &[f64; 4]| {
            for (weight, na) in weights[e * p - first..].iter_mut().zip(n) {
                for (wk, kk) in weight.iter_mut().zip(kernel) {
                    *wk += kk * na;
                }
            }
        };
        for e in e_lo..=e_hi {
            let a = if e == e_lo {
                inside_lo
            } else {
                e as f64 * self.h
            };
            let b = if e == e_hi {
                inside_hi
            } else {
                (e + 1) as f64 * self.h
            };
            if b <= a {
                continue;
            }
            for (x, kernel) in kernel_over(a, b) {
                self.basis.eval(
                    2.0 * (x - e as f64 * self.h) / self.h - 1.0,
                    &mut n,
                    &mut dn,
                );
                add(e, &n, &kernel);
            }
        }
        let last = self.spec.elements - 1;
        for (a, b, e, end) in [
            (lo, hi.min(0.0), 0, 0.0),
            (lo.max(self.length), hi, last, self.length),
        ] {
            if b <= a {
                continue;
            }
            self.basis
                .eval(if end == 0.0 { -1.0 } else { 1.0 }, &mut n, &mut dn);
            for d in dn.iter_mut() {
                *d = *d * 2.0 / self.h;
            }
            let mut tangent = vec![0.0; p + 1];
            for (x, kernel) in kernel_over(a, b) {
                for ((t, v), d) in tangent.iter_mut().zip(&n).zip(&dn) {
                    *t = v + d * (x - end);
                }
                add(e, &tangent, &kernel);
            }
        }
        weights
            .into_iter()
            .enumerate()
            .map(|(k, d)| {
                let node = first + k;
                NodeBasis {
                    u: self.eq[3 * node],
                    w: self.eq[3 * node + 1],
                    phi: self.eq[3 * node + 2],
                    d,
                }
            })
            .collect()
    }

    /// Global load components turned into the beam frame.
    pub fn to_local(&self, v: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.turn;
        [c * v[0] + s * v[1], -s * v[0] + c * v[1]]
    }

    pub fn to_global(&self, v: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.turn;
        [c * v[0] - s * v[1], s * v[0] + c * v[1]]
    }

    /// Add a point force (global fx, fy) and moment mz at material point x: the Dirac load's
    /// virtual work puts P·P_i(x) on each unknown, no mesh node needed at x.
    pub fn add_point_load(&self, x: f64, force: [f64; 2], mz: f64, f: &mut [f64]) {
        self.point_load_terms(x, force, mz, |i, v| f[i] += v);
    }

    /// The terms (unknown, value) of a point load at x, handed to `add` one by one: the few
    /// unknowns of the element that holds x.
    pub fn point_load_terms(
        &self,
        x: f64,
        force: [f64; 2],
        mz: f64,
        mut add: impl FnMut(usize, f64),
    ) {
        let local = self.to_local(force);
        let (e, n) = self.locate(x);
        let first = e * self.spec.order;
        // A component the load does not have adds nothing: an axle's force on a level deck is
        // one of the three, and on a modal beam each term is a row over the modes.
        let components = [(0, local[0]), (1, local[1]), (2, mz)];
        for (a, na) in n.iter().enumerate() {
            let node = first + a;
            for &(c, value) in components.iter().filter(|(_, v)| *v != 0.0) {
                if let Some(i) = self.eq[3 * node + c] {
                    add(i, na * value);
                }
            }
        }
    }

    /// Whether a support holds w at the end x = 0 (`false`) or x = L (`true`).
    pub fn holds_w_at(&self, end: bool) -> bool {
        self.spec.supports[usize::from(end)]
            .held_components()
            .contains(&1)
    }

    /// Displacement (global u, w) and rotation at material point x.
    pub fn displacement_at(&self, q: &[f64], x: f64) -> PointDisplacement {
        let (e, n) = self.locate(x);
        self.displacement_in(e, &n, q)
    }

    /// Material points whose displacements are read at every output row (the sampled axis):
    /// their elements and shape-function values, evaluated once for the run.
    pub fn stations(&self, xs: &[f64]) -> Stations {
        let per = self.spec.order + 1;
        let mut first = Vec::with_capacity(xs.len());
        let mut shape = Vec::with_capacity(xs.len() * per);
        for &x in xs {
            let (e, n) = self.locate(x);
            first.push(e * self.spec.order);
            shape.extend_from_slice(&n);
        }
        Stations { first, shape, per }
    }

    /// The field q spread over the nodes, (u, w, φ) each in the beam frame, zero where a
    /// support holds it.
    fn nodal(&self, q: &[f64]) -> Vec<[f64; 3]> {
        self.eq
            .chunks_exact(3)
            .map(|node| node_value(node, q))
            .collect()
    }

    /// Displacements at the stations, in their order.
    pub fn displacements(&self, stations: &Stations, q: &[f64]) -> Vec<PointDisplacement> {
        let nodal = self.nodal(q);
        stations
            .read(&nodal)
            .map(|[u, w, phi]| {
                let [u, w] = self.to_global([u, w]);
                PointDisplacement { u, w, phi }
            })
            .collect()
    }

    /// The global w alone at the stations: what an acceleration envelope reads.
    pub fn deflections(&self, stations: &Stations, q: &[f64]) -> Vec<f64> {
        let nodal = self.nodal(q);
        stations
            .read(&nodal)
            .map(|[u, w, _]| self.to_global([u, w])[1])
            .collect()
    }

    fn displacement_in(&self, e: usize, n: &[f64], q: &[f64]) -> PointDisplacement {
        let first = e * self.spec.order;
        let nodes = self.eq[3 * first..]
            .chunks_exact(3)
            .map(|node| node_value(node, q));
        let v = interpolate(n, nodes);
        let [u, w] = self.to_global([v[0], v[1]]);
        PointDisplacement { u, w, phi: v[2] }
    }

    /// What holds the unknowns of `nodes`, supports included, in equilibrium at q under the
    /// point loads `loads` (x, global force, moment) and, in motion, with the acceleration `a`
    /// of the free unknowns: R = F_int + M a − F_ext, in the beam frame, (u, w, φ) per node.
    /// At a held unknown this is the support's reaction; at a free one, the residual. Only the
    /// rows of the nodes asked are formed: K₀ and M are symmetric, so a node's row is its
    /// column, and on the exact beam only the elements that hold the node add to it.
    fn held_forces(
        &self,
        nodes: &[usize],
        q: &[f64],
        loads: &[(f64, [f64; 2], f64)],
        a: Option<&[f64]>,
    ) -> Vec<[f64; 3]> {
        let p = self.spec.order;
        let value = |e: Option<usize>, y: &[f64]| e.map_or(0.0, |i| y[i]);
        let column_dot = |m: &Sparse, dof: usize, y: &[f64]| -> f64 {
            let (col_ptr, row_idx) = (m.symbolic().col_ptr(), m.symbolic().row_idx());
            (col_ptr[dof]..col_ptr[dof + 1])
                .map(|k| m.val()[k] * value(self.eq[row_idx[k]], y))
                .sum()
        };
        let k = 3 * (p + 1);
        let (mut qe, mut fe) = (vec![0.0; k], vec![0.0; k]);
        let kernels = ElementKernels {
            section: &self.spec.section,
            stiff: &self.stiff,
        };
        nodes
            .iter()
            .map(|&node| {
                let mut r = [0.0; 3];
                match &self.linear {
                    Some((_, k0)) => {
                        for (c, rc) in r.iter_mut().enumerate() {
                            *rc = column_dot(k0, 3 * node + c, q);
                        }
                    }
                    None => {
                        let last = self.spec.elements - 1;
                        let holding = (node.saturating_sub(1) / p)..=(node / p).min(last);
                        for e in holding {
                            self.gather(e, q, &mut qe);
                            kernels.internal_force(&qe, &mut fe);
                            for (c, rc) in r.iter_mut().enumerate() {
                                *rc += fe[3 * (node - e * p) + c];
                            }
                        }
                    }
                }
                if let Some((_, weight)) = &self.weight {
                    for (c, rc) in r.iter_mut().enumerate() {
                        *rc -= weight[3 * node + c];
                    }
                }
                if let Some(a) = a {
                    for (c, rc) in r.iter_mut().enumerate() {
                        *rc += column_dot(&self.full_mass, 3 * node + c, a);
                    }
                }
                for &(x, force, mz) in loads {
                    let local = self.to_local(force);
                    let (e, n) = self.locate(x);
                    if let Some(na) = node.checked_sub(e * p).and_then(|l| n.get(l)) {
                        r[0] -= na * local[0];
                        r[1] -= na * local[1];
                        r[2] -= na * mz;
                    }
                }
                r
            })
            .collect()
    }

    /// Forces and moment the supports exert on the beam at each end, global (fx, fy, mz), at q
    /// under the point loads `loads` and, in motion, with the acceleration `a` of the free
    /// unknowns (see [`Beam::held_forces`]). Zero where an end is free to move.
    pub fn support_reactions(
        &self,
        q: &[f64],
        loads: &[(f64, [f64; 2], f64)],
        a: Option<&[f64]>,
    ) -> [[f64; 3]; 2] {
        let held = self.held_forces(&[0, self.nodes() - 1], q, loads, a);
        let mut out = [[0.0; 3]; 2];
        for (end, full) in held.into_iter().enumerate() {
            let mut r = [0.0; 3];
            for &c in self.spec.supports[end].held_components() {
                r[c] = full[c];
            }
            let g = self.to_global([r[0], r[1]]);
            out[end] = [g[0], g[1], r[2]];
        }
        out
    }

    /// The force each intermediate bearing exerts on the beam, global (fx, fy): it acts
    /// across the undeformed axis.
    pub fn bearing_reactions(
        &self,
        q: &[f64],
        loads: &[(f64, [f64; 2], f64)],
        a: Option<&[f64]>,
    ) -> Vec<[f64; 2]> {
        let nodes: Vec<usize> = self
            .spec
            .bearings
            .iter()
            .map(|&x| (x / self.h).round() as usize * self.spec.order)
            .collect();
        self.held_forces(&nodes, q, loads, a)
            .into_iter()
            .map(|r| self.to_global([0.0, r[1]]))
            .collect()
    }

    /// Position of the undeformed axis at material point x.
    pub fn reference_point(&self, x: f64) -> [f64; 2] {
        let (s, c) = self.turn;
        [self.spec.from[0] + x * c, self.spec.from[1] + x * s]
    }
}

/// A row along the elements per component of a point force, u and w ([`Beam::row_along`]).
pub type RowAlong = [Vec<Vec<f64>>; 2];

/// How far past its element's ends (in ξ) a load's path over a step may reach: the rounding
/// of the time it crosses a node, not a crossing.
const PATH_SLACK: f64 = 1e-9;

/// The powers (ξ0 + β σ)^j, j < `len`, in powers of σ: row j of `out` (`len` wide) holds
/// the binomial terms of the j-th. A path's powers serve every row read along it, each row
/// then a product with them ([`add_along`]) instead of a Horner composition of its own.
fn powers_along((xi0, beta): (f64, f64), len: usize, out: &mut [f64]) {
    out[0] = 1.0;
    for j in 1..len {
        let (before, row) = out.split_at_mut(j * len);
        let last = &before[(j - 1) * len..];
        row[0] = last[0] * xi0;
        for k in 1..=j {
            row[k] = last[k] * xi0 + last[k - 1] * beta;
        }
    }
}

/// Add `scale` times c(ξ0 + β σ) to the polynomial in σ `out`, c in powers of ξ (a row read
/// along an element, [`Beam::row_along_elements`]) and `powers` the path's powers of
/// ξ0 + β σ ([`powers_along`]): what the row reads of a point force moving straight along the
/// element, as a polynomial in the step's own time.
fn add_along(c: &[f64], (powers, width): (&[f64], usize), scale: f64, out: &mut Vec<f64>) {
    let len = c.len().min(width);
    if out.len() < len {
        out.resize(len, 0.0);
    }
    for (j, &cj) in c[..len].iter().enumerate() {
        let s = scale * cj;
        let row = &powers[j * width..j * width + j + 1];
        out.iter_mut().zip(row).for_each(|(o, pk)| *o += s * pk);
    }
}

//! Structural systems M q'' = f(t, q), with f = F_ext(t) − F_int(q) and K = −∂f/∂q, and their
//! first-order view y = (q, v) through [`FirstOrder`], which every method of this module
//! integrates: the Runge–Kutta methods as M y' = f, generalized-α directly on the structure.

use std::borrow::Cow;
use std::ops::Range;

use super::{Dynamics, EventSpec, Problem};
use crate::linalg::{self, Assembly, LowRank, Sparse};

/// A structure that is uncoupled linear oscillators under a force of time alone: M = I and
/// f(t, q, v) = g(t) − K q − C v with K and C diagonal (a modal beam under moving forces).
#[derive(Clone, Debug)]
pub struct LinearModal {
    /// The diagonal of K (ω² per oscillator).
    pub stiffness: Vec<f64>,
    /// The diagonal of C.
    pub damping: Vec<f64>,
    /// The degree of g as a polynomial in t between the problem's kinks
    /// ([`SecondOrderProblem::kinks`]).
    pub degree: usize,
}

/// M(t, q) q'' = f(t, q, v): what generalized-α needs to take a step.
pub trait Structure {
    fn dim(&self) -> usize;
    /// M(t, q): constant for a bare beam, state-dependent once a body rides on it.
    fn mass(&self, t: f64, q: &[f64]) -> Cow<'_, Sparse>;
    /// A constant mass is factorised into the iteration matrix once per step size.
    fn mass_is_constant(&self) -> bool {
        true
    }
    /// M(t, q) = B + Σ_k w_k g_k g_kᵀ with B constant and a few sparse rows g_k, where the
    /// mass has that form (a body riding on a structure): B, and the (w_k, g_k) at (t, q).
    /// Every implicit method then factorises its iteration matrix from B alone, once per step
    /// size and tangent, and adds the rest exactly at every step by the Woodbury identity.
    fn mass_split(&self, _t: f64, _q: &[f64]) -> Option<(&Sparse, LowRank)> {
        None
    }
    /// out = M(t, q) a, without assembling M where the problem can avoid it.
    fn mass_mul(&self, t: f64, q: &[f64], a: &[f64], out: &mut [f64]) {
        linalg::mul(&self.mass(t, q), a, out);
    }
    /// f(t, q, v) = F_ext(t) − F_int(q) − (forces quadratic in the velocities).
    fn force(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]);
    /// K(q) = −∂f/∂q, the tangent stiffness (the part that matters for Newton's convergence).
    fn stiffness(&self, t: f64, q: &[f64]) -> Sparse;
    /// C = −∂f/∂v where the structure is damped (constant): it enters the iteration matrix
    /// beside the stiffness.
    fn damping(&self) -> Option<Cow<'_, Sparse>> {
        None
    }
    /// Blocks of unknowns of one kind (beam displacements, the contact coordinate): each is
    /// measured against its own largest value in the error norm.
    fn norm_groups(&self) -> Vec<Range<usize>> {
        vec![0..self.dim()]
    }
    /// See [`super::Dynamics::norm_weights`]; for the displacements, and the same again for
    /// the velocities in the first-order view.
    fn norm_weights(&self) -> Option<Vec<f64>> {
        None
    }
    /// Rows over the displacements the error norm measures beside them (see
    /// [`super::NormRows`]), and the same again over the velocities in the first-order view.
    fn norm_rows(&self) -> Option<super::ModeRows> {
        None
    }
    /// Where the structure is uncoupled linear oscillators under a force of time alone, which
    /// `exact-modal` integrates in closed form.
    fn linear_modal(&self) -> Option<LinearModal> {
        None
    }
    /// The force at rest, f(t + σh, 0, 0), per unknown as a polynomial in σ ∈ [0, 1] (powers
    /// of σ, lowest first), where the structure forms it in closed form over the stretch;
    /// `None` where it is to be sampled.
    fn force_at_rest_over(&self, _t: f64, _h: f64) -> Option<Vec<Vec<f64>>> {
        None
    }
}

/// A structure over time: what the driver watches besides the steps (see [`Problem`]).
pub trait SecondOrderProblem: Structure {
    type Event: Copy + std::fmt::Debug;
    /// The longest step allowed from (t, q, v); see [`Problem::max_step`].
    fn max_step(&self, _t: f64, _q: &[f64], _v: &[f64]) -> f64 {
        f64::INFINITY
    }
    fn breakpoints(&self) -> Vec<f64> {
        Vec::new()
    }
    /// Times where the force, smooth between them, has a kink (a moving load crossing a node
    /// of the mesh): a method that fits the force by polynomials ends its steps there.
    fn kinks(&self) -> Vec<f64> {
        Vec::new()
    }
    fn enter_segment(&self, _start: f64, _end: f64) {}
    fn events(&self) -> &[EventSpec<Self::Event>] {
        &[]
    }
    /// g(t, q, v); the run is watched for g passing from ≥ 0 to < 0.
    fn event(&self, _index: usize, _t: f64, _q: &[f64], _v: &[f64]) -> f64 {
        1.0
    }
    /// See [`Problem::event_pace`].
    fn event_pace(&self, _t: f64, _q: &[f64], _v: &[f64]) -> f64 {
        f64::INFINITY
    }
    /// See [`Problem::accepted`].
    fn accepted(&self, _t: f64, _q: &[f64], _v: &[f64]) {}
}

/// y = (q, v): q' = v, M(q) v' = f(t, q, v). Mass diag(I, M), Jacobian [[0, I], [−K, 0]].
pub struct FirstOrder<'a, E> {
    pub inner: &'a dyn SecondOrderProblem<Event = E>,
    /// What a velocity's error counts for beside a displacement's: 1/ω (see
    /// [`super::Options::velocity_rate`]), or 1.
    velocity_weight: f64,
}

impl<'a, E> FirstOrder<'a, E> {
    pub fn new(inner: &'a dyn SecondOrderProblem<Event = E>) -> Self {
        FirstOrder {
            inner,
            velocity_weight: 1.0,
        }
    }
    /// Velocities measured against ω · atol where `rate` is ω.
    pub fn measuring_velocities_at(self, rate: Option<f64>) -> Self {
        FirstOrder {
            velocity_weight: rate.filter(|w| *w > 0.0).map_or(1.0, f64::recip),
            ..self
        }
    }
}

impl<E: Copy + std::fmt::Debug> Dynamics for FirstOrder<'_, E> {
    fn dim(&self) -> usize {
        2 * self.inner.dim()
    }
    fn rhs(&self, t: f64, y: &[f64], f: &mut [f64]) {
        let n = self.inner.dim();
        f[..n].copy_from_slice(&y[n..]);
        self.inner.force(t, &y[..n], &y[n..], &mut f[n..]);
    }
    fn mass(&self, t: f64, y: &[f64]) -> Option<Sparse> {
        let n = self.inner.dim();
        let mut a = Assembly::new(2 * n);
        (0..n).for_each(|i| a.add(i, i, 1.0));
        a.add_sparse(&self.inner.mass(t, &y[..n]), 1.0, n, n);
        Some(a.build())
    }
    fn mass_is_constant(&self) -> bool {
        self.inner.mass_is_constant()
    }
    fn jacobian(&self, t: f64, y: &[f64]) -> Option<Sparse> {
        let n = self.inner.dim();
        let mut a = Assembly::new(2 * n);
        (0..n).for_each(|i| a.add(i, n + i, 1.0));
        a.add_sparse(&self.inner.stiffness(t, &y[..n]), -1.0, n, 0);
        if let Some(c) = self.inner.damping() {
            a.add_sparse(&c, -1.0, n, n);
        }
        Some(a.build())
    }
    /// The structure's groups, once for the displacements and once for the velocities.
    fn norm_groups(&self) -> Option<Vec<Range<usize>>> {
        let n = self.inner.dim();
        let q = self.inner.norm_groups();
        let v = q.iter().map(|g| g.start + n..g.end + n);
        Some(q.iter().cloned().chain(v).collect())
    }
    fn norm_weights(&self) -> Option<Vec<f64>> {
        let weighs_velocities = self.velocity_weight != 1.0;
        let w = match self.inner.norm_weights() {
            Some(w) => w,
            None if weighs_velocities => vec![1.0; self.inner.dim()],
            None => return None,
        };
        let v = w.iter().map(|w| w * self.velocity_weight);
        Some(w.iter().copied().chain(v).collect())
    }
    fn norm_rows(&self) -> Option<super::NormRows> {
        self.inner.norm_rows().map(|rows| super::NormRows {
            rows,
            blocks: vec![(0, 1.0), (self.inner.dim(), self.velocity_weight)],
        })
    }
    fn second_order(&self) -> Option<&dyn Structure> {
        Some(self.inner)
    }
}

impl<E: Copy + std::fmt::Debug> Problem for FirstOrder<'_, E> {
    type Event = E;
    fn breakpoints(&self) -> Vec<f64> {
        self.inner.breakpoints()
    }
    fn kinks(&self) -> Vec<f64> {
        self.inner.kinks()
    }
    fn enter_segment(&self, start: f64, end: f64) {
        self.inner.enter_segment(start, end)
    }
    fn events(&self) -> &[EventSpec<E>] {
        self.inner.events()
    }
    fn event(&self, index: usize, t: f64, y: &[f64]) -> f64 {
        let n = self.inner.dim();
        self.inner.event(index, t, &y[..n], &y[n..])
    }
    fn max_step(&self, t: f64, y: &[f64]) -> f64 {
        let n = self.inner.dim();
        self.inner.max_step(t, &y[..n], &y[n..])
    }
    fn event_pace(&self, t: f64, y: &[f64]) -> f64 {
        let n = self.inner.dim();
        self.inner.event_pace(t, &y[..n], &y[n..])
    }
    fn accepted(&self, t: f64, y: &[f64]) {
        let n = self.inner.dim();
        self.inner.accepted(t, &y[..n], &y[n..])
    }
}

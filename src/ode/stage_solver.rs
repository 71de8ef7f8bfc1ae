//! The implicit stage of a diagonally implicit Runge–Kutta method with a mass matrix:
//! M(z)(z − base) = d h f(t, z), solved by simplified Newton on the iteration matrix M − d h J.
//!
//! Both TR-BDF2 and the ESDIRK have one diagonal coefficient d for every implicit stage, so one
//! factorised M − d h J serves every stage of a step, and is kept across steps for as long as
//! Newton converges with it. A failure first refreshes the Jacobian; the driver then shrinks
//! the step. [`Dirk`] is the stepper both methods share; each supplies only its stages and its
//! error estimate ([`DirkMethod`]).
//!
//! The first-order view of a structure (y = (q, v), mass diag(I, M), J = [[0, I], [−K, −C]])
//! has the iteration matrix [[I, −dh I], [dh K, M + dh C]]. Eliminating the first block row
//! (x₁ = b₁ + dh x₂) leaves (M + dh C + dh² K) x₂ = b₂ − dh K b₁: one matrix of the
//! structure's size to assemble and factorise instead of one twice its size with four blocks,
//! whose pivoting fills in. On a coupled beam that was most of a step's cost.
//!
//! The first block row, q − base_q = dh v, is linear: once a stage's iterate satisfies it, every
//! Newton update keeps it (b₁ = 0, x₁ = dh x₂). So Newton starts from a guess that satisfies it
//! and iterates on the velocities alone, and K b₁ is never formed; on a sudden load that product
//! was a sixth of a run.
//!
//! A body riding on the structure makes M(z) = B + Σ w g gᵀ move with it (see
//! [`super::second_order::Structure::mass_split`]). The iteration matrix is factorised from B
//! alone and the body's few terms are added at every step's start by the Woodbury identity, as
//! generalized-α does. Factorised whole, the body's inertia stayed where the factorisation
//! found it: on D44, where the disk outweighs the beam under its patch fifteenfold, Newton then
//! contracted by only 0.3–0.9 a step later, and one step in three refreshed its Jacobian.

use std::borrow::Cow;

use super::{Attempt, Ctx, Dynamics, SolveError, StepEnds, Stepper, SAFETY};
use crate::linalg::{self, Assembly, JointSum, Sparse, SparseLu, Woodbury};

const MAX_NEWTON: usize = 8;
/// Newton stops when its predicted remaining error is this fraction of the local tolerance.
const NEWTON_KAPPA: f64 = 0.01;

/// The state every diagonally implicit method here shares: the two ends of the last accepted
/// step (its dense output is their cubic Hermite), the stage solver, and the candidate of the
/// last attempt.
pub(crate) struct DirkState {
    pub ends: StepEnds,
    pub newton: StageSolver,
    /// y and y' at the end of the last attempt.
    pub y_new: Vec<f64>,
    pub yp_new: Vec<f64>,
}

/// What distinguishes one diagonally implicit method from another: its stages and its error
/// estimate.
pub(crate) trait DirkMethod {
    /// The order of the embedded error estimate.
    fn error_order(&self) -> u32;
    /// All stages of a step of size h from (t, y), leaving y_new and yp_new in `s`; false if
    /// Newton failed on one of them.
    fn stages(
        &mut self,
        s: &mut DirkState,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<bool, SolveError>;
    /// The local error estimate of the stages just solved.
    fn estimate(&mut self, s: &DirkState, p: &dyn Dynamics, t: f64, h: f64) -> Vec<f64>;
}

/// A diagonally implicit method as a stepper.
pub(crate) struct Dirk<M> {
    method: M,
    s: DirkState,
    t_try: f64,
    h_try: f64,
}

impl<M: DirkMethod> Dirk<M> {
    pub fn new(method: M, n: usize) -> Self {
        Dirk {
            method,
            s: DirkState {
                ends: StepEnds::new(n),
                newton: StageSolver::new(n),
                y_new: vec![0.0; n],
                yp_new: vec![0.0; n],
            },
            t_try: 0.0,
            h_try: 0.0,
        }
    }

    /// The stages of a step; if Newton fails on a Jacobian from an earlier step, once more
    /// with a Jacobian evaluated at (t, y). False if that fails too: the driver then shrinks
    /// the step.
    fn solve_stages(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<bool, SolveError> {
        if self.method.stages(&mut self.s, p, t, y, h, ctx)? {
            return Ok(true);
        }
        if self.s.newton.jac_fresh {
            return Ok(false);
        }
        self.s.newton.refresh_jacobian(p, t, y, ctx);
        self.method.stages(&mut self.s, p, t, y, h, ctx)
    }
}

impl<M: DirkMethod> Stepper for Dirk<M> {
    fn error_order(&self) -> u32 {
        self.method.error_order()
    }

    fn start(
        &mut self,
        p: &dyn Dynamics,
        t0: f64,
        y0: &[f64],
        ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        self.s.ends.start(p, t0, y0, ctx)?;
        self.s.newton.refresh_jacobian(p, t0, y0, ctx);
        Ok(())
    }

    fn attempt(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<Attempt, SolveError> {
        if !self.solve_stages(p, t, y, h, ctx)? {
            return Ok(Attempt::NewtonFailed);
        }
        let err = self.method.estimate(&self.s, p, t, h);
        self.t_try = t;
        self.h_try = h;
        Ok(Attempt::Done {
            err: ctx.norm(&err, y, &self.s.y_new),
        })
    }

    fn y_new(&self) -> &[f64] {
        &self.s.y_new
    }

    fn accept(&mut self, _t_new: f64) {
        let s = &mut self.s;
        s.ends.accept(self.t_try, self.h_try, &s.y_new, &s.yp_new);
        s.newton.jac_fresh = false;
    }

    fn interpolate(&self, t: f64, out: &mut [f64]) {
        self.s.ends.interpolate(t, out);
    }

    fn interpolate_rate(&self, t: f64, out: &mut [f64]) {
        self.s.ends.interpolate_rate(t, out);
    }

    fn rate_from_the_problem(&self) -> bool {
        true
    }

    /// Keep the factorised iteration matrix while the step would grow by less than 20 %, or
    /// shrink by no more than the controller's safety factor 0.9: a refactorisation costs
    /// more than the few steps a slightly larger h saves, and a proposal of 0.9 h or more
    /// comes from an error within tolerance at h, so h itself is expected to pass again. On
    /// B3 (ESDIRK4, rtol 3·10⁻⁴, 8 elements) the lower bound 1.0 refactorised at 5229 of
    /// 13 326 steps, 0.9 at 1614 of 12 144.
    fn keep_step(&self, h_old: f64, h_new: f64) -> f64 {
        if (SAFETY..=1.2).contains(&(h_new / h_old)) {
            h_old
        } else {
            h_new
        }
    }
}

/// The Jacobian Newton iterates with.
enum Tangent {
    /// ∂f/∂y of a general problem.
    Full(Sparse),
    /// The tangent stiffness K of a structure in its first-order view, whose Jacobian is
    /// [[0, I], [−K, −C]] (C constant, from the structure).
    Structural(Sparse),
}

/// out = M(t, y) x, through the structure's own product where the problem is one.
pub(crate) fn mass_mul(p: &dyn Dynamics, t: f64, y: &[f64], x: &[f64], out: &mut [f64]) {
    if let Some(s) = p.second_order() {
        let n = s.dim();
        out[..n].copy_from_slice(&x[..n]);
        s.mass_mul(t, &y[..n], &x[n..], &mut out[n..]);
        return;
    }
    match p.mass(t, y) {
        Some(m) => linalg::mul(&m, x, out),
        None => out.copy_from_slice(x),
    }
}

pub(crate) struct StageSolver {
    jac: Option<Tangent>,
    /// The Jacobian was evaluated at the current step start.
    pub jac_fresh: bool,
    /// Factorised M − d h J and the d h it was built for.
    iteration: Option<(f64, SparseLu)>,
    /// The factorisation is of an earlier Jacobian: only its symbolic analysis serves.
    iteration_stale: bool,
    /// With a split mass: the rider's terms at the step's start, added by Woodbury to the
    /// factorisation of the constant part.
    woodbury: Option<Woodbury>,
    pattern: JointSum,
    /// Newton contraction estimate carried between solves (Hairer & Wanner IV.8).
    eta: f64,
    f: Vec<f64>,
    g: Vec<f64>,
    /// Scratch for M g and, on a structure, K b₁.
    scratch: std::cell::RefCell<Vec<f64>>,
}

impl StageSolver {
    pub fn new(n: usize) -> Self {
        StageSolver {
            jac: None,
            jac_fresh: false,
            iteration: None,
            iteration_stale: false,
            woodbury: None,
            pattern: JointSum::default(),
            eta: 1.0,
            f: vec![0.0; n],
            g: vec![0.0; n],
            scratch: std::cell::RefCell::new(vec![0.0; n]),
        }
    }

    pub fn refresh_jacobian(&mut self, p: &dyn Dynamics, t: f64, y: &[f64], ctx: &mut Ctx) {
        self.jac = Some(match p.second_order() {
            Some(s) => {
                ctx.stats.jacobians += 1;
                Tangent::Structural(s.stiffness(t, &y[..s.dim()]))
            }
            None => {
                ctx.rhs(p, t, y, &mut self.f);
                let f0 = self.f.clone();
                Tangent::Full(ctx.jacobian(p, t, y, &f0))
            }
        });
        self.jac_fresh = true;
        self.iteration_stale = true;
    }

    /// Factorise M(t, y) − d h J unless the factorisation for this d h is at hand; with a split
    /// mass, factorise it with the constant part in M's place and add the rider's terms where
    /// the rider is now.
    pub fn factor(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        dh: f64,
        ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        let split = match (&self.jac, p.second_order()) {
            (Some(Tangent::Structural(_)), Some(s)) => s.mass_split(t, &y[..s.dim()]),
            _ => None,
        };
        let (base, rider) = split.unzip();
        self.factor_whole_or_base(p, t, y, dh, base, ctx)?;
        self.woodbury = match rider {
            Some(terms) => {
                let (_, lu) = self.iteration.as_ref().expect("factorised above");
                Some(Woodbury::new(lu, terms).ok_or(SolveError::SingularMatrix { t })?)
            }
            None => None,
        };
        Ok(())
    }

    /// M(t, y) − d h J factorised, or with `base` the constant part of a split mass in M's
    /// place; kept while the Jacobian and d h are those it was built for.
    fn factor_whole_or_base(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        dh: f64,
        base: Option<&Sparse>,
        ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        if !self.iteration_stale && matches!(self.iteration, Some((d, _)) if d == dh) {
            return Ok(());
        }
        let jac = self
            .jac
            .as_ref()
            .expect("the Jacobian is evaluated before the first factorisation");
        let w = match jac {
            Tangent::Full(jac) => {
                let n = y.len();
                let mass = p.mass(t, y).unwrap_or_else(|| {
                    let mut identity = Assembly::new(n);
                    (0..n).for_each(|i| identity.add(i, i, 1.0));
                    identity.build()
                });
                self.pattern.combine(&[(&mass, 1.0), (jac, -dh)])
            }
            Tangent::Structural(k) => {
                let s = p
                    .second_order()
                    .expect("a structural tangent comes from a structure");
                let mass = match base {
                    Some(b) => Cow::Borrowed(b),
                    None => s.mass(t, &y[..s.dim()]),
                };
                let damping = s.damping();
                let mut parts = vec![(mass.as_ref(), 1.0), (k, dh * dh)];
                parts.extend(damping.as_deref().map(|c| (c, dh)));
                self.pattern.combine(&parts)
            }
        };
        ctx.stats.factorizations += 1;
        let previous = self.iteration.take().map(|(_, lu)| lu);
        let lu = SparseLu::factor(&w, previous).ok_or(SolveError::SingularMatrix { t })?;
        self.iteration = Some((dh, lu));
        self.iteration_stale = false;
        Ok(())
    }

    /// x ← (M + dh C + dh² K)⁻¹ x, the structure's reduced iteration matrix (or the whole one
    /// of a general problem), with the rider's terms where the mass is split.
    fn solve_factorised(&self, x: &mut [f64]) {
        let (_, lu) = self.iteration.as_ref().expect("factorised before use");
        match &self.woodbury {
            Some(w) => w.solve_in_place(lu, x),
            None => lu.solve_in_place(x),
        }
    }

    /// Solve M(z)(z − base) = d h f(t, z) for z, from the guess in `z`; false if Newton does
    /// not converge.
    pub fn solve(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        base: &[f64],
        z: &mut [f64],
        dh: f64,
        ctx: &mut Ctx,
    ) -> bool {
        let n = z.len();
        let structure = match &self.jac {
            Some(Tangent::Structural(k)) => Some(k.nrows()),
            _ => None,
        };
        if let Some(m) = structure {
            kinematic(base, z, dh, m);
        }
        let mut eta = self.eta.max(f64::EPSILON).powf(0.8);
        let mut prev: Option<f64> = None;
        for k in 0..MAX_NEWTON {
            ctx.stats.newton_iterations += 1;
            ctx.rhs(p, t, z, &mut self.f);
            for i in 0..n {
                self.g[i] = z[i] - base[i];
            }
            {
                let mut mg = self.scratch.borrow_mut();
                mass_mul(p, t, z, &self.g, &mut mg);
                for i in 0..n {
                    self.g[i] = -(mg[i] - dh * self.f[i]);
                }
            }
            let mut g = std::mem::take(&mut self.g);
            match structure {
                Some(m) => self.velocity_correction(&mut g, m),
                None => self.back_substitute(&mut g),
            }
            self.g = g;
            for i in 0..n {
                z[i] += self.g[i];
            }
            if let Some(m) = structure {
                kinematic(base, z, dh, m);
            }
            let norm = ctx.unknowns_norm(&self.g, z, z);
            if !norm.is_finite() {
                return false;
            }
            if let Some(prev) = prev {
                let theta = norm / prev;
                if theta >= 0.99 {
                    return false;
                }
                eta = theta / (1.0 - theta);
                let remaining = MAX_NEWTON - 1 - k;
                if theta.powi(remaining as i32) / (1.0 - theta) * norm > NEWTON_KAPPA {
                    return false;
                }
            }
            if eta * norm <= NEWTON_KAPPA || norm <= 1e-3 * NEWTON_KAPPA {
                self.eta = eta;
                return true;
            }
            prev = Some(norm);
        }
        false
    }

    /// x ← (M − d h J)⁻¹ x on a structure's factorisation where x₁ = 0 (an iterate that
    /// satisfies the kinematic row): x₂ from the reduced matrix, x₁ = d h x₂.
    fn velocity_correction(&self, x: &mut [f64], m: usize) {
        let dh = self.iteration.as_ref().expect("factorised before use").0;
        let (x1, x2) = x.split_at_mut(m);
        self.solve_factorised(x2);
        for (a, b) in x1.iter_mut().zip(x2.iter()) {
            *a = dh * b;
        }
    }

    /// x ← (M − d h J)⁻¹ x on the current factorisation.
    pub fn back_substitute(&self, x: &mut [f64]) {
        let dh = self.iteration.as_ref().expect("factorised before use").0;
        match &self.jac {
            Some(Tangent::Structural(k)) => {
                let n = k.nrows();
                let (b1, b2) = x.split_at_mut(n);
                let mut scratch = self.scratch.borrow_mut();
                let kb = &mut scratch[..n];
                linalg::mul(k, b1, kb);
                for (b, kb) in b2.iter_mut().zip(kb.iter()) {
                    *b -= dh * kb;
                }
                self.solve_factorised(b2);
                for (a, b) in b1.iter_mut().zip(b2.iter()) {
                    *a += dh * b;
                }
            }
            _ => self.solve_factorised(x),
        }
    }
}

/// q = base_q + d h v: the stage's kinematic row, which a structure's iterate is kept on.
fn kinematic(base: &[f64], z: &mut [f64], dh: f64, m: usize) {
    let (q, v) = z.split_at_mut(m);
    for ((q, b), v) in q.iter_mut().zip(&base[..m]).zip(v.iter()) {
        *q = b + dh * v;
    }
}

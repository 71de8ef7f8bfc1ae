//! The implicit stage of a diagonally implicit Runge–Kutta method with a mass matrix:
//! M(z)(z − base) = d h f(t, z), solved by simplified Newton on the iteration matrix M − d h J.
//!
//! Both TR-BDF2 and the ESDIRK have one diagonal coefficient d for every implicit stage, so one
//! factorised M − d h J serves every stage of a step, and is kept across steps for as long as
//! Newton converges with it. A failure first refreshes the Jacobian; the stepper then halves
//! the step.

use super::{Ctx, Dynamics, SolveError};
use crate::linalg::{self, Assembly, Sparse, SparseLu};

const MAX_NEWTON: usize = 8;
/// Newton stops when its predicted remaining error is this fraction of the local tolerance.
const NEWTON_KAPPA: f64 = 0.01;

/// A stepper whose implicit stages a [`StageSolver`] solves.
pub(crate) trait ImplicitStages {
    fn newton(&mut self) -> &mut StageSolver;
    /// All stages of a step of size h from (t, y); false if Newton failed on one of them.
    fn stages(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<bool, SolveError>;
}

/// The stages of a step; if Newton fails on a Jacobian from an earlier step, once more with a
/// Jacobian evaluated at (t, y). False if that fails too: the driver then shrinks the step.
pub(crate) fn solve_stages(
    s: &mut impl ImplicitStages,
    p: &dyn Dynamics,
    t: f64,
    y: &[f64],
    h: f64,
    ctx: &mut Ctx,
) -> Result<bool, SolveError> {
    if s.stages(p, t, y, h, ctx)? {
        return Ok(true);
    }
    if s.newton().jac_fresh {
        return Ok(false);
    }
    s.newton().refresh_jacobian(p, t, y, ctx);
    s.stages(p, t, y, h, ctx)
}

pub(crate) struct StageSolver {
    jac: Option<Sparse>,
    /// The Jacobian was evaluated at the current step start.
    pub jac_fresh: bool,
    /// Factorised M − d h J and the d h it was built for.
    iteration: Option<(f64, SparseLu)>,
    /// Newton contraction estimate carried between solves (Hairer & Wanner IV.8).
    eta: f64,
    f: Vec<f64>,
    g: Vec<f64>,
}

impl StageSolver {
    pub fn new(n: usize) -> Self {
        StageSolver {
            jac: None,
            jac_fresh: false,
            iteration: None,
            eta: 1.0,
            f: vec![0.0; n],
            g: vec![0.0; n],
        }
    }

    pub fn refresh_jacobian(&mut self, p: &dyn Dynamics, t: f64, y: &[f64], ctx: &mut Ctx) {
        ctx.rhs(p, t, y, &mut self.f);
        let f0 = self.f.clone();
        self.jac = Some(ctx.jacobian(p, t, y, &f0));
        self.jac_fresh = true;
        self.iteration = None;
    }

    /// Factorise M(t, y) − d h J unless the factorisation for this d h is at hand.
    pub fn factor(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        dh: f64,
        ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        if matches!(self.iteration, Some((d, _)) if d == dh) {
            return Ok(());
        }
        let jac = self
            .jac
            .as_ref()
            .expect("the Jacobian is evaluated before the first factorisation");
        let n = y.len();
        let mut w = Assembly::new(n);
        match p.mass(t, y) {
            Some(m) => w.add_sparse(&m, 1.0, 0, 0),
            None => (0..n).for_each(|i| w.add(i, i, 1.0)),
        }
        w.add_sparse(jac, -dh, 0, 0);
        ctx.stats.factorizations += 1;
        let previous = self.iteration.take().map(|(_, lu)| lu);
        let lu = SparseLu::factor(&w.build(), previous).ok_or(SolveError::SingularMatrix { t })?;
        self.iteration = Some((dh, lu));
        Ok(())
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
        let mut eta = self.eta.max(f64::EPSILON).powf(0.8);
        let mut prev: Option<f64> = None;
        for k in 0..MAX_NEWTON {
            ctx.stats.newton_iterations += 1;
            ctx.rhs(p, t, z, &mut self.f);
            for i in 0..n {
                self.g[i] = z[i] - base[i];
            }
            if let Some(m) = p.mass(t, z) {
                let g = self.g.clone();
                linalg::mul(&m, &g, &mut self.g);
            }
            for i in 0..n {
                self.g[i] = -(self.g[i] - dh * self.f[i]);
            }
            let (_, lu) = self.iteration.as_ref().expect("factorised before Newton");
            lu.solve_in_place(&mut self.g);
            for i in 0..n {
                z[i] += self.g[i];
            }
            let norm = ctx.norm(&self.g, z, z);
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

    /// x ← (M − d h J)⁻¹ x on the current factorisation.
    pub fn back_substitute(&self, x: &mut [f64]) {
        let (_, lu) = self.iteration.as_ref().expect("factorised before use");
        lu.solve_in_place(x);
    }
}

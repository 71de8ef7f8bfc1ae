//! TR-BDF2 (Bank et al. 1985; Hosea & Shampine 1996, Matlab's ode23tb): a trapezoidal stage to
//! t + γh and a BDF2 stage to t + h, with γ = 2 − √2 so that both stages share the iteration
//! matrix M − d h J (d = γ/2). One-step, L-stable, second order; the error estimate is the
//! method's leading truncation term C h³ y''' with y''' from the three stage derivatives.
//!
//! Newton reuses the Jacobian and the factorised iteration matrix across steps for as long as it
//! converges; a failure first refreshes the Jacobian, then halves the step (twice).

use super::{Attempt, Ctx, Problem, SolveError, Stepper};
use crate::linalg::{self, Assembly, Sparse, SparseLu};

const GAMMA: f64 = 2.0 - std::f64::consts::SQRT_2;
const D: f64 = GAMMA / 2.0;
/// Local error constant of TR-BDF2: (−3γ² + 4γ − 2) / (12 (2 − γ)) ≈ −0.0404.
const ERR_CONST: f64 = (-3.0 * GAMMA * GAMMA + 4.0 * GAMMA - 2.0) / (12.0 * (2.0 - GAMMA));
const MAX_NEWTON: usize = 8;
/// Newton stops when its predicted remaining error is this fraction of the local tolerance.
const NEWTON_KAPPA: f64 = 0.01;

pub struct TrBdf2 {
    y_old: Vec<f64>,
    yp_old: Vec<f64>,
    /// Start of the last accepted step, for dense output.
    prev_y: Vec<f64>,
    prev_yp: Vec<f64>,
    y_gamma: Vec<f64>,
    yp_gamma: Vec<f64>,
    y_new: Vec<f64>,
    yp_new: Vec<f64>,
    t_old: f64,
    h: f64,
    t_try: f64,
    h_try: f64,
    jac: Option<Sparse>,
    /// The Jacobian was evaluated at the current step start.
    jac_fresh: bool,
    /// Factorised M − d h J and the d h it was built for.
    iteration: Option<(f64, SparseLu)>,
    /// Newton contraction estimate carried between solves (Hairer & Wanner IV.8).
    eta: f64,
    f: Vec<f64>,
    g: Vec<f64>,
}

impl TrBdf2 {
    pub fn new(n: usize) -> Self {
        let z = || vec![0.0; n];
        TrBdf2 {
            y_old: z(),
            yp_old: z(),
            prev_y: z(),
            prev_yp: z(),
            y_gamma: z(),
            yp_gamma: z(),
            y_new: z(),
            yp_new: z(),
            t_old: 0.0,
            h: 0.0,
            t_try: 0.0,
            h_try: 0.0,
            jac: None,
            jac_fresh: false,
            iteration: None,
            eta: 1.0,
            f: z(),
            g: z(),
        }
    }

    fn refresh_jacobian(&mut self, p: &dyn Problem, t: f64, y: &[f64], ctx: &mut Ctx) {
        ctx.rhs(p, t, y, &mut self.f);
        let f0 = self.f.clone();
        self.jac = Some(ctx.jacobian(p, t, y, &f0));
        self.jac_fresh = true;
        self.iteration = None;
    }

    fn factor(
        &mut self,
        p: &dyn Problem,
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

    /// Solve M(z)(z − base) = d h f(t, z) for z, from the guess in `z`.
    fn newton(
        &mut self,
        p: &dyn Problem,
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

    fn stages(
        &mut self,
        p: &dyn Problem,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<bool, SolveError> {
        let n = y.len();
        let dh = D * h;
        self.factor(p, t, y, dh, ctx)?;
        // Trapezoidal stage: z = y + d h (y'_n + y'_γ).
        let base: Vec<f64> = (0..n).map(|i| y[i] + dh * self.yp_old[i]).collect();
        let mut z: Vec<f64> = (0..n).map(|i| y[i] + GAMMA * h * self.yp_old[i]).collect();
        if !self.newton(p, t + GAMMA * h, &base, &mut z, dh, ctx) {
            return Ok(false);
        }
        for i in 0..n {
            self.yp_gamma[i] = (z[i] - base[i]) / dh;
        }
        self.y_gamma.copy_from_slice(&z);
        // BDF2 stage through y_n, y_γ, y_{n+1}.
        let w1 = 1.0 / (GAMMA * (2.0 - GAMMA));
        let w0 = (1.0 - GAMMA).powi(2) / (GAMMA * (2.0 - GAMMA));
        let base: Vec<f64> = (0..n).map(|i| w1 * self.y_gamma[i] - w0 * y[i]).collect();
        for i in 0..n {
            z[i] = self.y_gamma[i] + (1.0 - GAMMA) * h * self.yp_gamma[i];
        }
        if !self.newton(p, t + h, &base, &mut z, dh, ctx) {
            return Ok(false);
        }
        for i in 0..n {
            self.yp_new[i] = (z[i] - base[i]) / dh;
        }
        self.y_new.copy_from_slice(&z);
        Ok(true)
    }
}

impl Stepper for TrBdf2 {
    fn error_order(&self) -> u32 {
        2
    }

    fn start(
        &mut self,
        p: &dyn Problem,
        t0: f64,
        y0: &[f64],
        ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        self.y_old.copy_from_slice(y0);
        ctx.derivative(p, t0, y0, &mut self.yp_old)?;
        self.refresh_jacobian(p, t0, y0, ctx);
        Ok(())
    }

    fn attempt(
        &mut self,
        p: &dyn Problem,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<Attempt, SolveError> {
        if !self.stages(p, t, y, h, ctx)? {
            if self.jac_fresh {
                return Ok(Attempt::NewtonFailed);
            }
            self.refresh_jacobian(p, t, y, ctx);
            if !self.stages(p, t, y, h, ctx)? {
                return Ok(Attempt::NewtonFailed);
            }
        }
        let n = y.len();
        let err: Vec<f64> = (0..n)
            .map(|i| {
                let upper = (self.yp_new[i] - self.yp_gamma[i]) / (1.0 - GAMMA);
                let lower = (self.yp_gamma[i] - self.yp_old[i]) / GAMMA;
                2.0 * ERR_CONST * h * (upper - lower)
            })
            .collect();
        self.t_try = t;
        self.h_try = h;
        Ok(Attempt::Done {
            err: ctx.norm(&err, y, &self.y_new),
        })
    }

    fn y_new(&self) -> &[f64] {
        &self.y_new
    }

    fn accept(&mut self) {
        self.t_old = self.t_try;
        self.h = self.h_try;
        std::mem::swap(&mut self.prev_y, &mut self.y_old);
        std::mem::swap(&mut self.prev_yp, &mut self.yp_old);
        self.y_old.copy_from_slice(&self.y_new);
        self.yp_old.copy_from_slice(&self.yp_new);
        self.jac_fresh = false;
    }

    fn interpolate(&self, t: f64, out: &mut [f64]) {
        // Cubic Hermite on (y, y') at both ends of the step: third order, above the method's.
        let h = self.h;
        let th = (t - self.t_old) / h;
        let h00 = (1.0 + 2.0 * th) * (1.0 - th).powi(2);
        let h10 = th * (1.0 - th).powi(2);
        let h01 = th * th * (3.0 - 2.0 * th);
        let h11 = th * th * (th - 1.0);
        for (i, o) in out.iter_mut().enumerate() {
            *o = h00 * self.prev_y[i]
                + h * h10 * self.prev_yp[i]
                + h01 * self.y_old[i]
                + h * h11 * self.yp_old[i];
        }
    }

    fn keep_step(&self, h_old: f64, h_new: f64) -> f64 {
        if (1.0..=1.2).contains(&(h_new / h_old)) {
            h_old
        } else {
            h_new
        }
    }
}

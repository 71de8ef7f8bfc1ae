//! TR-BDF2 (Bank et al. 1985; Hosea & Shampine 1996, Matlab's ode23tb): a trapezoidal stage to
//! t + γh and a BDF2 stage to t + h, with γ = 2 − √2 so that both stages share the iteration
//! matrix M − d h J (d = γ/2). One-step, L-stable, second order; the error estimate is the
//! method's leading truncation term C h³ y''' with y''' from the three stage derivatives.
//!
//! The implicit stages are solved by [`StageSolver`].

use super::stage_solver::{solve_stages, ImplicitStages, StageSolver};
use super::{Attempt, Ctx, Dynamics, SolveError, StepEnds, Stepper};

const GAMMA: f64 = 2.0 - std::f64::consts::SQRT_2;
const D: f64 = GAMMA / 2.0;
/// Local error constant of TR-BDF2: (−3γ² + 4γ − 2) / (12 (2 − γ)) ≈ −0.0404.
const ERR_CONST: f64 = (-3.0 * GAMMA * GAMMA + 4.0 * GAMMA - 2.0) / (12.0 * (2.0 - GAMMA));

pub struct TrBdf2 {
    ends: StepEnds,
    y_gamma: Vec<f64>,
    yp_gamma: Vec<f64>,
    y_new: Vec<f64>,
    yp_new: Vec<f64>,
    t_try: f64,
    h_try: f64,
    newton: StageSolver,
}

impl TrBdf2 {
    pub fn new(n: usize) -> Self {
        let z = || vec![0.0; n];
        TrBdf2 {
            ends: StepEnds::new(n),
            y_gamma: z(),
            yp_gamma: z(),
            y_new: z(),
            yp_new: z(),
            t_try: 0.0,
            h_try: 0.0,
            newton: StageSolver::new(n),
        }
    }
}

impl ImplicitStages for TrBdf2 {
    fn newton(&mut self) -> &mut StageSolver {
        &mut self.newton
    }

    fn stages(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<bool, SolveError> {
        let n = y.len();
        let dh = D * h;
        self.newton.factor(p, t, y, dh, ctx)?;
        // Trapezoidal stage: z = y + d h (y'_n + y'_γ).
        let base: Vec<f64> = (0..n).map(|i| y[i] + dh * self.ends.yp[i]).collect();
        let mut z: Vec<f64> = (0..n).map(|i| y[i] + GAMMA * h * self.ends.yp[i]).collect();
        if !self.newton.solve(p, t + GAMMA * h, &base, &mut z, dh, ctx) {
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
        if !self.newton.solve(p, t + h, &base, &mut z, dh, ctx) {
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
        p: &dyn Dynamics,
        t0: f64,
        y0: &[f64],
        ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        self.ends.start(p, t0, y0, ctx)?;
        self.newton.refresh_jacobian(p, t0, y0, ctx);
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
        if !solve_stages(self, p, t, y, h, ctx)? {
            return Ok(Attempt::NewtonFailed);
        }
        let n = y.len();
        let err: Vec<f64> = (0..n)
            .map(|i| {
                let upper = (self.yp_new[i] - self.yp_gamma[i]) / (1.0 - GAMMA);
                let lower = (self.yp_gamma[i] - self.ends.yp[i]) / GAMMA;
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
        self.ends
            .accept(self.t_try, self.h_try, &self.y_new, &self.yp_new);
        self.newton.jac_fresh = false;
    }

    fn interpolate(&self, t: f64, out: &mut [f64]) {
        self.ends.interpolate(t, out);
    }

    fn keep_step(&self, h_old: f64, h_new: f64) -> f64 {
        super::keep_factorisation(h_old, h_new)
    }
}

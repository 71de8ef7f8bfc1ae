//! ESDIRK4(3)6L[2]SA (Kennedy & Carpenter 2003, the implicit half of their ARK4(3)6L[2]SA): six
//! stages, an explicit first stage, one diagonal coefficient γ = 1/4, fourth order with a
//! third-order embedded solution. L-stable and stiffly accurate: the last stage is the new
//! solution, so the stiff modes a step does not resolve are damped out rather than carried, and
//! the last stage derivative starts the next step.
//!
//! The higher order is what a tight tolerance asks for: against TR-BDF2 the steps grow as
//! tol^(−1/4) instead of tol^(−1/3) per unit of accuracy. The implicit stages are solved by
//! the shared stage solver (`stage_solver.rs`) on the one iteration matrix M − γ h J; the
//! error estimate is filtered through it (Hairer & Wanner IV.8), so that stiff components do
//! not reject steps whose error they do not carry.

use super::stage_solver::{mass_mul, DirkMethod, DirkState};
use super::{Ctx, Dynamics, SolveError};

const STAGES: usize = 6;
const GAMMA: f64 = 0.25;
pub(crate) const C: [f64; STAGES] = [0.0, 0.5, 83.0 / 250.0, 31.0 / 50.0, 17.0 / 20.0, 1.0];
pub(crate) const A: [[f64; STAGES]; STAGES] = [
    [0.0; STAGES],
    [0.25, 0.25, 0.0, 0.0, 0.0, 0.0],
    [8611.0 / 62500.0, -1743.0 / 31250.0, 0.25, 0.0, 0.0, 0.0],
    [
        5012029.0 / 34652500.0,
        -654441.0 / 2922500.0,
        174375.0 / 388108.0,
        0.25,
        0.0,
        0.0,
    ],
    [
        15267082809.0 / 155376265600.0,
        -71443401.0 / 120774400.0,
        730878875.0 / 902184768.0,
        2285395.0 / 8070912.0,
        0.25,
        0.0,
    ],
    [
        82889.0 / 524892.0,
        0.0,
        15625.0 / 83664.0,
        69875.0 / 102672.0,
        -2260.0 / 8211.0,
        0.25,
    ],
];
/// Weights of the third-order embedded solution (those of the method are the last row of A).
pub(crate) const B_HAT: [f64; STAGES] = [
    4586570599.0 / 29645900160.0,
    0.0,
    178811875.0 / 945068544.0,
    814220225.0 / 1159782912.0,
    -3700637.0 / 11593932.0,
    61727.0 / 225920.0,
];

pub struct Esdirk4 {
    /// Stage derivatives k_i = y'(t + c_i h) of the last attempt.
    k: [Vec<f64>; STAGES],
    base: Vec<f64>,
}

impl Esdirk4 {
    pub fn new(n: usize) -> Self {
        Esdirk4 {
            k: std::array::from_fn(|_| vec![0.0; n]),
            base: vec![0.0; n],
        }
    }
}

impl DirkMethod for Esdirk4 {
    fn error_order(&self) -> u32 {
        3
    }

    /// The five implicit stages after the explicit first.
    fn stages(
        &mut self,
        s: &mut DirkState,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<bool, SolveError> {
        let n = y.len();
        let dh = GAMMA * h;
        s.newton.factor(p, t, y, dh, ctx)?;
        self.k[0].copy_from_slice(&s.ends.yp);
        let mut z = vec![0.0; n];
        for i in 1..STAGES {
            for r in 0..n {
                self.base[r] = y[r] + h * (0..i).map(|j| A[i][j] * self.k[j][r]).sum::<f64>();
                // Predictor: the previous stage's slope carried to this stage's time.
                z[r] = self.base[r] + dh * self.k[i - 1][r];
            }
            if !s.newton.solve(p, t + C[i] * h, &self.base, &mut z, dh, ctx) {
                return Ok(false);
            }
            for r in 0..n {
                self.k[i][r] = (z[r] - self.base[r]) / dh;
            }
        }
        s.y_new.copy_from_slice(&z);
        s.yp_new.copy_from_slice(&self.k[STAGES - 1]);
        Ok(true)
    }

    /// ŷ − y from the embedded weights, filtered as (M − γ h J) e = M (y − ŷ).
    fn estimate(&mut self, s: &DirkState, p: &dyn Dynamics, t: f64, h: f64) -> Vec<f64> {
        let n = s.y_new.len();
        for r in 0..n {
            self.base[r] = h
                * (0..STAGES)
                    .map(|j| (A[STAGES - 1][j] - B_HAT[j]) * self.k[j][r])
                    .sum::<f64>();
        }
        let mut err = vec![0.0; n];
        mass_mul(p, t + h, &s.y_new, &self.base, &mut err);
        s.newton.back_substitute(&mut err);
        err
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tableau as transcribed satisfies the order conditions: rows sum to c, the method to
    /// order 4 (the eight conditions), the embedding to order 3 but not 4; the method is
    /// stiffly accurate and its stability function vanishes at infinity (L-stable).
    #[test]
    fn order_conditions() {
        let b = A[STAGES - 1];
        for i in 0..STAGES {
            assert!((A[i].iter().sum::<f64>() - C[i]).abs() < 1e-14, "row {i}");
        }
        let ac = |v: &[f64; STAGES]| -> [f64; STAGES] {
            std::array::from_fn(|i| (0..STAGES).map(|j| A[i][j] * v[j]).sum())
        };
        let dot = |u: &[f64; STAGES], v: &[f64; STAGES]| -> f64 {
            u.iter().zip(v).map(|(a, b)| a * b).sum()
        };
        let ones = [1.0; STAGES];
        let c2: [f64; STAGES] = std::array::from_fn(|i| C[i] * C[i]);
        let c3: [f64; STAGES] = std::array::from_fn(|i| C[i].powi(3));
        let a_c = ac(&C);
        let a_c2 = ac(&c2);
        let a_a_c = ac(&a_c);
        let c_ac: [f64; STAGES] = std::array::from_fn(|i| C[i] * a_c[i]);
        let conditions = |w: &[f64; STAGES]| {
            [
                dot(w, &ones) - 1.0,
                dot(w, &C) - 0.5,
                dot(w, &c2) - 1.0 / 3.0,
                dot(w, &a_c) - 1.0 / 6.0,
                dot(w, &c3) - 0.25,
                dot(w, &c_ac) - 0.125,
                dot(w, &a_c2) - 1.0 / 12.0,
                dot(w, &a_a_c) - 1.0 / 24.0,
            ]
        };
        for (k, r) in conditions(&b).iter().enumerate() {
            assert!(r.abs() < 1e-13, "method condition {k}: {r:e}");
        }
        let embedded = conditions(&B_HAT);
        for (k, r) in embedded[..4].iter().enumerate() {
            assert!(r.abs() < 1e-13, "embedding condition {k}: {r:e}");
        }
        assert!(embedded[4..].iter().any(|r| r.abs() > 1e-4));
        // R(z) = 1 + z bᵀ (I − z A)⁻¹ 1 by forward substitution (A is lower triangular):
        // it must vanish as z → −∞ (L-stability) and stay within the unit disc on iℝ.
        let r = |z: f64, im: f64| -> f64 {
            let z = nalgebra::Complex::new(z, im);
            let mut x = [nalgebra::Complex::new(0.0, 0.0); STAGES];
            for i in 0..STAGES {
                let s: nalgebra::Complex<f64> = (0..i).map(|j| z * A[i][j] * x[j]).sum();
                x[i] = (s + 1.0) / (1.0 - z * A[i][i]);
            }
            let sum: nalgebra::Complex<f64> = (0..STAGES).map(|j| b[j] * x[j]).sum();
            (1.0 + z * sum).norm()
        };
        assert!(r(-1e8, 0.0) < 1e-6, "R(-1e8) = {}", r(-1e8, 0.0));
        for w in [0.1, 1.0, 10.0, 100.0, 1e4] {
            assert!(r(0.0, w) <= 1.0 + 1e-12, "|R({w} i)| = {}", r(0.0, w));
        }
    }
}

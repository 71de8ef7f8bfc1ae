//! The thesis' system (Table 1): unknowns (X_T, Y_T, v_x, s, φ, Ω_z) and M_D(y) y' = F_D(y),
//!   [D1]  e_tX Ẋ_T + e_tY Ẏ_T = v_x          centre velocity along the tangent
//!   [D2] −e_tY Ẋ_T + e_tX Ẏ_T = 0            … and none along the normal
//!   [D3]  v̇_x + a Ω̇ = 0                     no slip, differentiated
//!   [D4] −m a v̇_x + C Ω̇ = m g a e_tY        angular momentum with R_t eliminated
//!   [D5]  ψ' ṡ + φ̇ = Ω                       ψ' in curvature form (erratum 1)
//!   [D6]  Ẋ_T + (a e_tY' − X') ṡ = 0         the centre stays on the offset curve
//! with e_tY' = ψ' e_tX. The reactions follow from (3.6) with erratum 2.

use nalgebra::{DMatrix, DVector};

use super::StopReason;
use super::{DiskObservation, Rolling, RollingModel};
use crate::ode::{Dynamics, EventSpec, Problem};

pub struct Thesis {
    pub rolling: Rolling,
}

impl Thesis {
    fn mass_matrix(&self, y: &[f64]) -> DMatrix<f64> {
        let p = self.rolling.curve.at(y[3]);
        let [tx, ty] = p.tangent();
        let a = self.rolling.disk.radius;
        let m = self.rolling.disk.mass;
        let psi1 = p.psi_prime();
        let mut md = DMatrix::zeros(6, 6);
        md[(0, 0)] = tx;
        md[(0, 1)] = ty;
        md[(1, 0)] = -ty;
        md[(1, 1)] = tx;
        md[(2, 2)] = 1.0;
        md[(2, 5)] = a;
        md[(3, 2)] = -m * a;
        md[(3, 5)] = self.rolling.disk.inertia();
        md[(4, 3)] = psi1;
        md[(4, 4)] = 1.0;
        md[(5, 0)] = 1.0;
        md[(5, 3)] = a * psi1 * tx - p.d1[0];
        md
    }

    /// y' from M_D y' = F_D; the reactions need v̇_x and ṡ.
    fn derivative(&self, y: &[f64]) -> Option<Vec<f64>> {
        let mut f = vec![0.0; 6];
        self.rhs(0.0, y, &mut f);
        let lu = self.mass_matrix(y).lu();
        lu.solve(&DVector::from_vec(f))
            .map(|v| v.as_slice().to_vec())
    }
}

impl Dynamics for Thesis {
    fn dim(&self) -> usize {
        6
    }

    fn rhs(&self, _t: f64, y: &[f64], f: &mut [f64]) {
        let p = self.rolling.curve.at(y[3]);
        let d = &self.rolling.disk;
        f.fill(0.0);
        f[0] = y[2];
        f[3] = d.mass * self.rolling.gravity * d.radius * p.tangent()[1];
        f[4] = y[5];
    }

    fn mass(&self, _t: f64, y: &[f64]) -> Option<crate::linalg::Sparse> {
        Some(crate::linalg::from_dense(&self.mass_matrix(y)))
    }
}

impl Problem for Thesis {
    type Event = StopReason;

    fn events(&self) -> &[EventSpec<StopReason>] {
        self.rolling.event_specs()
    }

    fn event(&self, index: usize, t: f64, y: &[f64]) -> f64 {
        self.rolling.event_value(index, &self.observe(t, y))
    }
}

impl RollingModel for Thesis {
    /// Table 2: the centre from the contact point, v_x from the no-slip condition.
    fn initial_state(&self) -> Vec<f64> {
        let r = &self.rolling;
        self.state_at(r.s0, r.v0(), 0.0)
    }

    fn state_at(&self, s: f64, v: f64, phi: f64) -> Vec<f64> {
        let r = &self.rolling;
        let c = r.centre(&r.curve.at(s));
        vec![c[0], c[1], v, s, phi, -v / r.disk.radius]
    }

    fn observe(&self, _t: f64, y: &[f64]) -> DiskObservation {
        let r = &self.rolling;
        let p = r.curve.at(y[3]);
        let t = p.tangent();
        let yp = self.derivative(y).unwrap_or_else(|| vec![f64::NAN; 6]);
        let (rt, rn) = r.reactions(&p, y[2], yp[2], yp[3]);
        let (kinetic, potential) = r.energies(y[2], y[5], y[1]);
        DiskObservation {
            s: y[3],
            x: y[0],
            y: y[1],
            vx: y[2] * t[0],
            vy: y[2] * t[1],
            omega: y[5],
            phi: y[4],
            rt,
            rn,
            kinetic,
            potential,
        }
    }

    fn formulation(&self) -> &'static str {
        "thesis"
    }
}

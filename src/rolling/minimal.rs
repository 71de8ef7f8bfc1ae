//! One degree of freedom: the contact parameter s. The centre rides on the offset curve
//! r_c(s) = r(s) + a e_n(s), whose arc length per unit s is h(s) = |r'| (1 − aκ) = |r'| − aψ'.
//! With v the centre's speed along e_t and no slip (Ω = −v/a), the energy is
//!   E = ½ (m + C/a²) v² + m g Y_c(s),   dY_c/ds = h e_tY,
//! and dE/dt = 0 gives (m + C/a²) v̇ = −m g e_tY. So the state is (s, v, φ) with
//!   ṡ = v / h,   v̇ = −g e_tY m / (m + C/a²),   φ̇ = Ω − ψ' ṡ,
//! where φ, the rotation relative to the tangent frame, is carried only to report it.

use super::StopReason;
use super::{DiskObservation, Rolling, RollingModel};
use crate::ode::{Dynamics, EventSpec, Problem};

pub struct Minimal {
    pub rolling: Rolling,
}

impl Minimal {
    fn rates(&self, y: &[f64]) -> (f64, f64, f64) {
        let p = self.rolling.curve.at(y[0]);
        let a = self.rolling.disk.radius;
        let h = p.speed() - a * p.psi_prime();
        let v = y[1];
        let sdot = v / h;
        let vdot = -self.rolling.gravity * p.tangent()[1] * self.rolling.disk.mass
            / self.rolling.disk.rolling_mass();
        let phidot = -v / a - p.psi_prime() * sdot;
        (sdot, vdot, phidot)
    }
}

impl Dynamics for Minimal {
    fn dim(&self) -> usize {
        3
    }

    fn rhs(&self, _t: f64, y: &[f64], f: &mut [f64]) {
        let (sdot, vdot, phidot) = self.rates(y);
        f[0] = sdot;
        f[1] = vdot;
        f[2] = phidot;
    }
}

impl Problem for Minimal {
    type Event = StopReason;

    fn events(&self) -> &[EventSpec<StopReason>] {
        self.rolling.event_specs()
    }

    fn event(&self, index: usize, t: f64, y: &[f64]) -> f64 {
        self.rolling.event_value(index, &self.observe(t, y))
    }
}

impl RollingModel for Minimal {
    fn initial_state(&self) -> Vec<f64> {
        self.state_at(self.rolling.s0, self.rolling.v0(), 0.0)
    }

    fn state_at(&self, s: f64, v: f64, phi: f64) -> Vec<f64> {
        vec![s, v, phi]
    }

    fn observe(&self, _t: f64, y: &[f64]) -> DiskObservation {
        let r = &self.rolling;
        let p = r.curve.at(y[0]);
        let c = r.centre(&p);
        let t = p.tangent();
        let v = y[1];
        let (sdot, vdot, _) = self.rates(y);
        let (rt, rn) = r.reactions(&p, v, vdot, sdot);
        let omega = -v / r.disk.radius;
        let (kinetic, potential) = r.energies(v, omega, c[1]);
        DiskObservation {
            s: y[0],
            x: c[0],
            y: c[1],
            vx: v * t[0],
            vy: v * t[1],
            omega,
            phi: y[2],
            rt,
            rn,
            kinetic,
            potential,
        }
    }

    fn formulation(&self) -> &'static str {
        "minimal"
    }
}

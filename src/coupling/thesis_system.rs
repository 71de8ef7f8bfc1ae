//! Thesis Table 9 letter for letter: 3n + 6 first-order unknowns and the state-dependent mass
//! matrix (5.27), as the thesis integrated them with ode23tb (TR-BDF2):
//!   y = (q, v, X_T, Y_T, v_x, s, φ, Ω),   diag(I, M_N, M_D(y)) y' = (v, F_N, F_D),
//! with the rows of M_D as (5.24) lists them:
//!   [ND_3n+1]  e_tX Ẋ_T + e_tY Ẏ_T = v_x          [ND_3n+2]  −e_tY Ẋ_T + e_tX Ẏ_T = 0
//!   [ND_3n+3]  v̇_x + a Ω̇ = 0                       [ND_3n+4]  −m a v̇_x + C Ω̇ = m g a e_tY
//!   [ND_3n+5]  ψ_s ṡ + φ̇ = Ω                        [ND_3n+6]  Ẋ_T − r'_X (1 − a ψ_s/|r'|) ṡ = 0
//! The contact force on the beam needs v̇_x and ṡ, which the thesis lists as dependent
//! unknowns: rows 3–4 give v̇_x = −m g a² e_tY / (m a² + C) and rows 1, 2 and 6 give
//! ṡ = v_x / (|r'| − a ψ_s), both explicit in the state. The same force is the one
//! [`super::Coupling::Thesis`] applies, which generalized-α and ESDIRK4 integrate in the
//! equivalent (s, ṡ) form; a test checks that the two agree.

use crate::disk::StopReason;
use crate::linalg::{Assembly, Sparse};
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::{Dynamics, EventSpec, Method, Problem};

use super::DiskOnBeam;

/// Whether `method` integrates the thesis coupling as this published system: the first-order
/// methods do, as the thesis did; generalized-α and ESDIRK4 step the (s, ṡ) form, which holds
/// any beam model (ESDIRK4 on this system took 370 times generalized-α's steps on the exact
/// beam).
pub fn integrates_as_published(method: Method) -> bool {
    matches!(method, Method::Dopri5 | Method::TrBdf2)
}

pub struct ThesisSystem<'s, 'a> {
    pub coupled: &'s DiskOnBeam<'a>,
}

impl ThesisSystem<'_, '_> {
    fn n(&self) -> usize {
        self.coupled.beam().dim()
    }

    /// y at t = 0: the beam at rest in displacements q0 (undeformed in Table 10), the disk on
    /// it at s0.
    pub fn initial_state(&self, q0: &[f64]) -> Vec<f64> {
        let n = self.n();
        let (z, zd) = self.coupled.initial_state(q0);
        let o = self.coupled.observe(0.0, &z, &zd);
        let mut y = vec![0.0; 2 * n + 6];
        y[..n].copy_from_slice(q0);
        let spec = self.coupled.spec();
        y[2 * n..].copy_from_slice(&[o.x, o.y, spec.v0(), spec.s0, 0.0, spec.omega0]);
        y
    }

    /// The reduced state (z, ż) = ((q, s), (v, ṡ)) that the run records.
    pub fn reduced(&self, t: f64, y: &[f64]) -> Vec<f64> {
        let n = self.n();
        let (s, vx) = (y[2 * n + 3], y[2 * n + 2]);
        let mut out = Vec::with_capacity(2 * n + 2);
        out.extend_from_slice(&y[..n]);
        out.push(s);
        out.extend_from_slice(&y[n..2 * n]);
        out.push(self.sdot(t, y, s, vx));
        out
    }

    /// ṡ = v_x / (|r'| − a ψ_s), from rows 1, 2 and 6.
    fn sdot(&self, t: f64, y: &[f64], s: f64, vx: f64) -> f64 {
        let n = self.n();
        let mut z = y[..n].to_vec();
        z.push(s);
        let mut zd = y[n..2 * n].to_vec();
        zd.push(0.0);
        let at = self.coupled.contact(0, t, &z, &zd);
        vx / (at.rp.v - self.coupled.spec().disk.radius * at.psi_s.v)
    }
}

impl Dynamics for ThesisSystem<'_, '_> {
    fn dim(&self) -> usize {
        2 * self.n() + 6
    }

    fn rhs(&self, t: f64, y: &[f64], f: &mut [f64]) {
        let n = self.n();
        let r = self.reduced(t, y);
        let (z, zd) = r.split_at(n + 1);
        f[..n].copy_from_slice(&y[n..2 * n]);
        self.coupled
            .loaded
            .force(t, &y[..n], &y[n..2 * n], &mut f[n..2 * n]);
        self.coupled
            .add_disk_force_on_beam(t, z, zd, &mut f[n..2 * n]);
        let spec = self.coupled.spec();
        let at = self.coupled.contact(0, t, z, zd);
        let e_t = self.coupled.beam().to_global(at.tangent());
        let (m, a) = (spec.disk.mass, spec.disk.radius);
        let d = &y[2 * n..];
        f[2 * n..].copy_from_slice(&[d[2], 0.0, 0.0, m * spec.gravity * a * e_t[1], d[5], 0.0]);
    }

    fn mass(&self, t: f64, y: &[f64]) -> Option<Sparse> {
        let n = self.n();
        let r = self.reduced(t, y);
        let (z, zd) = r.split_at(n + 1);
        let at = self.coupled.contact(0, t, z, zd);
        let e_t = self.coupled.beam().to_global(at.tangent());
        let spec = self.coupled.spec();
        let (m, a, c) = (spec.disk.mass, spec.disk.radius, spec.disk.inertia());
        let mut mm = Assembly::new(2 * n + 6);
        (0..n).for_each(|i| mm.add(i, i, 1.0));
        mm.add_sparse(self.coupled.beam().mass(), 1.0, n, n);
        let k = 2 * n;
        let rx = at.rp.v * e_t[0];
        for (i, j, v) in [
            (0, 0, e_t[0]),
            (0, 1, e_t[1]),
            (1, 0, -e_t[1]),
            (1, 1, e_t[0]),
            (2, 2, 1.0),
            (2, 5, a),
            (3, 2, -m * a),
            (3, 5, c),
            (4, 3, at.psi_s.v),
            (4, 4, 1.0),
            (5, 0, 1.0),
            (5, 3, -rx * (1.0 - a * at.psi_s.v / at.rp.v)),
        ] {
            mm.add(k + i, k + j, v);
        }
        Some(mm.build())
    }

    fn jacobian(&self, t: f64, y: &[f64]) -> Option<Sparse> {
        // The beam's own [[0, I], [−K, 0]]; the disk's terms are left to Newton's iterations.
        let n = self.n();
        let mut a = Assembly::new(2 * n + 6);
        (0..n).for_each(|i| a.add(i, n + i, 1.0));
        a.add_sparse(&self.coupled.loaded.stiffness(t, &y[..n]), -1.0, n, 0);
        a.add(2 * n + 5, 2 * n + 5, 0.0);
        Some(a.build())
    }
}

impl Problem for ThesisSystem<'_, '_> {
    type Event = StopReason;

    fn breakpoints(&self) -> Vec<f64> {
        self.coupled.loaded.breakpoints()
    }

    fn enter_segment(&self, start: f64, end: f64) {
        self.coupled.loaded.enter_segment(start, end)
    }

    fn max_step(&self, t: f64, _y: &[f64]) -> f64 {
        self.coupled.loaded.load_step_bound(t)
    }

    fn events(&self) -> &[EventSpec<StopReason>] {
        // Off either end, and contact lost: the rolling couplings' first three.
        &super::EVENTS[..3]
    }

    fn event(&self, index: usize, t: f64, y: &[f64]) -> f64 {
        let n = self.n();
        let s = y[2 * n + 3];
        match index {
            0 => self.coupled.beam().length - s,
            1 => s,
            _ => {
                let r = self.reduced(t, y);
                let (z, zd) = r.split_at(n + 1);
                self.coupled.observe(t, z, zd).rn
            }
        }
    }
}

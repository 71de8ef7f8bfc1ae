//! One Reissner beam element in the beam's own frame (x along the undeformed axis).
//!
//! Kinematics: r' = (1 + u', w'), section rotation φ, t = (cos φ, sin φ), n = (−sin φ, cos φ):
//!   ε = r'·t − 1,   γ = r'·n,   κ = φ'.
//! Section: N = EA ε, Q = GAv γ, M = EI κ; the stress resultant in the beam frame is
//! R = N t + Q n. Virtual work of the internal forces, with δε = t·δr' + γ δφ,
//! δγ = n·δr' − (1 + ε) δφ, δκ = δφ', gives per node a
//!   f_u = ∫ R_x P_a',  f_w = ∫ R_y P_a',  f_φ = ∫ M P_a' + (N γ − Q (1 + ε)) P_a   (thesis (4.16)),
//! and its derivative the tangent stiffness: a material part Bᵀ D B and a geometric part
//!   (N n − Q t)·(δr' Δφ + Δr' δφ) − (N (1 + ε) + Q γ) δφ Δφ.

use super::basis::Lagrange;
use super::quadrature::Rule;

/// Elastic and inertial properties of the cross-section.
#[derive(Clone, Copy, Debug)]
pub struct Section {
    pub ea: f64,
    pub gav: f64,
    pub ei: f64,
    pub rho_a: f64,
    pub rho_i: f64,
}

/// Strains and resultants at one point.
#[derive(Clone, Copy, Debug)]
pub struct PointState {
    pub eps: f64,
    pub gamma: f64,
    pub kappa: f64,
    pub n: f64,
    pub q: f64,
    pub m: f64,
    pub t: [f64; 2],
    pub nrm: [f64; 2],
}

pub fn point_state(s: &Section, du: f64, dw: f64, phi: f64, dphi: f64) -> PointState {
    let (sn, cs) = phi.sin_cos();
    let t = [cs, sn];
    let nrm = [-sn, cs];
    let r1 = [1.0 + du, dw];
    let eps = r1[0] * t[0] + r1[1] * t[1] - 1.0;
    let gamma = r1[0] * nrm[0] + r1[1] * nrm[1];
    PointState {
        eps,
        gamma,
        kappa: dphi,
        n: s.ea * eps,
        q: s.gav * gamma,
        m: s.ei * dphi,
        t,
        nrm,
    }
}

/// Shape functions evaluated at the quadrature points of one rule, scaled to an element of
/// length h (derivatives in x, weights times the Jacobian h/2).
#[derive(Clone, Debug)]
pub struct Tabulated {
    pub n: Vec<Vec<f64>>,
    pub dn: Vec<Vec<f64>>,
    pub w: Vec<f64>,
}

impl Tabulated {
    pub fn new(basis: &Lagrange, rule: &Rule, h: f64) -> Self {
        let k = basis.count();
        let mut n = Vec::new();
        let mut dn = Vec::new();
        for &xi in &rule.points {
            let mut a = vec![0.0; k];
            let mut b = vec![0.0; k];
            basis.eval(xi, &mut a, &mut b);
            b.iter_mut().for_each(|v| *v *= 2.0 / h);
            n.push(a);
            dn.push(b);
        }
        Tabulated {
            n,
            dn,
            w: rule.weights.iter().map(|w| w * h / 2.0).collect(),
        }
    }
}

/// Element unknowns are ordered node by node: (u, w, φ) of node 0, of node 1, …
pub struct ElementKernels<'a> {
    pub section: &'a Section,
    pub stiff: &'a Tabulated,
}

impl ElementKernels<'_> {
    fn interpolate(&self, q: &[f64], g: usize) -> (f64, f64, f64, f64) {
        let (n, dn) = (&self.stiff.n[g], &self.stiff.dn[g]);
        let (mut du, mut dw, mut phi, mut dphi) = (0.0, 0.0, 0.0, 0.0);
        for a in 0..n.len() {
            du += dn[a] * q[3 * a];
            dw += dn[a] * q[3 * a + 1];
            phi += n[a] * q[3 * a + 2];
            dphi += dn[a] * q[3 * a + 2];
        }
        (du, dw, phi, dphi)
    }

    /// Internal force vector; returns the element's strain energy.
    pub fn internal_force(&self, q: &[f64], f: &mut [f64]) -> f64 {
        f.fill(0.0);
        let mut energy = 0.0;
        let s = self.section;
        for g in 0..self.stiff.w.len() {
            let (du, dw, phi, dphi) = self.interpolate(q, g);
            let p = point_state(s, du, dw, phi, dphi);
            let w = self.stiff.w[g];
            let rx = p.n * p.t[0] + p.q * p.nrm[0];
            let ry = p.n * p.t[1] + p.q * p.nrm[1];
            let couple = p.n * p.gamma - p.q * (1.0 + p.eps);
            let (n, dn) = (&self.stiff.n[g], &self.stiff.dn[g]);
            for a in 0..n.len() {
                f[3 * a] += w * rx * dn[a];
                f[3 * a + 1] += w * ry * dn[a];
                f[3 * a + 2] += w * (p.m * dn[a] + couple * n[a]);
            }
            energy += 0.5
                * w
                * (s.ea * p.eps * p.eps + s.gav * p.gamma * p.gamma + s.ei * p.kappa * p.kappa);
        }
        energy
    }

    /// Tangent stiffness ∂f/∂q, dense k × k with k = 3 (p + 1), row-major.
    pub fn tangent(&self, q: &[f64], k: &mut [f64]) {
        let dim = q.len();
        k.fill(0.0);
        let s = self.section;
        let mut be = vec![0.0; dim];
        let mut bg = vec![0.0; dim];
        for g in 0..self.stiff.w.len() {
            let (du, dw, phi, dphi) = self.interpolate(q, g);
            let p = point_state(s, du, dw, phi, dphi);
            let w = self.stiff.w[g];
            let (n, dn) = (&self.stiff.n[g], &self.stiff.dn[g]);
            for a in 0..n.len() {
                be[3 * a] = p.t[0] * dn[a];
                be[3 * a + 1] = p.t[1] * dn[a];
                be[3 * a + 2] = p.gamma * n[a];
                bg[3 * a] = p.nrm[0] * dn[a];
                bg[3 * a + 1] = p.nrm[1] * dn[a];
                bg[3 * a + 2] = -(1.0 + p.eps) * n[a];
            }
            for i in 0..dim {
                for j in 0..dim {
                    k[i * dim + j] += w * (s.ea * be[i] * be[j] + s.gav * bg[i] * bg[j]);
                }
            }
            let gx = p.n * p.nrm[0] - p.q * p.t[0];
            let gy = p.n * p.nrm[1] - p.q * p.t[1];
            let c = -(p.n * (1.0 + p.eps) + p.q * p.gamma);
            for a in 0..n.len() {
                for b in 0..n.len() {
                    k[(3 * a + 2) * dim + 3 * b + 2] +=
                        w * (s.ei * dn[a] * dn[b] + c * n[a] * n[b]);
                    k[(3 * a) * dim + 3 * b + 2] += w * gx * dn[a] * n[b];
                    k[(3 * a + 1) * dim + 3 * b + 2] += w * gy * dn[a] * n[b];
                    k[(3 * a + 2) * dim + 3 * b] += w * gx * n[a] * dn[b];
                    k[(3 * a + 2) * dim + 3 * b + 1] += w * gy * n[a] * dn[b];
                }
            }
        }
    }
}

/// Consistent mass: ρA for u and w, ρI for φ, integrated with `mass` (exact for the products).
pub fn mass(section: &Section, mass: &Tabulated, m: &mut [f64]) {
    let k = mass.n[0].len();
    let dim = 3 * k;
    m.fill(0.0);
    for g in 0..mass.w.len() {
        let n = &mass.n[g];
        for a in 0..k {
            for b in 0..k {
                let v = mass.w[g] * n[a] * n[b];
                m[(3 * a) * dim + 3 * b] += section.rho_a * v;
                m[(3 * a + 1) * dim + 3 * b + 1] += section.rho_a * v;
                m[(3 * a + 2) * dim + 3 * b + 2] += section.rho_i * v;
            }
        }
    }
}

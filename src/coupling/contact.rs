//! The contact point: material point s of the deformed beam axis, in the beam's own frame.
//!
//! The disk touches the axis through a contact patch: it rolls on r(s, t) = (s + u, w), the
//! axis averaged around s with a smooth kernel of half-width b (see
//! [`Beam::patch_basis_at`]), u = Σ S_a U_a, w = Σ S_a W_a. A point contact would sit on two
//! kinks: the C0 elements meet with a jump of slope, and the shear-deformable axis itself
//! turns by P/(G Av) under a point force; ψ_s under the disk would then grow without bound
//! as the mesh is refined. Averaged, the track is C3 in s, the same at every mesh, and b → 0
//! recovers the point contact. Every
//! quantity is a jet along the motion: its value, its rate d/dt = ∂/∂t + ṡ ∂/∂s, and the part of
//! its second rate that is quadratic in the velocities (the accelerations s̈, Ü, Ẅ set to zero),
//! which is what the equations of motion add as centripetal and Coriolis terms. With
//! r' = |r'| t and ψ the angle of t:
//!   ψ = atan(w' / (1 + u')),   ψ_s = ((1 + u') w'' − w' u'') / |r'|²,
//! the disk's centre c = r + a n, n the left normal.

use crate::beam::{Beam, NodeBasis, PastFreeEnd};
use crate::curve::jet::Jet;

/// A sparse row: (unknown, coefficient).
pub type Row = Vec<(usize, f64)>;

pub struct AxisPoint {
    pub nodes: Vec<NodeBasis>,
    /// Position of the axis point, beam frame: (s + u, w).
    pub x: Jet,
    pub y: Jet,
    pub du: Jet,
    pub dw: Jet,
    /// Section rotation at s.
    pub phi: Jet,
    /// |r'|: the stretch of the axis at s.
    pub rp: Jet,
    pub psi: Jet,
    /// ψ_s and its rate; its quadratic part is not formed (it would need N'''').
    pub psi_s: Jet,
    pub sdot: f64,
}

impl AxisPoint {
    /// The axis at material point s moving at ṡ, for the beam state (q, v), averaged over a
    /// patch of half-width `half`.
    pub fn at(beam: &Beam, q: &[f64], v: &[f64], s: f64, sdot: f64, half: f64) -> AxisPoint {
        Self::on(
            beam.patch_basis_at(s, half, PastFreeEnd::CarriedOn),
            q,
            v,
            s,
            sdot,
        )
    }

    /// The same, from the patch-averaged shape functions at s, `nodes`.
    pub fn on(nodes: Vec<NodeBasis>, q: &[f64], v: &[f64], s: f64, sdot: f64) -> AxisPoint {
        let value = |i: Option<usize>, y: &[f64]| i.map_or(0.0, |i| y[i]);
        // Σ_a N_a^(k)(s(t)) U_a(t) as a jet in t.
        let field = |k: usize, pick: fn(&NodeBasis) -> Option<usize>| {
            nodes.iter().fold(Jet::constant(0.0), |acc, nb| {
                let basis = Jet {
                    v: nb.d[k],
                    d1: nb.d.get(k + 1).map_or(0.0, |d| d * sdot),
                    d2: nb.d.get(k + 2).map_or(0.0, |d| d * sdot * sdot),
                };
                let dof = Jet {
                    v: value(pick(nb), q),
                    d1: value(pick(nb), v),
                    d2: 0.0,
                };
                acc + basis * dof
            })
        };
        let u = field(0, |n| n.u);
        let w = field(0, |n| n.w);
        let du = field(1, |n| n.u);
        let dw = field(1, |n| n.w);
        let mut ddu = field(2, |n| n.u);
        let mut ddw = field(2, |n| n.w);
        ddu.d2 = 0.0;
        ddw.d2 = 0.0;
        let phi = field(0, |n| n.phi);
        let one = Jet::constant(1.0);
        let ax = one + du;
        let rp2 = ax * ax + dw * dw;
        let rp = rp2.sqrt();
        let psi = (dw / ax).atan();
        let mut psi_s = (ax * ddw - dw * ddu) / rp2;
        psi_s.d2 = 0.0;
        AxisPoint {
            nodes,
            x: Jet {
                v: s,
                d1: sdot,
                d2: 0.0,
            } + u,
            y: w,
            du,
            dw,
            phi,
            rp,
            psi,
            psi_s,
            sdot,
        }
    }

    pub fn tangent(&self) -> [f64; 2] {
        let (sn, cs) = self.psi.v.sin_cos();
        [cs, sn]
    }

    pub fn normal(&self) -> [f64; 2] {
        let (sn, cs) = self.psi.v.sin_cos();
        [-sn, cs]
    }

    /// The centre of a disk of radius a resting on the axis here: c = r + a n.
    pub fn centre(&self, a: f64) -> [Jet; 2] {
        let r = Jet::constant(a);
        [self.x - r * self.psi.sin(), self.y + r * self.psi.cos()]
    }

    /// ∂ψ/∂q: the slope responds to the nodal displacements through S'.
    pub fn psi_gradient(&self) -> Row {
        let rp2 = self.rp.v * self.rp.v;
        // Room for the contact coordinate's entry a rolling law adds after these.
        let mut row = Row::with_capacity(2 * self.nodes.len() + 1);
        for nb in &self.nodes {
            if let Some(i) = nb.u {
                row.push((i, -self.dw.v * nb.d[1] / rp2));
            }
            if let Some(i) = nb.w {
                row.push((i, (1.0 + self.du.v) * nb.d[1] / rp2));
            }
        }
        row
    }

    /// ∂r/∂q for the X and the Y component of the axis point (beam frame).
    pub fn position_gradient(&self) -> [Row; 2] {
        crate::beam::position_rows(&self.nodes)
    }

    /// Spread the contact force (beam frame) at s onto the beam's unknowns: its virtual work
    /// F·δr(s) = F·Σ S_a δ(U_a, W_a), i.e. over the patch.
    pub fn spread(&self, force: [f64; 2], f: &mut [f64]) {
        for nb in &self.nodes {
            if let Some(i) = nb.u {
                f[i] += nb.d[0] * force[0];
            }
            if let Some(i) = nb.w {
                f[i] += nb.d[0] * force[1];
            }
        }
    }

    /// The material velocity of the axis at s, ∂r/∂t at fixed s.
    pub fn material_velocity(&self) -> [f64; 2] {
        [
            self.x.d1 - self.sdot * (1.0 + self.du.v),
            self.y.d1 - self.sdot * self.dw.v,
        ]
    }
}

pub fn dot(row: &Row, y: &[f64]) -> f64 {
    row.iter().map(|&(i, c)| c * y[i]).sum()
}

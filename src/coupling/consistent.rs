//! The consistent coupling: the disk stays on the moving beam and rolls on it without slip.
//! Centre c(q, s) = r(s) + a n(s); rolling, measured against the beam's own material velocity
//! at s, is θ̇ = dψ/dt − |r'| ṡ / a. With the rows J_c = ∂c/∂z and B = ∂θ̇/∂ż the disk adds
//! m J_cᵀ J_c + C Bᵀ B to the mass and −m J_cᵀ (J̇_c ż − g) − C Bᵀ (Ḃ ż) to the force; the
//! constraint does no work, so the total energy is conserved (see `mod.rs`).

use super::contact::{dot, AxisPoint, Row};
use super::law::{AddedMass, Law, Motion, Rider};

pub(crate) struct Consistent;

impl Consistent {
    /// The force on the rows of [`Self::rows`]: −m (c̈ − g) where c̈ is the centre's
    /// acceleration at z̈ = 0, and −C times the rolling rate's part that z̈ does not give.
    fn force_weights(r: &Rider, at: &AxisPoint) -> [f64; 3] {
        let (m, a, g) = (r.disk.mass, r.disk.radius, r.gravity);
        let c = at.centre(a);
        let theta_quad = at.psi.d2 - at.rp.d1 * at.sdot / a;
        [
            -m * (c[0].d2 - g[0]),
            -m * (c[1].d2 - g[1]),
            -r.disk.inertia() * theta_quad,
        ]
    }

    /// ∂c_X/∂z, ∂c_Y/∂z and B = ∂θ̇/∂ż.
    fn rows(r: &Rider, at: &AxisPoint) -> [Row; 3] {
        let a = r.disk.radius;
        let tg = at.tangent();
        let dpsi = at.psi_gradient();
        let [mut gx, mut gy] = at.position_gradient();
        gx.reserve(dpsi.len() + 1);
        gy.reserve(dpsi.len() + 1);
        for &(i, d) in &dpsi {
            gx.push((i, -a * d * tg[0]));
            gy.push((i, -a * d * tg[1]));
        }
        let along = at.rp.v - a * at.psi_s.v;
        gx.push((r.n, along * tg[0]));
        gy.push((r.n, along * tg[1]));
        let mut gb = dpsi;
        gb.push((r.n, at.psi_s.v - at.rp.v / a));
        [gx, gy, gb]
    }
}

impl Law for Consistent {
    fn unknowns(&self) -> usize {
        1
    }

    fn added_mass(&self, r: &Rider, at: &AxisPoint) -> AddedMass {
        let [gx, gy, gb] = Self::rows(r, at);
        vec![(r.disk.mass, gx), (r.disk.mass, gy), (r.disk.inertia(), gb)]
    }

    fn force(&self, r: &Rider, at: &AxisPoint, force: &mut Vec<(usize, f64)>) {
        let [gx, gy, gb] = Self::rows(r, at);
        let weights = Self::force_weights(r, at);
        force.reserve(gx.len() + gy.len() + gb.len());
        for (row, w) in [&gx, &gy, &gb].into_iter().zip(weights) {
            force.extend(row.iter().map(|&(i, v)| (i, v * w)));
        }
    }

    fn force_on_inertia_rows(&self, r: &Rider, at: &AxisPoint) -> Option<Vec<f64>> {
        Some(Self::force_weights(r, at).to_vec())
    }

    fn motion(&self, r: &Rider, at: &AxisPoint, zd: &[f64], zdd: &[f64]) -> Motion {
        let (m, g) = (r.disk.mass, r.gravity);
        let [gx, gy, gb] = Self::rows(r, at);
        let c = at.centre(r.disk.radius);
        let acc = [dot(&gx, zdd) + c[0].d2, dot(&gy, zdd) + c[1].d2];
        let velocity = [c[0].d1, c[1].d1];
        let omega = dot(&gb, zd);
        Motion {
            centre: [c[0].v, c[1].v],
            velocity,
            omega,
            contact: [m * (acc[0] - g[0]), m * (acc[1] - g[1])],
            kinetic: 0.5 * m * (velocity[0].powi(2) + velocity[1].powi(2))
                + 0.5 * r.disk.inertia() * omega * omega,
            potential: None,
        }
    }
}

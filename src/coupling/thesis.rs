//! Thesis Table 9 as published (errata 2–3 corrected): the disk rolls on the axis as if it
//! were frozen, v_x = ṡ (|r'| − a ψ_s), v̇_x = m g·t / (m + C/a²); the contact force
//! R_x = m v̇_x − m g·t, R_y = m v_x ψ_s ṡ − m g·n acts on the beam turned to global axes with
//! the section rotation φ (5.13). The (s, v_x) system is integrated as (s, ṡ):
//! s̈ = (v̇_x − ṡ d(|r'| − a ψ_s)/dt) / (|r'| − a ψ_s); the literal 3n + 6 system of the thesis
//! is `thesis_system.rs`.

use super::contact::AxisPoint;
use super::law::{spread_terms, AddedMass, Law, Motion, Rider};

pub(crate) struct Thesis;

impl Thesis {
    /// R_xK, R_yK (tangent and normal contact force on the disk) and v_x.
    pub(crate) fn reactions(r: &Rider, at: &AxisPoint) -> (f64, f64, f64) {
        let (m, a, g) = (r.disk.mass, r.disk.radius, r.gravity);
        let tg = at.tangent();
        let nm = at.normal();
        let vx = at.sdot * (at.rp.v - a * at.psi_s.v);
        let g_t = g[0] * tg[0] + g[1] * tg[1];
        let g_n = g[0] * nm[0] + g[1] * nm[1];
        let vx_rate = m * g_t / r.disk.rolling_mass();
        (
            m * vx_rate - m * g_t,
            m * vx * at.psi_s.v * at.sdot - m * g_n,
            vx,
        )
    }
}

impl Law for Thesis {
    fn unknowns(&self) -> usize {
        1
    }

    fn added_mass(&self, r: &Rider, at: &AxisPoint) -> AddedMass {
        let gs = at.rp.v - r.disk.radius * at.psi_s.v;
        vec![(r.disk.rolling_mass() * gs, vec![(r.n, 1.0)])]
    }

    fn force(&self, r: &Rider, at: &AxisPoint, force: &mut Vec<(usize, f64)>) {
        let (m, a, g) = (r.disk.mass, r.disk.radius, r.gravity);
        let (rx, ry, _) = Self::reactions(r, at);
        // (5.13): the reaction turned with the section rotation φ, not with ψ.
        let (sp, cp) = at.phi.v.sin_cos();
        let p = [-(rx * cp - ry * sp), -(rx * sp + ry * cp)];
        spread_terms(at, p, r.n, force);
        let tg = at.tangent();
        let gs_rate = at.rp.d1 - a * at.psi_s.d1;
        force.push((
            r.n,
            m * (g[0] * tg[0] + g[1] * tg[1]) - r.disk.rolling_mass() * at.sdot * gs_rate,
        ));
    }

    fn motion(&self, r: &Rider, at: &AxisPoint, _zd: &[f64], _zdd: &[f64]) -> Motion {
        let (rx, ry, vx) = Self::reactions(r, at);
        let tg = at.tangent();
        let nm = at.normal();
        let c = at.centre(r.disk.radius);
        Motion {
            centre: [c[0].v, c[1].v],
            velocity: [vx * tg[0], vx * tg[1]],
            omega: -vx / r.disk.radius,
            contact: [rx * tg[0] + ry * nm[0], rx * tg[1] + ry * nm[1]],
            kinetic: 0.5 * r.disk.rolling_mass() * vx * vx,
            potential: None,
        }
    }
}

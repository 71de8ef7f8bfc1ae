//! The moving force: the constant weight m g at s = s0 + v0 t, spread through the contact
//! patch. The motion is prescribed: the system is the beam alone, and the work the force does
//! on it is the `work` of the energy budget.

use super::contact::AxisPoint;
use super::law::{spread_terms, AddedMass, Law, Motion, Rider};

pub(crate) struct MovingForce;

impl Law for MovingForce {
    fn unknowns(&self) -> usize {
        0
    }

    fn added_mass(&self, _r: &Rider, _at: &AxisPoint) -> AddedMass {
        Vec::new()
    }

    fn force(&self, r: &Rider, at: &AxisPoint, force: &mut Vec<(usize, f64)>) {
        let (m, g) = (r.disk.mass, r.gravity);
        spread_terms(at, [m * g[0], m * g[1]], r.n, force);
    }

    fn motion(&self, r: &Rider, at: &AxisPoint, _zd: &[f64], _zdd: &[f64]) -> Motion {
        let (m, g) = (r.disk.mass, r.gravity);
        prescribed_motion(r, at, [-m * g[0], -m * g[1]])
    }
}

/// The motion of a rider carried along the axis at the prescribed speed: its centre a radius
/// off the axis, turning at its initial rate, outside the system's energy.
pub(crate) fn prescribed_motion(r: &Rider, at: &AxisPoint, contact: [f64; 2]) -> Motion {
    let a = r.disk.radius;
    let tg = at.tangent();
    let c = at.centre(a);
    Motion {
        centre: [c[0].v, c[1].v],
        velocity: [
            at.x.d1 - a * at.psi.d1 * tg[0],
            at.y.d1 - a * at.psi.d1 * tg[1],
        ],
        omega: r.omega0,
        contact,
        kinetic: 0.0,
        potential: Some(0.0),
    }
}

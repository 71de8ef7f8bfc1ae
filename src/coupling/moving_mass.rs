//! The moving mass: a point mass at s = s0 + v0 t on the axis, following its displacement with
//! its inertia. The motion along the axis is prescribed: the system is the beam alone, and the
//! work the load does on it is the `work` of the energy budget.

use super::contact::{dot, AxisPoint};
use super::law::{AddedMass, Law, Motion, Rider};
use super::moving_force::prescribed_motion;

pub(crate) struct MovingMass;

/// The force on the rows of the position's gradient: −m (r̈ − g), r̈ the axis point's
/// acceleration at z̈ = 0 (its convected part).
fn weights(r: &Rider, at: &AxisPoint) -> [f64; 2] {
    let (m, g) = (r.disk.mass, r.gravity);
    [-m * (at.x.d2 - g[0]), -m * (at.y.d2 - g[1])]
}

impl Law for MovingMass {
    fn unknowns(&self) -> usize {
        0
    }

    fn added_mass(&self, r: &Rider, at: &AxisPoint) -> AddedMass {
        let [gx, gy] = at.position_gradient();
        vec![(r.disk.mass, gx), (r.disk.mass, gy)]
    }

    fn force(&self, r: &Rider, at: &AxisPoint, force: &mut Vec<(usize, f64)>) {
        let [gx, gy] = at.position_gradient();
        for (row, w) in [&gx, &gy].into_iter().zip(weights(r, at)) {
            force.extend(row.iter().map(|&(i, v)| (i, v * w)));
        }
    }

    fn force_on_inertia_rows(&self, r: &Rider, at: &AxisPoint) -> Option<Vec<f64>> {
        Some(weights(r, at).to_vec())
    }

    fn motion(&self, r: &Rider, at: &AxisPoint, _zd: &[f64], zdd: &[f64]) -> Motion {
        let (m, g) = (r.disk.mass, r.gravity);
        let [gx, gy] = at.position_gradient();
        let acc = [dot(&gx, zdd) + at.x.d2, dot(&gy, zdd) + at.y.d2];
        prescribed_motion(r, at, [m * (acc[0] - g[0]), m * (acc[1] - g[1])])
    }
}

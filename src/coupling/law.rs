//! What one coupling law says, seen from the beam's unknowns z through the contact point: the
//! rider's inertia as z feels it, its generalised force on z, and its motion and contact force
//! for the observation. The laws know nothing of assembly or integration (`mod.rs` does that
//! for any law), and each lives in a file of its own: `consistent.rs`, `thesis.rs`,
//! `moving_mass.rs`, `moving_force.rs`.

use super::contact::{AxisPoint, Row};
use crate::disk::Disk;

/// Mass added by a rider: Σ_k w_k g_k g_kᵀ, with sparse rows g_k.
pub(crate) type AddedMass = Vec<(f64, Row)>;

/// The rider as every law sees it.
pub(crate) struct Rider {
    pub disk: Disk,
    /// Gravity's acceleration in the beam frame.
    pub gravity: [f64; 2],
    /// The beam's unknowns; a rider whose path is an unknown has its contact coordinate s
    /// next, at index n of z.
    pub n: usize,
    /// Absolute angular velocity, for a rider whose rotation is prescribed.
    pub omega0: f64,
}

/// A rider's motion and the force the beam exerts on it, beam-local axes.
pub(crate) struct Motion {
    pub centre: [f64; 2],
    pub velocity: [f64; 2],
    pub omega: f64,
    pub contact: [f64; 2],
    pub kinetic: f64,
    /// `None`: the rider's weight in the gravity field, m g Y of its centre.
    pub potential: Option<f64>,
}

pub(crate) trait Law {
    /// Unknowns the rider adds to the beam's: its contact coordinate s where its path is an
    /// unknown, none where it is prescribed.
    fn unknowns(&self) -> usize;
    /// The rider's inertia as z feels it. It reads the contact's position only (the values
    /// of its jets, not their rates): the inertia at z is formed from whichever contact at z
    /// comes first, whatever its velocity.
    fn added_mass(&self, r: &Rider, at: &AxisPoint) -> AddedMass;
    /// The rider's generalised force on z, appended to `force` as (index, value).
    fn force(&self, r: &Rider, at: &AxisPoint, force: &mut Vec<(usize, f64)>);
    /// Where the generalised force is Σ c_k g_k over the rows g_k of [`Law::added_mass`], in
    /// their order, the c_k: the same force as [`Law::force`], from rows formed once.
    fn force_on_inertia_rows(&self, _r: &Rider, _at: &AxisPoint) -> Option<Vec<f64>> {
        None
    }
    /// The rider's motion at the state whose velocities are `zd` and accelerations `zdd`.
    fn motion(&self, r: &Rider, at: &AxisPoint, zd: &[f64], zdd: &[f64]) -> Motion;
}

/// A point force on the axis, spread through the contact patch, as (index, value) terms.
pub(crate) fn spread_terms(at: &AxisPoint, p: [f64; 2], n: usize, force: &mut Vec<(usize, f64)>) {
    let mut f = vec![0.0; n];
    at.spread(p, &mut f);
    force.extend(
        f.iter()
            .enumerate()
            .filter(|(_, v)| **v != 0.0)
            .map(|(i, v)| (i, *v)),
    );
}

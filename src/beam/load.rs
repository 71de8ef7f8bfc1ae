//! What acts on the beam and where it is watched: point loads switched on and off in time,
//! probes at material points, and the state the beam starts from.

/// A point force (global components) and moment at material point x, on for from ≤ t < until.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLoad {
    pub x: f64,
    pub force: [f64; 2],
    pub mz: f64,
    pub from: f64,
    pub until: f64,
}

impl PointLoad {
    pub fn active(&self, t: f64) -> bool {
        self.from <= t && t < self.until
    }
}

/// A material point x whose displacements a run records under a name.
#[derive(Clone, Debug)]
pub struct Probe {
    pub name: String,
    pub x: f64,
}

/// The beam's state at t = 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BeamStart {
    /// Undeformed, at rest.
    Rest,
    /// At rest in static equilibrium under the loads active at t = 0 and the disk's weight at
    /// s0: a dead load already carried, as on a real bridge.
    Static,
}

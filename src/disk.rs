//! The rolling body: a uniform rigid disk.

#[derive(Clone, Copy, Debug)]
pub struct Disk {
    pub mass: f64,
    pub radius: f64,
}

impl Disk {
    /// Polar moment of inertia about the centre, C = m a² / 2.
    pub fn inertia(&self) -> f64 {
        0.5 * self.mass * self.radius * self.radius
    }

    /// Mass felt along the path when rolling without slip: m + C/a².
    pub fn rolling_mass(&self) -> f64 {
        self.mass + self.inertia() / (self.radius * self.radius)
    }
}

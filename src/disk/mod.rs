//! The rolling body, a uniform rigid disk, and what it does at a track whatever the track is:
//! what a run reports of it, where it stops rolling, what happens where it loses contact, and
//! its flight in closed form ([`flight`]). The rigid curve (`rolling`) and the beam
//! (`coupling`) both build on it.

pub mod flight;
pub mod life;

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

/// Everything a run reports about the disk at one instant.
#[derive(Clone, Copy, Debug, Default)]
pub struct DiskObservation {
    pub s: f64,
    /// Centre position and velocity, global.
    pub x: f64,
    pub y: f64,
    pub vx: f64,
    pub vy: f64,
    /// Absolute angular velocity (Ω < 0 rolls towards +s).
    pub omega: f64,
    /// Rotation of the disk relative to the tangent frame (thesis φ).
    pub phi: f64,
    /// Contact force on the disk: along the track tangent, and along the left normal (positive
    /// pushes the disk off the track).
    pub rt: f64,
    pub rn: f64,
    pub kinetic: f64,
    pub potential: f64,
}

impl DiskObservation {
    /// The friction coefficient rolling needs here, |R_t| / R_n; none where the disk does not
    /// press on the track (R_n ≤ 0), since no friction coefficient holds it there.
    pub fn mu_needed(&self) -> Option<f64> {
        (self.rn > 0.0).then(|| self.rt.abs() / self.rn)
    }
}

/// Where the disk stops being a disk rolling on this track.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    ContactLost,
    Slip,
    NoFit,
    LeftTrack,
}

impl StopReason {
    pub fn name(self) -> &'static str {
        match self {
            StopReason::ContactLost => "contact-lost",
            StopReason::Slip => "slip",
            StopReason::NoFit => "no-fit",
            StopReason::LeftTrack => "left-track",
        }
    }
}

/// What happens where the normal force falls to zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ContactLoss {
    /// The disk leaves the track, flies, and lands by an impact that gives back `restitution`
    /// of the normal speed.
    Fly { restitution: f64 },
    /// The run ends there (`contact-lost`), as the thesis' program did.
    Stop,
}

/// The disk is taken not to fit once 1 − aκ falls below this: the offset curve is about to
/// turn singular and ṡ = v / (|r'| (1 − aκ)) to blow up.
pub const FIT_MARGIN: f64 = 1e-6;

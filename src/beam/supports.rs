//! Supports at the two ends of the beam, as the unknowns they hold in the beam frame
//! (0 = u along the undeformed axis, 1 = w across it, 2 = φ), and intermediate bearings
//! between them, which hold w at a mesh node (a continuous beam over several spans).

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Support {
    Clamped,
    Pinned,
    /// Free to slide along the undeformed axis.
    Roller,
    Free,
}

impl Support {
    pub const ALL: [Support; 4] = [
        Support::Clamped,
        Support::Pinned,
        Support::Roller,
        Support::Free,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Support::Clamped => "clamped",
            Support::Pinned => "pinned",
            Support::Roller => "roller",
            Support::Free => "free",
        }
    }

    pub fn from_name(name: &str) -> Option<Support> {
        Support::ALL.into_iter().find(|s| s.name() == name)
    }

    pub fn held_components(self) -> &'static [usize] {
        match self {
            Support::Clamped => &[0, 1, 2],
            Support::Pinned => &[0, 1],
            Support::Roller => &[1],
            Support::Free => &[],
        }
    }
}

/// A straight beam needs three independent support reactions to carry a static load; each
/// intermediate bearing adds one.
pub fn statically_supported(ends: [Support; 2], bearings: usize) -> bool {
    ends.iter()
        .map(|s| s.held_components().len())
        .sum::<usize>()
        + bearings
        >= 3
}

/// The fewest elements of a uniform mesh that put a node at every intermediate bearing (given
/// as fractions x/L of the length): every admissible element count is a multiple of it.
/// `None` when no count up to `limit` does, the spans being incommensurable.
pub fn mesh_multiple(fractions: &[f64], limit: usize) -> Option<usize> {
    (1..=limit).find(|&m| {
        fractions.iter().all(|f| {
            let at = f * m as f64;
            (at - at.round()).abs() <= 1e-9 * m as f64
        })
    })
}

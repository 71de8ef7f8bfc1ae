//! Supports at the two ends of the beam, as the unknowns they hold in the beam frame
//! (0 = u along the undeformed axis, 1 = w across it, 2 = φ).

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

/// A straight beam needs three independent support reactions to carry a static load.
pub fn statically_supported(ends: [Support; 2]) -> bool {
    ends.iter()
        .map(|s| s.held_components().len())
        .sum::<usize>()
        >= 3
}

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

/// The rigid-body motions a straight beam's supports leave it: of sliding along its axis
/// (held by any end that holds u), and of moving across it and turning (held by w at two
/// points, or w at one and φ at a clamped end). Intermediate bearings hold w, each at a point
/// of its own. Counting reactions instead took a beam on rollers alone with a bearing between
/// them (three reactions, all across the axis) for supported, and its static solution put
/// 10²² N in the reactions of a load with a component along the axis.
pub fn rigid_motions(ends: [Support; 2], bearings: usize) -> usize {
    let holding = |c: usize| {
        ends.iter()
            .filter(|s| s.held_components().contains(&c))
            .count()
    };
    let sliding = usize::from(holding(0) == 0);
    let across = holding(1) + bearings + usize::from(holding(2) > 0);
    sliding + 2 - across.min(2)
}

/// Whether the supports hold every rigid-body motion, so that the beam carries a static load.
pub fn statically_supported(ends: [Support; 2], bearings: usize) -> bool {
    rigid_motions(ends, bearings) == 0
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

#[cfg(test)]
mod tests {
    use super::*;
    use Support::*;

    /// Each pair of ends against the motions a straight beam on them can make without
    /// straining: slide (u), move across (w), turn about a point (w = x, φ = 1).
    #[test]
    fn the_rigid_motions_left_are_those_no_support_holds() {
        for (ends, bearings, left) in [
            ([Pinned, Roller], 0, 0),
            ([Clamped, Free], 0, 0),
            ([Free, Clamped], 0, 0),
            ([Pinned, Free], 0, 1),
            ([Roller, Free], 0, 2),
            ([Roller, Roller], 0, 1),
            ([Roller, Roller], 1, 1),
            ([Free, Free], 0, 3),
            ([Free, Free], 2, 1),
            ([Pinned, Free], 1, 0),
            ([Clamped, Clamped], 3, 0),
        ] {
            assert_eq!(
                rigid_motions(ends, bearings),
                left,
                "{ends:?} with {bearings} bearings"
            );
        }
    }
}

//! A train of axle loads crossing the beam at constant speed: each axle enters at x = 0 and
//! leaves at x = L, as a vertical force (moving forces, the model of EN 1991-2 §6.4 and of
//! CALDINTAV) or as a point mass load/g that follows the beam (moving masses). The axles are
//! given as distances behind the first, or as one of EN 1991-2's High Speed Load Models
//! HSLM-A1…A10 (Annex E, Table E.1, Figure E.2).
//!
//! A moving mass feels the track's curvature under it: its vertical acceleration is
//! ẅ + 2 v ẇ' + v² w'' at the axle. On C0 elements w'' is a train of Dirac deltas at the nodes,
//! so the axle rides on the axis averaged over a contact patch (the disk's kernel, see
//! `Beam::patch_basis_at`) whose half-width comes from the deck's depth: the load dispersed
//! at one to one down to the axis, as for the disk. A moving force needs no curvature and
//! stays a point force.

use super::NodeBasis;

/// HSLM-A trains: (intermediate coaches N, coach length D, bogie axle spacing d, axle force P).
const HSLM_A: [(usize, f64, f64, f64); 10] = [
    (18, 18.0, 2.0, 170.0e3),
    (17, 19.0, 3.5, 200.0e3),
    (16, 20.0, 2.0, 180.0e3),
    (15, 21.0, 3.0, 190.0e3),
    (14, 22.0, 2.0, 170.0e3),
    (13, 23.0, 2.0, 180.0e3),
    (13, 24.0, 2.0, 190.0e3),
    (12, 25.0, 2.5, 190.0e3),
    (11, 26.0, 2.0, 210.0e3),
    (11, 27.0, 2.0, 210.0e3),
];

/// A power car's axles, from its first.
const POWER_CAR: [f64; 4] = [0.0, 3.0, 14.0, 17.0];
/// From a power car's last axle to the first trailer axle, and from the last trailer axle to
/// the rear power car.
const POWER_CAR_GAP: f64 = 3.525;

/// The axles of HSLM-Ak (k from 1 to 10), as distances behind the first, and the axle force.
/// A power car, N + 3 trailer bogies with centres D apart (each two axles d apart), and the
/// mirror power car: 2N + 14 axles.
pub fn hslm(name: &str) -> Option<(Vec<f64>, f64)> {
    let digits = name.strip_prefix('A')?;
    // The names are A1 to A10 as EN 1991-2 writes them: not A01, nor A+1.
    if digits.starts_with('0') || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let k: usize = digits.parse().ok()?;
    let &(n, coach, bogie, force) = HSLM_A.get(k.checked_sub(1)?)?;
    let mut axles = POWER_CAR.to_vec();
    let first = POWER_CAR[3] + POWER_CAR_GAP;
    for b in 0..n + 3 {
        let start = first + b as f64 * coach;
        axles.extend([start, start + bogie]);
    }
    let rear = axles[axles.len() - 1] + POWER_CAR_GAP;
    axles.extend(POWER_CAR.iter().map(|x| rear + x));
    Some((axles, force))
}

/// The names `hslm` knows.
pub const HSLM_NAMES: &str = "A1 to A10";

/// How the axles act on the beam.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TrainModel {
    /// Constant vertical forces.
    MovingForce,
    /// Point masses load/g carried at the train's speed, following the beam's displacement.
    MovingMass,
}

impl TrainModel {
    pub fn name(self) -> &'static str {
        match self {
            TrainModel::MovingForce => "moving-force",
            TrainModel::MovingMass => "moving-mass",
        }
    }
}

#[derive(Clone, Debug)]
pub struct Train {
    /// What the scene calls it: the HSLM name, or "axles".
    pub name: String,
    /// Distances behind the first axle (m), increasing from 0.
    pub axles: Vec<f64>,
    /// Force per axle (N, acting in −Y).
    pub loads: Vec<f64>,
    /// m/s; the first axle is at x = 0 at t = 0.
    pub speed: f64,
    pub model: TrainModel,
    /// Mass per axle (kg): its load over gravity, for moving masses; empty for moving forces.
    pub masses: Vec<f64>,
    /// Half-width of the patch a moving mass rides on (m).
    pub patch: f64,
}

impl Train {
    /// From the first axle to the last.
    pub fn length(&self) -> f64 {
        self.axles.last().copied().unwrap_or(0.0)
    }

    /// The most the axles put on a stretch of track `span` long at once: the largest sum of
    /// loads over axles within `span` of each other.
    pub fn heaviest_within(&self, span: f64) -> f64 {
        let mut heaviest = 0.0_f64;
        let mut sum = 0.0;
        let mut first = 0;
        for (&d, &p) in self.axles.iter().zip(&self.loads) {
            sum += p.abs();
            while d - self.axles[first] > span {
                sum -= self.loads[first].abs();
                first += 1;
            }
            heaviest = heaviest.max(sum);
        }
        heaviest
    }

    /// Where axle a is at time t (it is on a beam of length L while 0 ≤ x ≤ L).
    pub fn position(&self, a: usize, t: f64) -> f64 {
        self.speed * t - self.axles[a]
    }

    /// The axles on a beam of length `length` at t, 0 ≤ position ≤ length: a run of them, as
    /// the positions fall with the distance behind the first (found by bisection: a train
    /// may have thousands of axles, the beam holds a few).
    pub fn on(&self, length: f64, t: f64) -> std::ops::Range<usize> {
        let ahead = self.speed * t;
        let first = self.axles.partition_point(|d| ahead - d > length);
        let end = self.axles.partition_point(|d| ahead - d >= 0.0);
        first..end.max(first)
    }

    /// When the last axle leaves a beam of length `length`.
    pub fn gone(&self, length: f64) -> f64 {
        (self.length() + length) / self.speed
    }
}

/// An axle riding on the beam as a moving mass, at one instant: its mass, its load, and the
/// patch-averaged shape functions at its place with their derivatives along the axis.
pub struct RidingAxle {
    /// Where it is on the axis (m; past an end while its patch still overlaps the beam).
    pub x: f64,
    pub mass: f64,
    pub load: f64,
    pub basis: Vec<NodeBasis>,
}

impl RidingAxle {
    /// ∂r/∂q of the point the axle rides on, X and Y of the beam frame: the rows through which
    /// its inertia m g gᵀ adds to the beam's mass.
    pub fn rows(&self) -> [Vec<(usize, f64)>; 2] {
        super::position_rows(&self.basis)
    }

    /// The part of the axle's acceleration (beam frame) that the beam's displacements and
    /// velocities make as it travels along at `speed`: d²r/dt² = r̈ + 2 v ṙ' + v² r'' at the
    /// moving point, less r̈. `q` and `v` read the mesh's unknowns.
    pub fn convective(
        &self,
        speed: f64,
        q: impl Fn(usize) -> f64,
        v: impl Fn(usize) -> f64,
    ) -> [f64; 2] {
        let mut out = [0.0; 2];
        for nb in &self.basis {
            for (o, i) in out.iter_mut().zip([nb.u, nb.w]) {
                if let Some(i) = i {
                    *o += 2.0 * speed * nb.d[1] * v(i) + speed * speed * nb.d[2] * q(i);
                }
            }
        }
        out
    }

    /// The force the axle exerts on the beam (beam frame), m (g − a), spread over its patch
    /// onto the mesh's unknowns through `add`; `weight` is its load in the beam frame and
    /// `acceleration` its own.
    pub fn spread(
        &self,
        weight: [f64; 2],
        acceleration: [f64; 2],
        mut add: impl FnMut(usize, f64),
    ) -> [f64; 2] {
        let force = [
            weight[0] - self.mass * acceleration[0],
            weight[1] - self.mass * acceleration[1],
        ];
        for nb in &self.basis {
            if let Some(i) = nb.u {
                add(i, nb.d[0] * force[0]);
            }
            if let Some(i) = nb.w {
                add(i, nb.d[0] * force[1]);
            }
        }
        force
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The axles on the beam found by bisection are those whose position lies on it, at every
    /// time of a crossing and at the instants an axle stands on either end.
    #[test]
    fn the_axles_on_the_beam_by_bisection() {
        let (axles, load) = hslm("A1").expect("a known train");
        let train = Train {
            name: "A1".into(),
            loads: vec![load; axles.len()],
            axles,
            speed: 83.0,
            model: TrainModel::MovingForce,
            masses: Vec::new(),
            patch: 0.0,
        };
        let length = 15.0;
        let ends = train
            .axles
            .iter()
            .flat_map(|d| [d / train.speed, (d + length) / train.speed]);
        let times = (0..5000).map(|i| i as f64 * 6e-4 - 0.1).chain(ends);
        for t in times {
            let brute: Vec<usize> = (0..train.axles.len())
                .filter(|&a| (0.0..=length).contains(&train.position(a, t)))
                .collect();
            assert_eq!(train.on(length, t).collect::<Vec<_>>(), brute, "t = {t}");
        }
    }

    /// The most a stretch of track holds at once, against every window of axles counted
    /// by hand: HSLM-A1's axles over spans from 1 to 60 m, and a span shorter than any gap.
    #[test]
    fn the_heaviest_stretch_of_a_train_against_every_window() {
        let (axles, load) = hslm("A1").expect("a known train");
        let loads: Vec<f64> = (0..axles.len())
            .map(|a| load * (1.0 + 0.01 * a as f64))
            .collect();
        let train = Train {
            name: "A1".into(),
            loads,
            axles,
            speed: 83.0,
            model: TrainModel::MovingForce,
            masses: Vec::new(),
            patch: 0.0,
        };
        for span in [0.5, 1.0, 2.0, 3.525, 15.0, 18.0, 60.0] {
            let brute = (0..train.axles.len())
                .map(|i| {
                    (i..train.axles.len())
                        .filter(|&j| train.axles[j] - train.axles[i] <= span)
                        .map(|j| train.loads[j])
                        .sum::<f64>()
                })
                .fold(0.0, f64::max);
            let found = train.heaviest_within(span);
            assert!(
                (found - brute).abs() <= 1e-9 * brute,
                "span {span}: {found} against {brute}"
            );
        }
    }

    /// EN 1991-2 Table E.1 gives each train 2N + 14 axles: A1 50, A2 48, A3 46, A4 44, A5 42,
    /// A6 40, A7 40, A8 38, A9 36, A10 36; the axles increase, and each train is its own
    /// mirror image (power car, coaches, power car).
    #[test]
    fn hslm_axle_counts_and_symmetry() {
        let counts = [50, 48, 46, 44, 42, 40, 40, 38, 36, 36];
        for (k, &count) in counts.iter().enumerate() {
            let (axles, _) = hslm(&format!("A{}", k + 1)).expect("a known train");
            assert_eq!(axles.len(), count, "A{}", k + 1);
            assert!(axles.windows(2).all(|w| w[1] > w[0]));
            let length = axles[axles.len() - 1];
            for (a, b) in axles.iter().zip(axles.iter().rev()) {
                assert!((a + b - length).abs() < 1e-9, "A{} is not symmetric", k + 1);
            }
        }
        for name in ["A0", "A11", "B1", "A01", "A+1", "A", "a1"] {
            assert!(hslm(name).is_none(), "{name}");
        }
    }
}

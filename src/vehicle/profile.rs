//! The running surface's vertical irregularity r(x) (m, positive up), the same under every
//! wheel: piecewise linear through given points and constant beyond them, or a random profile
//! of an ISO 8608 class as a sum of cosines.
//!
//! ISO 8608 gives the displacement's one-sided power spectral density in the spatial frequency
//! n (cycles/m) as G(n) = G(n₀) (n/n₀)⁻², n₀ = 0.1 cycles/m, with G(n₀) = 16·10⁻⁶ m³ for class
//! A (the geometric mean of its band) and four times as much for each class after it. The
//! profile is Σ_k √(2 G(n_k) Δn) cos(2π n_k x + φ_k) over equal steps Δn between the
//! wavelengths asked for, the phases φ_k uniform and drawn from the seed.

/// Scan points a shortest wave of a rough road spans where a disk wheel looks for the crest it
/// rests on: at that spacing the samples find every crest, each refined between its neighbours.
pub const SCAN_PER_WAVE: f64 = 8.0;

/// The most scan points a disk wheel's reach (2 × radius) may need on a rough road: with
/// [`SCAN_PER_WAVE`], a radius of at most 256 shortest waves.
pub const MAX_CREST_SCAN: f64 = 4096.0;

/// ISO 8608's classes, A (smoothest) to H.
pub const ISO_CLASSES: &str = "ABCDEFGH";

/// Cosines of a random profile at the least: enough that the spectrum's shape holds between
/// its limits where they are two decades apart, ISO 8608's usual band.
pub const ISO_TERMS: usize = 200;
/// The most cosines a random profile is drawn with: every wheel sums them at every contact.
pub const MAX_ISO_TERMS: usize = 20_000;

/// How many cosines, evenly spaced in wavenumber, draw a random profile of wavelengths
/// [shortest, longest]: at least [`ISO_TERMS`], and spaced at most half the lowest
/// wavenumber apart. The spectrum falls as n⁻², so its lowest band carries most of the
/// variance, which the cosine at its middle stands for: at half the lowest wavenumber apart the
/// cosines' variance falls 2 % short of the spectrum's, where 200 cosines over three decades
/// fall 43 % short. `None` past [`MAX_ISO_TERMS`].
pub fn iso_terms(shortest: f64, longest: f64) -> Option<usize> {
    let needed = (2.0 * (longest / shortest - 1.0)).ceil();
    (needed <= MAX_ISO_TERMS as f64).then(|| (needed as usize).max(ISO_TERMS))
}

#[derive(Clone, Debug, PartialEq)]
pub enum Profile {
    /// Level: r ≡ 0.
    Smooth,
    /// Through these (x, r), x increasing.
    Points(Vec<[f64; 2]>),
    /// Σ a_k cos(κ_k x + φ_k) with κ_k = κ₀ + k Δκ.
    Cosines(Cosines),
}

/// Cosines of equally spaced wavenumbers: at x their phases turn by Δκ x from one to the next,
/// so rotations carry every term from a few sines and cosines a point, not one per term.
#[derive(Clone, Debug, PartialEq)]
pub struct Cosines {
    /// κ₀ and Δκ (rad/m).
    pub first: f64,
    pub step: f64,
    /// Per term: a_k, cos φ_k, sin φ_k.
    pub terms: Vec<[f64; 3]>,
    /// Σ a_k κ_k², a bound on |r''|, which every disk wheel's contact asks for.
    pub curvature: f64,
    /// The terms as [`Cosines::at`] sums them.
    chunks: Vec<[[f64; LANES]; 3]>,
}

/// Independent chains of rotations a random profile is summed in, term k in chain k mod
/// [`LANES`]: one chain's rotations wait on each other, several overlap and vectorise (a disk
/// wheel's crest search sums the profile thousands of times a step).
const LANES: usize = 4;

/// The terms [`LANES`] at a time, as the sum reads them: a_k cos φ_k, a_k sin φ_k and κ_k,
/// the last chunk filled with terms of no amplitude.
fn chunked(first: f64, step: f64, terms: &[[f64; 3]]) -> Vec<[[f64; LANES]; 3]> {
    terms
        .chunks(LANES)
        .enumerate()
        .map(|(chunk, part)| {
            let mut lanes = [[0.0; LANES]; 3];
            for (l, &[a, cos_phi, sin_phi]) in part.iter().enumerate() {
                lanes[0][l] = a * cos_phi;
                lanes[1][l] = a * sin_phi;
                lanes[2][l] = first + (chunk * LANES + l) as f64 * step;
            }
            lanes
        })
        .collect()
}

impl Cosines {
    /// r, r' and r'' at x: chain l starts at term l's phase and turns by LANES Δκ x a term.
    fn at(&self, x: f64) -> [f64; 3] {
        let (mut tc, mut ts) = ([0.0; LANES], [0.0; LANES]);
        (ts[0], tc[0]) = (self.first * x).sin_cos();
        let (ds, dc) = (self.step * x).sin_cos();
        for l in 1..LANES {
            (tc[l], ts[l]) = (
                tc[l - 1] * dc - ts[l - 1] * ds,
                ts[l - 1] * dc + tc[l - 1] * ds,
            );
        }
        let (rs, rc) = (LANES as f64 * self.step * x).sin_cos();
        let mut sums = [[0.0; LANES]; 3];
        for [ac, asin, k] in &self.chunks {
            for l in 0..LANES {
                let re = ac[l] * tc[l] - asin[l] * ts[l];
                let im = asin[l] * tc[l] + ac[l] * ts[l];
                sums[0][l] += re;
                sums[1][l] -= k[l] * im;
                sums[2][l] -= k[l] * k[l] * re;
                (tc[l], ts[l]) = (tc[l] * rc - ts[l] * rs, ts[l] * rc + tc[l] * rs);
            }
        }
        sums.map(|lanes| lanes.iter().sum())
    }

    /// r at x0 + k h, k = 0..=count: each term turned by its own κ_k h from one point to the
    /// next, the terms independent of each other (a crest scan's samples, where summing each
    /// point afresh turns every term from the first).
    fn along(&self, x0: f64, h: f64, count: usize) -> Vec<f64> {
        let mut terms = self.turns(x0);
        for (z, [ac, asin, _]) in terms.iter_mut().zip(&self.chunks) {
            for l in 0..LANES {
                let (c, s) = (z[0][l], z[1][l]);
                z[0][l] = ac[l] * c - asin[l] * s;
                z[1][l] = asin[l] * c + ac[l] * s;
            }
        }
        let turn = self.turns(h);
        (0..=count)
            .map(|_| {
                let mut sums = [0.0; LANES];
                for (z, w) in terms.iter_mut().zip(&turn) {
                    for l in 0..LANES {
                        sums[l] += z[0][l];
                        let (c, s) = (z[0][l], z[1][l]);
                        z[0][l] = c * w[0][l] - s * w[1][l];
                        z[1][l] = s * w[0][l] + c * w[1][l];
                    }
                }
                sums.iter().sum()
            })
            .collect()
    }

    /// e^{i κ_k x} of every term, as (cos, sin) four terms at a time.
    fn turns(&self, x: f64) -> Vec<[[f64; LANES]; 2]> {
        let (s0, c0) = (self.first * x).sin_cos();
        let (ds, dc) = (self.step * x).sin_cos();
        let (mut c, mut s) = (c0, s0);
        (0..self.chunks.len())
            .map(|_| {
                let mut chunk = [[0.0; LANES]; 2];
                for l in 0..LANES {
                    (chunk[0][l], chunk[1][l]) = (c, s);
                    (c, s) = (c * dc - s * ds, s * dc + c * ds);
                }
                chunk
            })
            .collect()
    }
}

impl Profile {
    /// A random profile of ISO 8608 class `class` (A..H) with wavelengths in [shortest,
    /// longest] m, the phases drawn from `seed`; `None` for a class it does not know or a
    /// band wider than [`MAX_ISO_TERMS`] cosines hold.
    pub fn iso8608(class: char, seed: u64, shortest: f64, longest: f64) -> Option<Profile> {
        let k = ISO_CLASSES.find(class)?;
        let count = iso_terms(shortest, longest)?;
        let g0 = 16.0e-6 * 4.0_f64.powi(k as i32);
        let n0 = 0.1;
        let (lo, hi) = (1.0 / longest, 1.0 / shortest);
        let dn = (hi - lo) / count as f64;
        let mut random = SplitMix(seed);
        let tau = std::f64::consts::TAU;
        let (first, step) = (tau * (lo + 0.5 * dn), tau * dn);
        let terms: Vec<[f64; 3]> = (0..count)
            .map(|i| {
                let n = lo + (i as f64 + 0.5) * dn;
                let g = g0 * (n / n0).powi(-2);
                let (sin, cos) = (tau * random.unit()).sin_cos();
                [(2.0 * g * dn).sqrt(), cos, sin]
            })
            .collect();
        let curvature = (terms.iter().enumerate())
            .map(|(k, t)| t[0] * (first + k as f64 * step).powi(2))
            .sum();
        Some(Profile::Cosines(Cosines {
            first,
            step,
            chunks: chunked(first, step, &terms),
            terms,
            curvature,
        }))
    }

    /// r, r' and r'' at x; on a piecewise-linear profile the slope is the one of the piece
    /// that holds `side` (a point a little on the side the wheel is going), r'' is 0.
    pub fn at(&self, x: f64, side: f64) -> [f64; 3] {
        match self {
            Profile::Smooth => [0.0; 3],
            Profile::Points(p) => {
                let last = p.len() - 1;
                let slope = if side <= p[0][0] || side >= p[last][0] {
                    0.0
                } else {
                    let i = p.partition_point(|q| q[0] <= side).clamp(1, last);
                    (p[i][1] - p[i - 1][1]) / (p[i][0] - p[i - 1][0])
                };
                [linear(p, x), slope, 0.0]
            }
            Profile::Cosines(c) => c.at(x),
        }
    }

    /// r at x0 + k h, k = 0..=count: a crest scan's samples.
    pub fn along(&self, x0: f64, h: f64, count: usize) -> Vec<f64> {
        match self {
            Profile::Cosines(c) => c.along(x0, h, count),
            _ => (0..=count)
                .map(|k| self.at(x0 + k as f64 * h, x0 + k as f64 * h)[0])
                .collect(),
        }
    }

    /// Each kink with the slopes on its two sides: (x, left, right).
    pub fn corners(&self) -> Vec<(f64, f64, f64)> {
        let Profile::Points(p) = self else {
            return Vec::new();
        };
        let slope = |i: usize| -> f64 {
            if i == 0 || i >= p.len() {
                0.0
            } else {
                (p[i][1] - p[i - 1][1]) / (p[i][0] - p[i - 1][0])
            }
        };
        (0..p.len())
            .map(|i| (p[i][0], slope(i), slope(i + 1)))
            .collect()
    }

    /// A bound on |r''| (1/m): Σ a_k κ_k² of a random profile, 0 where the faces are straight.
    /// Where it stays below a disk wheel's 1/radius the disk touches every hollow it passes
    /// and one crest at a time; past it the disk may bridge a hollow between two crests.
    pub fn curvature_bound(&self) -> f64 {
        match self {
            Profile::Cosines(c) => c.curvature,
            _ => 0.0,
        }
    }

    /// The shortest wavelength of a random profile (m); `None` for straight faces.
    pub fn shortest_wave(&self) -> Option<f64> {
        match self {
            Profile::Cosines(c) if !c.terms.is_empty() => {
                Some(std::f64::consts::TAU / (c.first + (c.terms.len() - 1) as f64 * c.step))
            }
            _ => None,
        }
    }

    /// Where a disk wheel of `radius` may bridge a hollow (the road bends faster than the
    /// disk somewhere), how many spaces its reach is scanned at for the crest it rests on;
    /// `None` where it touches one crest at a time.
    pub fn crest_scan(&self, radius: f64) -> Option<f64> {
        if self.curvature_bound() * radius < 1.0 {
            return None;
        }
        let wave = self.shortest_wave().unwrap_or(2.0 * radius);
        Some((2.0 * radius * SCAN_PER_WAVE / wave).ceil())
    }

    /// Where the slope jumps: a wheel crossing one of these is a breakpoint.
    pub fn kinks(&self) -> Vec<f64> {
        match self {
            Profile::Points(p) => p.iter().map(|q| q[0]).collect(),
            _ => Vec::new(),
        }
    }
}

/// r at x on a piecewise-linear profile, constant beyond its ends.
fn linear(p: &[[f64; 2]], x: f64) -> f64 {
    let last = p.len() - 1;
    if x <= p[0][0] {
        return p[0][1];
    }
    if x >= p[last][0] {
        return p[last][1];
    }
    let i = p.partition_point(|q| q[0] <= x).clamp(1, p.len() - 1);
    let (a, b) = (p[i - 1], p[i]);
    a[1] + (b[1] - a[1]) * (x - a[0]) / (b[0] - a[0])
}

/// Steele, Lea and Flood's SplitMix64: a seeded stream of uniform numbers, which is all a
/// profile's phases need, reproducible on any machine.
struct SplitMix(u64);

impl SplitMix {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ramp_is_linear_between_its_points_and_constant_beyond() {
        let p = Profile::Points(vec![[0.0, 0.0], [10.0, 0.01], [20.0, 0.01]]);
        assert_eq!(p.at(-5.0, -4.0), [0.0, 0.0, 0.0]);
        let mid = p.at(5.0, 5.1);
        assert!((mid[0] - 0.005).abs() < 1e-15 && (mid[1] - 0.001).abs() < 1e-15);
        assert_eq!(p.at(10.0, 10.1)[1], 0.0);
        assert!((p.at(10.0, 9.9)[1] - 0.001).abs() < 1e-15);
        assert_eq!(p.at(25.0, 25.1), [0.01, 0.0, 0.0]);
    }

    /// The turned phases against each term's own sine and cosine, out to 400 m (phases of
    /// thousands of radians): r, r' and r'' within 10⁻¹² of their sizes.
    #[test]
    fn turned_phases_are_each_terms_own() {
        let Some(Profile::Cosines(c)) = Profile::iso8608('B', 3, 0.5, 50.0) else {
            panic!("class B is known");
        };
        for x in [-400.0, -3.7, 0.0, 0.123, 25.0, 399.9] {
            let turned = Profile::Cosines(c.clone()).at(x, x);
            let mut direct = [0.0; 3];
            let mut size = [0.0; 3];
            for (i, &[a, cos_phi, sin_phi]) in c.terms.iter().enumerate() {
                let k = c.first + i as f64 * c.step;
                let phi = sin_phi.atan2(cos_phi);
                let (s, co) = (k * x + phi).sin_cos();
                direct[0] += a * co;
                direct[1] -= a * k * s;
                direct[2] -= a * k * k * co;
                size[0] += a;
                size[1] += a * k;
                size[2] += a * k * k;
            }
            for j in 0..3 {
                assert!(
                    (turned[j] - direct[j]).abs() < 1e-12 * size[j],
                    "x {x}, derivative {j}: {} against {}",
                    turned[j],
                    direct[j]
                );
            }
        }
    }

    /// A scan's samples, each term turned along the grid, against the profile summed at each
    /// point: within 10⁻¹¹ of the amplitudes' sum over 4096 points, as far out as 400 m (the
    /// turns' round-off grows with the points). The samples only choose which crests are
    /// refined, by margins of the profile's curvature times the spacing squared, far larger.
    #[test]
    fn samples_along_a_grid_are_the_profile_at_its_points() {
        let p = Profile::iso8608('H', 5, 0.1, 20.0).expect("class H is known");
        let Profile::Cosines(c) = &p else {
            panic!("a random profile");
        };
        let size: f64 = c.terms.iter().map(|t| t[0]).sum();
        for (x0, h, count) in [(-3.7, 0.01, 64), (395.0, 1.0e-3, 4096)] {
            let along = p.along(x0, h, count);
            assert_eq!(along.len(), count + 1);
            for (k, r) in along.iter().enumerate() {
                let x = x0 + k as f64 * h;
                let at = p.at(x, x)[0];
                assert!((r - at).abs() < 1e-11 * size, "x {x}: {r} against {at}");
            }
        }
    }

    /// The variance of a random profile is the integral of its spectrum: ∫ G(n) dn between
    /// the limits, G(n₀) n₀² (1/n_lo − 1/n_hi), which the cosines' Σ a²/2 reproduces to the
    /// midpoint rule's error, whatever the band: ISO 8608's usual two decades, and three and
    /// four, where 200 cosines fall 43 % and 91 % short. The usual band keeps its 200.
    #[test]
    fn an_iso_profile_carries_its_class_variance() {
        for (shortest, longest) in [(0.5, 50.0), (0.1, 100.0), (0.01, 100.0), (0.5, 5.0)] {
            let (lo, hi) = (1.0 / longest, 1.0 / shortest);
            let Some(Profile::Cosines(c)) = Profile::iso8608('C', 7, shortest, longest) else {
                panic!("class C is known");
            };
            let variance: f64 = c.terms.iter().map(|t| 0.5 * t[0] * t[0]).sum();
            let exact = 256.0e-6 * 0.01 * (1.0 / lo - 1.0 / hi);
            assert!(
                (variance / exact - 1.0).abs() < 0.025,
                "[{shortest}, {longest}]: {variance} against {exact}"
            );
        }
        assert_eq!(iso_terms(0.5, 50.0), Some(ISO_TERMS));
        assert!(Profile::iso8608('I', 1, 0.5, 50.0).is_none());
        assert!(Profile::iso8608('C', 1, 1e-6, 1e9).is_none());
    }
}

//! The outputs of a beam run, recorded at each output time from what the run computed there
//! ([`Sample`]): the history rows (probes, the disk, energies, reactions), the envelopes along
//! the beam, and the deformed shapes and animation frames. They observe; they compute no
//! physics.

use super::ledger::Energy;
use super::{BeamRow, Envelope, Frame};
use crate::beam::load::Probe;
use crate::beam::{Beam, BeamModel, PointDisplacement};
use crate::disk::DiskObservation;

/// The state at one output time, as the sensors see it.
pub(super) struct Sample<'s> {
    pub t: f64,
    pub q: &'s [f64],
    /// The mesh's accelerations, the modes above the cutoff left out.
    pub a: &'s [f64],
    /// Displacements at the beam's sample points.
    pub along: &'s [PointDisplacement],
    /// Each disk while it is on or over the beam (none once they have all left).
    pub disks: Vec<Option<DiskObservation>>,
    /// The flying disk's gap to the beam (0 while it rolls), and which disk flies.
    pub gap: f64,
    pub flying: Option<usize>,
    pub energy: Energy,
    pub reactions: [[f64; 3]; 2],
    pub vehicles: Option<crate::coupling::vehicles::VehicleObservation>,
}

/// The rows of `history.csv`.
pub(super) struct History<'a> {
    pub beam: &'a Beam,
    pub probes: &'a [Probe],
    pub rows: Vec<BeamRow>,
}

impl History<'_> {
    pub fn record(&mut self, s: &Sample) {
        let beam = self.beam;
        self.rows.push(BeamRow {
            t: s.t,
            probes: self
                .probes
                .iter()
                .map(|p| beam.displacement_at(s.q, p.x))
                .collect(),
            disks: s.disks.clone(),
            w_under: s
                .disks
                .iter()
                .map(|d| d.map_or(f64::NAN, |d| beam.displacement_at(s.q, d.s).w))
                .collect(),
            kinetic: s.energy.kinetic,
            strain: s.energy.strain,
            potential: s.energy.potential,
            work: s.energy.work,
            dissipated: s.energy.dissipated,
            impact: s.energy.impact,
            gap: s.gap,
            flying: s.flying,
            accelerations: self
                .probes
                .iter()
                .map(|p| beam.displacement_at(s.a, p.x).w)
                .collect(),
            reactions: s.reactions,
            vehicles: s.vehicles.clone(),
        });
    }
}

impl Envelope {
    /// Extremes of u, w and φ over time at the sample points `x`, and the axis' stretch.
    pub(super) fn new(x: Vec<f64>) -> Self {
        let n = x.len();
        Envelope {
            x,
            min: vec![
                PointDisplacement {
                    u: f64::INFINITY,
                    w: f64::INFINITY,
                    phi: f64::INFINITY,
                };
                n
            ],
            max: vec![
                PointDisplacement {
                    u: f64::NEG_INFINITY,
                    w: f64::NEG_INFINITY,
                    phi: f64::NEG_INFINITY,
                };
                n
            ],
            stretch_max: f64::NEG_INFINITY,
            draw_in_max: 0.0,
            a_max: (0.0, 0.0, 0.0),
        }
    }

    /// The envelope from the extremes of the stations' (u, w, φ, a) and of the stretch, as
    /// watched (`Recorder::watch`).
    pub(super) fn from_stations(&self, ranges: &[crate::run::extremes::Range]) -> Envelope {
        let mut e = Envelope::new(self.x.clone());
        for (k, r) in ranges.chunks(4).take(self.x.len()).enumerate() {
            e.min[k] = PointDisplacement {
                u: r[0].min,
                w: r[1].min,
                phi: r[2].min,
            };
            e.max[k] = PointDisplacement {
                u: r[0].max,
                w: r[1].max,
                phi: r[2].max,
            };
            let (a, t) = r[3].largest_magnitude();
            if a > e.a_max.0 {
                e.a_max = (a, self.x[k], t);
            }
        }
        if let Some(stretch) = ranges.get(4 * self.x.len()) {
            e.stretch_max = stretch.max;
        }
        if let Some(draw_in) = ranges.get(4 * self.x.len() + 1).filter(|r| r.seen()) {
            e.draw_in_max = draw_in.max;
        }
        e
    }
}

/// How much longer than the span the axis through the sample points `x` is, displaced by
/// `along`: each chord's growth, ((h + Δu)² + Δw² − h²) / (|chord| + h), with Δu, Δw along and
/// across the undeformed axis (the global ones would count an inclined chord's first-order
/// turning as growth), since the length minus h would cancel all but a few digits of a stretch
/// 10⁻⁷ of the span; the samples span the axis, so their h add up to its length. A linear or
/// modal beam whose end may slide grows by Δu alone, its strain u': the exact beam draws that
/// end in by the ½ ∫ w'² dx its chords would add (over HSLM's 15 m bridge the roller moves
/// 0.27 mm, the axis lengthens 3·10⁻³ mm). Held at both ends, the exact axis stretches by it,
/// and the chords measure it to second order.
pub(super) fn stretch(beam: &Beam, x: &[f64], along: &[PointDisplacement]) -> f64 {
    let strain_alone = grows_by_strain_alone(beam);
    chords(beam, x, along)
        .map(|(du, growth)| if strain_alone { du } else { growth })
        .sum()
}

/// How far a linear or modal beam's end that may slide would draw in as the axis through the
/// sample points bends, which its u, first-order, leaves out: what the chords add to the strain
/// [`stretch`] reads (½ ∫ w'² dx to second order). 0 where [`stretch`] reads the chords.
pub(super) fn draw_in(beam: &Beam, x: &[f64], along: &[PointDisplacement]) -> f64 {
    if !grows_by_strain_alone(beam) {
        return 0.0;
    }
    chords(beam, x, along).map(|(du, growth)| growth - du).sum()
}

/// Per chord between consecutive sample points, Δu along the undeformed axis and the chord's
/// growth ((h + Δu)² + Δw² − h²) / (|chord| + h).
fn chords<'a>(
    beam: &'a Beam,
    x: &'a [f64],
    along: &'a [PointDisplacement],
) -> impl Iterator<Item = (f64, f64)> + 'a {
    x.windows(2).zip(along.windows(2)).map(|(x, d)| {
        let [du, dw] = beam.to_local([d[1].u - d[0].u, d[1].w - d[0].w]);
        let h = x[1] - x[0];
        let chord = ((h + du) * (h + du) + dw * dw).sqrt();
        (du, (du * (2.0 * h + du) + dw * dw) / (chord + h))
    })
}

/// Whether [`stretch`] reads a linear or modal beam's strain u' alone.
pub(super) fn grows_by_strain_alone(beam: &Beam) -> bool {
    beam.spec.model != BeamModel::Exact && !beam.spec.holds_u_at_both_ends()
}

/// Deformed shapes at the requested times, and the animation's frames on a coarse grid with
/// the angle the disk has turned through (the trapezoidal rule on Ω over the output rows).
pub(super) struct Pictures<'a> {
    pub shape_times: &'a [f64],
    /// The frames' spacing in time; `None` records no frames.
    pub frame_every: Option<f64>,
    pub shapes: Vec<(f64, Vec<PointDisplacement>)>,
    pub frames: Vec<Frame>,
    /// Per disk, (t, Ω, angle) at the last row with it on the beam.
    pub turned: Vec<(f64, f64, f64)>,
    /// Per vehicle, its wheels' distances behind its first axle.
    pub wheel_offsets: Vec<Vec<f64>>,
}

impl Pictures<'_> {
    /// Whether a sample at t is drawn: a frame of the animation or a shape asked for.
    pub fn draws_at(&self, t: f64) -> bool {
        self.next_frame(t) || self.shape_times.iter().any(|&st| (st - t).abs() < 1e-9)
    }

    fn next_frame(&self, t: f64) -> bool {
        self.frame_every
            .is_some_and(|every| self.frames.last().is_none_or(|f| t >= f.t + every - 1e-9))
    }

    /// Record the sample.
    pub fn record(&mut self, s: &Sample) {
        let t = s.t;
        for (d, turned) in s.disks.iter().zip(self.turned.iter_mut()) {
            if let Some(d) = d {
                let (t0, w0, angle) = *turned;
                *turned = (t, d.omega, angle + 0.5 * (w0 + d.omega) * (t - t0));
            }
        }
        if self.next_frame(t) {
            self.frames.push(Frame {
                t,
                along: s.along.to_vec(),
                // After the riders have left, the samples hold no disks.
                disks: self
                    .turned
                    .iter()
                    .enumerate()
                    .map(|(k, turned)| {
                        let d = s.disks.get(k).copied().flatten();
                        let gap = if s.flying == Some(k) { s.gap } else { 0.0 };
                        d.map(|d| (d.s, turned.2, gap))
                    })
                    .collect(),
                wheels: s.vehicles.as_ref().map_or_else(Vec::new, |v| {
                    v.x.iter()
                        .zip(&self.wheel_offsets)
                        .flat_map(|(x, offsets)| offsets.iter().map(move |d| x - d))
                        .collect()
                }),
            });
        }
        if self.shape_times.iter().any(|&st| (st - t).abs() < 1e-9) {
            self.shapes.push((t, s.along.to_vec()));
        }
    }
}

/// How many equal windows the run is cut into for [`WindowedMeans`].
pub const MEAN_WINDOWS: usize = 10;

/// Gauss–Legendre's three points on [−1, 1] and their weights: exact for the cubic dense
/// output times the smooth window over a step's piece.
const GAUSS: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

/// Each probe's deflection averaged over equal windows of the run with a Hann weight, the
/// integral taken on every step's dense output. The weight's leakage falls as the cube of a
/// mode's frequency, so the fast modes whose phase decides the extremes leave the means
/// alone; integrated on the output grid instead, they would alias into them
/// (docs/numerics.md, "The work–precision grids").
pub struct WindowedMeans {
    length: f64,
    /// Σ Hann · w per probe and window, probe-major.
    sums: Vec<f64>,
    weights: [f64; MEAN_WINDOWS],
    /// How much of each window the steps have covered: a window the run did not cover whole
    /// has no mean.
    covered: [f64; MEAN_WINDOWS],
}

impl WindowedMeans {
    pub fn new(duration: f64, probes: usize) -> Self {
        WindowedMeans {
            length: duration / MEAN_WINDOWS as f64,
            sums: vec![0.0; probes * MEAN_WINDOWS],
            weights: [0.0; MEAN_WINDOWS],
            covered: [0.0; MEAN_WINDOWS],
        }
    }

    /// Add the step from t0 to t1, whose probes' deflections at t are `w(t)`.
    pub fn record_span(&mut self, t0: f64, t1: f64, w: impl Fn(f64) -> Vec<f64>) {
        let probes = self.sums.len() / MEAN_WINDOWS;
        let mut a = t0;
        while a < t1 {
            // a may sit on a window's end up to rounding: it then starts the next window.
            let mut k = (a / self.length) as usize;
            if (k + 1) as f64 * self.length - a <= 1e-12 * self.length {
                k += 1;
            }
            if k >= MEAN_WINDOWS {
                break;
            }
            let start = k as f64 * self.length;
            let b = t1.min(start + self.length);
            if b <= a {
                break;
            }
            let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
            for (x, gw) in GAUSS {
                let t = mid + half * x;
                let hann = (std::f64::consts::PI * (t - start) / self.length)
                    .sin()
                    .powi(2);
                let weight = gw * half * hann;
                self.weights[k] += weight;
                for (p, wp) in w(t).iter().enumerate().take(probes) {
                    self.sums[p * MEAN_WINDOWS + k] += weight * wp;
                }
            }
            self.covered[k] += b - a;
            a = b;
        }
    }

    /// The means, probe-major, of the windows the run covered from the first on (a run that
    /// stopped early has fewer).
    pub fn means(&self) -> Vec<f64> {
        let whole = self
            .covered
            .iter()
            .take_while(|&&c| c >= self.length * (1.0 - 1e-9))
            .count();
        let probes = self.sums.len() / MEAN_WINDOWS;
        (0..probes)
            .flat_map(|p| (0..whole).map(move |k| (p, k)))
            .map(|(p, k)| self.sums[p * MEAN_WINDOWS + k] / self.weights[k])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::{WindowedMeans, MEAN_WINDOWS};

    fn means_of(steps: usize, w: impl Fn(f64) -> Vec<f64>) -> Vec<f64> {
        let mut m = WindowedMeans::new(3.0, 1);
        let h = 3.0 / steps as f64;
        for i in 0..steps {
            m.record_span(i as f64 * h, (i + 1) as f64 * h, &w);
        }
        m.means()
    }

    /// The Hann-weighted mean of c + t over a window is c plus the window's centre, since the
    /// weight is symmetric about it: three Gauss points a step give it to rounding once the
    /// steps are short against the window.
    #[test]
    fn a_linear_signal_averages_to_the_windows_centre() {
        for steps in [300, 4001] {
            let means = means_of(steps, |t| vec![0.5 + t]);
            assert_eq!(means.len(), MEAN_WINDOWS);
            for (k, m) in means.iter().enumerate() {
                let centre = (k as f64 + 0.5) * 0.3;
                assert!(
                    (m - (0.5 + centre)).abs() < 1e-10,
                    "{steps} steps: {means:?}"
                );
            }
        }
    }

    /// A sine ten periods to a window is filtered to its Hann leakage, at most
    /// 2 (2π)² / (ωL ((ωL)² − (2π)²)) of its amplitude (the window's transform; 3.7·10⁻⁴ at
    /// ωL = 60); three Gauss points a step have converged it once a period spans ten steps (a
    /// quarter of the steps gives the same to 10⁻⁹).
    #[test]
    fn a_fast_sine_is_filtered_to_the_windows_leakage() {
        let omega = 200.0;
        let sine = |t: f64| vec![(omega * t).sin()];
        let (coarse, fine) = (means_of(1001, sine), means_of(4001, sine));
        let (wl, two_pi) = (omega * 0.3, std::f64::consts::TAU);
        let leakage = 2.0 * two_pi * two_pi / (wl * (wl * wl - two_pi * two_pi));
        for (c, f) in coarse.iter().zip(&fine) {
            assert!(f.abs() <= leakage, "{fine:?} against {leakage:e}");
            assert!((c - f).abs() < 1e-9, "{coarse:?} against {fine:?}");
        }
    }

    /// A run that stops inside a window has means only for the windows before it.
    #[test]
    fn an_unfinished_window_has_no_mean() {
        let mut m = WindowedMeans::new(1.0, 1);
        m.record_span(0.0, 0.25, |_| vec![1.0]);
        assert_eq!(m.means(), vec![1.0, 1.0]);
    }
}

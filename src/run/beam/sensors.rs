//! The outputs of a beam run, recorded at each output time from what the run computed there
//! ([`Sample`]): the history rows (probes, the disk, energies, reactions), the envelopes along
//! the beam, and the deformed shapes and animation frames. They observe; they compute no
//! physics.

use super::ledger::Energy;
use super::{BeamRow, Envelope, Frame};
use crate::beam::load::Probe;
use crate::beam::{Beam, PointDisplacement};
use crate::rolling::DiskObservation;

/// The state at one output time, as the sensors see it.
pub(super) struct Sample<'s> {
    pub t: f64,
    pub q: &'s [f64],
    /// The mesh's accelerations, the modes above the cutoff left out.
    pub a: &'s [f64],
    /// Displacements at the beam's sample points.
    pub along: &'s [PointDisplacement],
    /// Vertical accelerations at the beam's sample points.
    pub along_a: &'s [f64],
    pub disk: Option<DiskObservation>,
    /// The flying disk's gap to the beam (0 while it rolls).
    pub gap: f64,
    pub energy: Energy,
    pub reactions: [[f64; 3]; 2],
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
            disk: s.disk,
            w_under: s
                .disk
                .map_or(f64::NAN, |d| beam.displacement_at(s.q, d.s).w),
            kinetic: s.energy.kinetic,
            strain: s.energy.strain,
            potential: s.energy.potential,
            work: s.energy.work,
            dissipated: s.energy.dissipated,
            impact: s.energy.impact,
            gap: s.gap,
            accelerations: self
                .probes
                .iter()
                .map(|p| beam.displacement_at(s.a, p.x).w)
                .collect(),
            reactions: s.reactions,
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
            a_max: (0.0, 0.0, 0.0),
        }
    }

    pub(super) fn record(&mut self, s: &Sample) {
        // Each chord's growth, ((h + Δu)² + Δw² − h²) / (|chord| + h): the length minus h
        // would cancel all but a few digits of a stretch 10⁻⁷ of the span, and the samples
        // span the axis, so their h add up to its length.
        let stretch: f64 = self
            .x
            .windows(2)
            .zip(s.along.windows(2))
            .map(|(x, d)| {
                let (h, du, dw) = (x[1] - x[0], d[1].u - d[0].u, d[1].w - d[0].w);
                let chord = ((h + du) * (h + du) + dw * dw).sqrt();
                (du * (2.0 * h + du) + dw * dw) / (chord + h)
            })
            .sum();
        self.stretch_max = self.stretch_max.max(stretch);
        for (k, a) in s.along_a.iter().enumerate() {
            if a.abs() > self.a_max.0 {
                self.a_max = (a.abs(), self.x[k], s.t);
            }
        }
        for (k, d) in s.along.iter().enumerate() {
            let (lo, hi) = (&mut self.min[k], &mut self.max[k]);
            lo.u = lo.u.min(d.u);
            lo.w = lo.w.min(d.w);
            lo.phi = lo.phi.min(d.phi);
            hi.u = hi.u.max(d.u);
            hi.w = hi.w.max(d.w);
            hi.phi = hi.phi.max(d.phi);
        }
    }
}

/// Deformed shapes at the requested times, and the animation's frames on a coarse grid with
/// the angle the disk has turned through (the trapezoidal rule on Ω over the output rows).
pub(super) struct Pictures<'a> {
    pub shape_times: &'a [f64],
    /// The frames' spacing in time; `None` records no frames.
    pub frame_every: Option<f64>,
    pub shapes: Vec<(f64, Vec<PointDisplacement>)>,
    pub frames: Vec<Frame>,
    /// (t, Ω, angle) at the last row with the disk on the beam.
    pub turned: (f64, f64, f64),
}

impl Pictures<'_> {
    pub fn record(&mut self, s: &Sample) {
        let t = s.t;
        if let Some(d) = s.disk {
            let (t0, w0, angle) = self.turned;
            self.turned = (t, d.omega, angle + 0.5 * (w0 + d.omega) * (t - t0));
        }
        if self
            .frame_every
            .is_some_and(|every| self.frames.last().is_none_or(|f| t >= f.t + every - 1e-9))
        {
            self.frames.push(Frame {
                t,
                along: s.along.to_vec(),
                disk: s.disk.map(|d| (d.s, self.turned.2, s.gap)),
            });
        }
        if self.shape_times.iter().any(|&st| (st - t).abs() < 1e-9) {
            self.shapes.push((t, s.along.to_vec()));
        }
    }
}

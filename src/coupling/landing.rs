//! The disk off the beam and back on it (issue 18): where a flying disk is against the track
//! it would roll on, and what a landing does to the disk and the beam.
//!
//! **Gap.** The track is the patch-averaged axis the consistent coupling rolls the disk on,
//! at the beam's present displacements. The centre of a disk resting on it at material point
//! s is c(s) = r(s) + a n(s); the flying centre's nearest such point s* makes
//! (c − c(s*))·t(s*) = 0, found by Newton (d c(s)/ds = (|r'| − aψ_s) t), and the gap is
//! (c − c(s*))·n(s*): zero when the disk touches, as on a rigid curve.
//!
//! **Landing.** A plastic landing (the contact sticks, normally and tangentially) leaves
//! disk and beam moving as the coupled system does: velocities ż' of z = (q, s). The impulse
//! acts between disk and beam only, at the contact, and the coupled motions are exactly those
//! whose velocities J ż (beam v; disk centre velocity and spin) keep the contact, so the
//! momenta the impulse leaves unchanged are the free momenta seen along the coupled motions:
//! Jᵀ M_free u' = Jᵀ M_free u, and with u' = J ż' that is M_c ż' = Jᵀ M_free u, M_c = Jᵀ M_free J
//! the coupled mass matrix the run already assembles. The rows of J for the disk are the
//! consistent coupling's own (its added mass m g_Xᵀ g_X + m g_Yᵀ g_Y + C g_θᵀ g_θ), so
//! Jᵀ M_free u = M v + m u_X g_X + m u_Y g_Y + C Ω g_θ. Any rigid motion of disk and free beam
//! together is a coupled motion, so linear and angular momentum are conserved across the
//! landing; the kinetic energy lost is ½uᵀM_free u − ½ż'ᵀM_c ż'.

use super::contact::AxisPoint;
use super::{Coupling, DiskOnBeam};
use crate::linalg::{self, SparseLu};

/// A flying disk against the beam.
#[derive(Clone, Copy, Debug)]
pub struct BeamGap {
    /// The track's nearest material point.
    pub s: f64,
    /// Distance from the centre to where it would rest there, along the normal.
    pub gap: f64,
    /// The nearest point is an end of the beam and the centre lies beyond it.
    pub past_end: bool,
}

/// What a landing leaves.
pub struct Landing {
    /// The coupled state (z, ż) just after it, in the model's unknowns.
    pub z: Vec<f64>,
    pub zd: Vec<f64>,
    /// Kinetic energy it took (J).
    pub energy_lost: f64,
}

/// Newton iterations for the nearest point; each step is limited to a radius along the beam.
const NEAREST_ITERATIONS: usize = 50;

impl DiskOnBeam<'_> {
    /// The gap of a flying disk's centre (global) over the beam displaced `q` (the model's
    /// unknowns), its nearest point searched from `s`.
    pub fn gap(&self, q: &[f64], centre: [f64; 2], s: f64) -> BeamGap {
        let beam = self.beam();
        let a = self.spec.disk.radius;
        let origin = beam.spec.from;
        let c = beam.to_local([centre[0] - origin[0], centre[1] - origin[1]]);
        let q = self.loaded.to_mesh(q);
        let still = vec![0.0; q.len()];
        let length = beam.length;
        let at = |s: f64| AxisPoint::at(beam, &q, &still, s, 0.0, self.spec.patch);
        let mut s = s.clamp(0.0, length);
        for _ in 0..NEAREST_ITERATIONS {
            let p = at(s);
            let rest = p.centre(a);
            let d = [c[0] - rest[0].v, c[1] - rest[1].v];
            let (t, n) = (p.tangent(), p.normal());
            let f = d[0] * t[0] + d[1] * t[1];
            let h = p.rp.v - a * p.psi_s.v;
            let df = -h + p.psi_s.v * (d[0] * n[0] + d[1] * n[1]);
            let step = if df < 0.0 {
                -f / df
            } else {
                f / h.max(f64::MIN_POSITIVE)
            }
            .clamp(-a, a);
            let next = (s + step).clamp(0.0, length);
            let done = (next - s).abs() <= 1e-14 * (1.0 + length);
            s = next;
            if done {
                break;
            }
        }
        let p = at(s);
        let rest = p.centre(a);
        let d = [c[0] - rest[0].v, c[1] - rest[1].v];
        let (t, n) = (p.tangent(), p.normal());
        let along = d[0] * t[0] + d[1] * t[1];
        BeamGap {
            s,
            gap: d[0] * n[0] + d[1] * n[1],
            past_end: (s <= 0.0 && along < 0.0) || (s >= length && along > 0.0),
        }
    }

    /// The plastic landing at t of the disk flying at `velocity` (global) with spin `omega`
    /// on the beam at displacements `q` and velocities `v` (the model's unknowns), touching
    /// at material point `s`. `None` for a coupling other than the consistent one, whose rows
    /// are not the disk's velocities, or where the coupled mass cannot be factorised.
    pub fn land(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        s: f64,
        velocity: [f64; 2],
        omega: f64,
    ) -> Option<Landing> {
        if self.spec.coupling != Coupling::Consistent {
            return None;
        }
        let n = self.n;
        let z: Vec<f64> = q.iter().copied().chain([s]).collect();
        let still: Vec<f64> = v.iter().copied().chain([0.0]).collect();
        let added = self.added_mass(&self.contact(t, &z, &still));
        let local = self.beam().to_local(velocity);
        let disk = [local[0], local[1], omega];
        let mut momenta = vec![0.0; n + 1];
        linalg::mul(self.loaded.model_mass(), v, &mut momenta[..n]);
        let beam_kinetic = 0.5 * v.iter().zip(&momenta).map(|(a, b)| a * b).sum::<f64>();
        for ((w, row), u) in added.iter().zip(disk) {
            for &(i, g) in row {
                momenta[i] += w * u * g;
            }
        }
        let mut zd = momenta.clone();
        SparseLu::factor(&self.mass_matrix(&added), None)?.solve_in_place(&mut zd);
        let (m, c) = (self.spec.disk.mass, self.spec.disk.inertia());
        let before = beam_kinetic
            + 0.5 * m * (velocity[0] * velocity[0] + velocity[1] * velocity[1])
            + 0.5 * c * omega * omega;
        let after = 0.5 * zd.iter().zip(&momenta).map(|(a, b)| a * b).sum::<f64>();
        zd.iter().all(|x| x.is_finite()).then_some(Landing {
            z,
            zd,
            energy_lost: before - after,
        })
    }
}

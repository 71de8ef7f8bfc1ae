//! The disk off the beam and back on it: where a flying disk is against the track
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
//! landing; the kinetic energy lost is ½uᵀM_free u − ½ż'ᵀM_c ż'. A train's moving masses ride
//! with the beam: their inertia m g gᵀ is the beam's on both sides of the impulse, and the work
//! they do on it through the impulse is minus the change of their ½ m (g·v)².

use super::contact::AxisPoint;
use super::{Coupling, DiskOnBeam};
use crate::linalg::{self, Assembly, LowRank, SparseLu};

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
    /// Kinetic energy it took (J), the moving masses' share of the beam's included.
    pub energy_lost: f64,
    /// What the train's moving masses, riding with the beam, did on it as the impulse changed
    /// the beam's velocity under them: minus the change of ½ m (g·v)² (J).
    pub axle_work: f64,
}

/// Newton iterations for the nearest point; each step is limited to a radius along the beam.
const NEAREST_ITERATIONS: usize = 50;

impl DiskOnBeam<'_> {
    /// The gap of a flying disk's centre (global) over the beam displaced `q` (the model's
    /// unknowns), its nearest point searched from `s`.
    pub fn gap(&self, q: &[f64], centre: [f64; 2], s: f64) -> BeamGap {
        let beam = self.beam();
        let a = self.spec().disk.radius;
        let origin = beam.spec.from;
        let c = beam.to_local([centre[0] - origin[0], centre[1] - origin[1]]);
        let q = self.loaded.to_mesh(q);
        let still = vec![0.0; q.len()];
        let length = beam.length;
        let at = |s: f64| AxisPoint::at(beam, &q, &still, s, 0.0, self.spec().patch);
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
        if self.spec().coupling != Coupling::Consistent {
            return None;
        }
        let n = self.n;
        let z: Vec<f64> = q.iter().copied().chain([s]).collect();
        let still: Vec<f64> = v.iter().copied().chain([0.0]).collect();
        let added = self.added_mass(&self.disks[0], &self.contact(0, t, &z, &still));
        let local = self.beam().to_local(velocity);
        let disk = [local[0], local[1], omega];
        // The train's moving masses ride with the beam: their inertia m g gᵀ joins the
        // beam's on both sides of the impulse (their prescribed motion along the track is the
        // same just before and after it, and drops out).
        let axles = self.loaded.axle_inertia(t);
        let masses = |v: &[f64]| axle_kinetic(&axles, v);
        let mut momenta = vec![0.0; n + 1];
        linalg::mul(self.loaded.model_mass(), v, &mut momenta[..n]);
        let beam_kinetic =
            0.5 * v.iter().zip(&momenta).map(|(a, b)| a * b).sum::<f64>() + masses(v);
        for (m, row) in &axles {
            let rate = row.iter().map(|&(i, g)| g * v[i]).sum::<f64>();
            row.iter().for_each(|&(i, g)| momenta[i] += m * rate * g);
        }
        for ((w, row), u) in added.iter().zip(disk) {
            for &(i, g) in row {
                momenta[i] += w * u * g;
            }
        }
        let mut zd = momenta.clone();
        let coupled: Vec<_> = added.iter().chain(&axles).cloned().collect();
        SparseLu::factor(&self.mass_matrix(&coupled), None)?.solve_in_place(&mut zd);
        let (m, c) = (self.spec().disk.mass, self.spec().disk.inertia());
        let before = beam_kinetic
            + 0.5 * m * (velocity[0] * velocity[0] + velocity[1] * velocity[1])
            + 0.5 * c * omega * omega;
        let after = 0.5 * zd.iter().zip(&momenta).map(|(a, b)| a * b).sum::<f64>();
        zd.iter().all(|x| x.is_finite()).then_some(Landing {
            axle_work: masses(v) - masses(&zd[..n]),
            z,
            zd,
            energy_lost: before - after,
        })
    }
}

/// ½ m (g·v)² summed over the moving masses' rows (`axle_inertia`): their kinetic energy as
/// the beam's velocities v move them, what an impulse on the beam changes of it.
fn axle_kinetic(axles: &LowRank, v: &[f64]) -> f64 {
    axles
        .iter()
        .map(|(m, row)| 0.5 * m * row.iter().map(|&(i, g)| g * v[i]).sum::<f64>().powi(2))
        .sum()
}

/// What a bounce leaves: the disk free again, the beam moving on.
pub struct Bounce {
    /// The disk's centre velocity (global) and spin.
    pub velocity: [f64; 2],
    pub omega: f64,
    /// The beam's velocities, the model's unknowns.
    pub beam: Vec<f64>,
    /// The disk's speed away from the track, relative to it (m/s).
    pub leaving: f64,
    /// Kinetic energy the whole impact took, the plastic part included (J).
    pub energy_lost: f64,
    /// What the train's moving masses did on the beam through both impulses (see
    /// [`Landing::axle_work`]).
    pub axle_work: f64,
}

impl DiskOnBeam<'_> {
    /// The contact point's velocity relative to the beam's averaged track at s, in the
    /// track's (tangent, normal) components, local axes: the disk's centre `velocity` (local)
    /// and spin against the beam's velocities `v` (the model's unknowns).
    pub fn relative(
        &self,
        q: &[f64],
        v: &[f64],
        s: f64,
        velocity: [f64; 2],
        omega: f64,
    ) -> [f64; 2] {
        let a = self.spec().disk.radius;
        let (q, v) = (self.loaded.to_mesh(q), self.loaded.to_mesh(v));
        let at = AxisPoint::at(self.beam(), &q, &v, s, 0.0, self.spec().patch);
        let (t, n) = (at.tangent(), at.normal());
        let track = at.material_velocity();
        let rel = [
            velocity[0] + a * omega * t[0] - track[0],
            velocity[1] + a * omega * t[1] - track[1],
        ];
        [rel[0] * t[0] + rel[1] * t[1], rel[0] * n[0] + rel[1] * n[1]]
    }

    /// The beam's velocity change (the model's unknowns) under an impulse `j` (local axes) the
    /// disk puts on it at s, spread over the contact patch.
    fn beam_kick(&self, q: &[f64], s: f64, j: [f64; 2], mass: &SparseLu) -> Vec<f64> {
        let mesh = self.loaded.to_mesh(q);
        let still = vec![0.0; mesh.len()];
        let at = AxisPoint::at(self.beam(), &mesh, &still, s, 0.0, self.spec().patch);
        let mut f = vec![0.0; mesh.len()];
        at.spread(j, &mut f);
        let mut dv = match self.loaded.modal {
            Some(m) => {
                let mut out = vec![0.0; m.dim()];
                m.project(&f, &mut out);
                out
            }
            None => f,
        };
        mass.solve_in_place(&mut dv);
        dv
    }

    /// A landing with restitution e > 0 (Newton's law at the contact, sticking): after the
    /// plastic `landing`, a second impulse J between disk and beam at the contact, found from
    /// the 2 × 2 Delassus matrix W of the contact (the contact point's relative velocity per
    /// unit impulse: the disk's 1/m + a²/C tangentially and 1/m normally, plus the beam's
    /// track velocity under the impulse spread over the patch), such that the disk leaves
    /// with −e times the normal relative speed it came with and the contact still sticks
    /// tangentially. J is internal to disk and beam, so the momenta stay as the plastic
    /// landing left them. `mass` is the beam's mass matrix (the model's unknowns), factorised;
    /// the train's moving masses, riding with the beam, join it at t.
    #[allow(clippy::too_many_arguments)]
    pub fn bounce(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        s: f64,
        velocity: [f64; 2],
        omega: f64,
        restitution: f64,
        landing: &Landing,
        mass: &SparseLu,
    ) -> Option<Bounce> {
        let n = self.n;
        let beam = self.beam();
        let (m, a, c) = (
            self.spec().disk.mass,
            self.spec().disk.radius,
            self.spec().disk.inertia(),
        );
        let came = self.relative(q, v, s, beam.to_local(velocity), omega)[1];
        let plastic = self.observe(t, &landing.z, &landing.zd);
        let v_plastic = &landing.zd[..n];
        let disk_plastic = beam.to_local([plastic.vx, plastic.vy]);
        let rel = self.relative(q, v_plastic, s, disk_plastic, plastic.omega);
        let mesh = self.loaded.to_mesh(q);
        let still = vec![0.0; mesh.len()];
        let at = AxisPoint::at(beam, &mesh, &still, s, 0.0, self.spec().patch);
        let (tg, nm) = (at.tangent(), at.normal());
        let axles = self.loaded.axle_inertia(t);
        let with_axles = if axles.is_empty() {
            None
        } else {
            let mut a = Assembly::new(n);
            a.add_sparse(self.loaded.model_mass(), 1.0, 0, 0);
            linalg::low_rank_entries(&axles).for_each(|(i, j, v)| a.add(i, j, v));
            Some(SparseLu::factor(&a.build(), None)?)
        };
        let mass = with_axles.as_ref().unwrap_or(mass);
        // W, column by column: the relative velocity a unit impulse along t, then n, makes.
        let mut w = [[0.0; 2]; 2];
        for (k, dir) in [tg, nm].into_iter().enumerate() {
            let kick = self.beam_kick(q, s, [-dir[0], -dir[1]], mass);
            let track = self.relative(q, &kick, s, [0.0, 0.0], 0.0);
            w[0][k] = track[0];
            w[1][k] = track[1];
        }
        w[0][0] += 1.0 / m + a * a / c;
        w[1][1] += 1.0 / m;
        let want = [-rel[0], -restitution * came - rel[1]];
        let det = w[0][0] * w[1][1] - w[0][1] * w[1][0];
        if !(det.abs() > 0.0) {
            return None;
        }
        let jt = (want[0] * w[1][1] - w[0][1] * want[1]) / det;
        let jn = (w[0][0] * want[1] - w[1][0] * want[0]) / det;
        let j = [jt * tg[0] + jn * nm[0], jt * tg[1] + jn * nm[1]];
        let disk_after = [disk_plastic[0] + j[0] / m, disk_plastic[1] + j[1] / m];
        let omega_after = plastic.omega + a * jt / c;
        let kick = self.beam_kick(q, s, [-j[0], -j[1]], mass);
        let beam_after: Vec<f64> = v_plastic.iter().zip(&kick).map(|(a, b)| a + b).collect();
        let kinetic = |v: &[f64], d: [f64; 2], w: f64| {
            let mut mv = vec![0.0; n];
            linalg::mul(self.loaded.model_mass(), v, &mut mv);
            0.5 * v.iter().zip(&mv).map(|(a, b)| a * b).sum::<f64>()
                + axle_kinetic(&axles, v)
                + 0.5 * m * (d[0] * d[0] + d[1] * d[1])
                + 0.5 * c * w * w
        };
        let before = kinetic(v, beam.to_local(velocity), omega);
        let after = kinetic(&beam_after, disk_after, omega_after);
        let leaving = self.relative(q, &beam_after, s, disk_after, omega_after)[1];
        let axle_work = axle_kinetic(&axles, v) - axle_kinetic(&axles, &beam_after);
        [disk_after[0], disk_after[1], omega_after, leaving]
            .iter()
            .chain(&beam_after)
            .all(|x| x.is_finite())
            .then(|| Bounce {
                velocity: beam.to_global(disk_after),
                omega: omega_after,
                beam: beam_after,
                leaving,
                energy_lost: before - after,
                axle_work,
            })
    }
}

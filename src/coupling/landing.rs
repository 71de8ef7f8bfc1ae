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
use crate::ode::second_order::Structure;

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
    /// The gap of disk k's flying centre (global) over the beam displaced `q` (the beam's
    /// unknowns of the model), its nearest point searched from `s`.
    pub fn gap(&self, k: usize, q: &[f64], centre: [f64; 2], s: f64) -> BeamGap {
        let beam = self.beam();
        let spec = self.spec_of(k);
        let a = spec.disk.radius;
        let origin = beam.spec.from;
        let c = beam.to_local([centre[0] - origin[0], centre[1] - origin[1]]);
        let q = self.loaded.to_mesh(q);
        let still = vec![0.0; q.len()];
        let length = beam.length;
        let at = |s: f64| AxisPoint::at(beam, &q, &still, s, 0.0, spec.patch);
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

    /// The plastic landing at t of disk k flying at `velocity` (global) with spin `omega`
    /// on what rides on without it, in the state `rest` = (z, ż): the beam's unknowns alone,
    /// or with the contact coordinates of the disks rolling on it; touching at material point
    /// `s`. `None` for a coupling other than the consistent one, whose rows are not the disk's
    /// velocities, or where the coupled mass cannot be factorised. Disk k must be on the beam
    /// again (not left), the others as they ride.
    pub fn land(
        &self,
        k: usize,
        t: f64,
        rest: (&[f64], &[f64]),
        s: f64,
        velocity: [f64; 2],
        omega: f64,
    ) -> Option<Landing> {
        let d = &self.disks[k];
        let slot = d.slot.filter(|_| d.spec.coupling == Coupling::Consistent)?;
        let n = self.n;
        let (z, still) = self.with_contact_at(rest, slot, s);
        let v = &still[..n];
        let added = self.added_mass(d, &self.contact(k, t, &z, &still));
        let others = self.others_inertia(k, t, &z);
        let local = self.beam().to_local(velocity);
        let disk = [local[0], local[1], omega];
        // The train's moving masses ride with the beam: their inertia m g gᵀ joins the
        // beam's on both sides of the impulse (their prescribed motion along the track is the
        // same just before and after it, and drops out).
        let axles = self.loaded.axle_inertia(t);
        let masses = |v: &[f64]| axle_kinetic(&axles, v);
        let mut momenta = vec![0.0; z.len()];
        linalg::mul(self.loaded.model_mass(), v, &mut momenta[..n]);
        let beam_kinetic = 0.5 * v.iter().zip(&momenta).map(|(a, b)| a * b).sum::<f64>()
            + masses(v)
            + quadratic(&others, &still);
        for (m, row) in axles.iter().chain(&others) {
            let rate = row.iter().map(|&(i, g)| g * still[i]).sum::<f64>();
            row.iter().for_each(|&(i, g)| momenta[i] += m * rate * g);
        }
        for ((w, row), u) in added.iter().zip(disk) {
            for &(i, g) in row {
                momenta[i] += w * u * g;
            }
        }
        let mut zd = momenta.clone();
        let coupled: Vec<_> = added.iter().chain(&axles).chain(&others).cloned().collect();
        SparseLu::factor(&self.mass_matrix(&coupled), None)?.solve_in_place(&mut zd);
        let (m, c) = (d.spec.disk.mass, d.spec.disk.inertia());
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
    quadratic(axles, v)
}

/// ½ żᵀ A ż of a low-rank inertia A = Σ w g gᵀ: the kinetic energy of what it holds.
fn quadratic(inertia: &LowRank, zd: &[f64]) -> f64 {
    inertia
        .iter()
        .map(|(m, row)| 0.5 * m * row.iter().map(|&(i, g)| g * zd[i]).sum::<f64>().powi(2))
        .sum()
}

impl DiskOnBeam<'_> {
    /// The model's (z, ż) from what rides on without disk k, `rest`, with k's contact
    /// coordinate (at `slot`) at s and at rest: where the beam alone rode on (`rest` holds the
    /// beam's unknowns only), the disks that left rest at 0.
    fn with_contact_at(&self, rest: (&[f64], &[f64]), slot: usize, s: f64) -> (Vec<f64>, Vec<f64>) {
        let mut z = vec![0.0; self.dim()];
        let mut zd = vec![0.0; self.dim()];
        z[..rest.0.len()].copy_from_slice(rest.0);
        zd[..rest.1.len()].copy_from_slice(rest.1);
        z[slot] = s;
        zd[slot] = 0.0;
        (z, zd)
    }

    /// The inertia of the disks rolling beside disk k at (t, z): they ride through its impulse
    /// with the beam, as the train's moving masses do. Only the consistent coupling and the
    /// moving force ride beside a flight (`DiskOnBeam::rides_beside_a_flight`): the first's
    /// added mass is its kinetic energy, the second has none.
    fn others_inertia(&self, k: usize, t: f64, z: &[f64]) -> LowRank {
        let still = vec![0.0; z.len()];
        self.on()
            .filter(|&(j, _)| j != k)
            .flat_map(|(_, d)| self.added_mass(d, &self.contact_of(d, t, z, &still)))
            .collect()
    }
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
    /// Disk k's contact point's velocity relative to the beam's averaged track at s, in the
    /// track's (tangent, normal) components, local axes: the disk's centre `velocity` (local)
    /// and spin against the beam's velocities `v` (the beam's unknowns of the model).
    pub fn relative(
        &self,
        k: usize,
        (q, v): (&[f64], &[f64]),
        s: f64,
        velocity: [f64; 2],
        omega: f64,
    ) -> [f64; 2] {
        let spec = self.spec_of(k);
        let a = spec.disk.radius;
        let (q, v) = (self.loaded.to_mesh(q), self.loaded.to_mesh(v));
        let at = AxisPoint::at(self.beam(), &q, &v, s, 0.0, spec.patch);
        let (t, n) = (at.tangent(), at.normal());
        let track = at.material_velocity();
        let rel = [
            velocity[0] + a * omega * t[0] - track[0],
            velocity[1] + a * omega * t[1] - track[1],
        ];
        [rel[0] * t[0] + rel[1] * t[1], rel[0] * n[0] + rel[1] * n[1]]
    }

    /// The velocity change of what rides on under an impulse `j` (local axes) disk k puts on
    /// the beam at s, spread over its contact patch: `mass` is the inertia of what rides on
    /// (the beam's, or with the disks rolling on it), factorised.
    fn kick(&self, k: usize, q: &[f64], s: f64, j: [f64; 2], mass: &Rest) -> Vec<f64> {
        let mesh = self.loaded.to_mesh(q);
        let still = vec![0.0; mesh.len()];
        let at = AxisPoint::at(self.beam(), &mesh, &still, s, 0.0, self.spec_of(k).patch);
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
        dv.resize(mass.dim, 0.0);
        mass.lu().solve_in_place(&mut dv);
        dv
    }

    /// A landing of disk k with restitution e > 0 (Newton's law at the contact, sticking):
    /// after the plastic `landing`, a second impulse J between disk and beam at the contact,
    /// found from the 2 × 2 Delassus matrix W of the contact (the contact point's relative
    /// velocity per unit impulse: the disk's 1/m + a²/C tangentially and 1/m normally, plus
    /// the beam's track velocity under the impulse spread over the patch), such that the disk
    /// leaves with −e times the normal relative speed it came with and the contact still
    /// sticks tangentially. J is internal to disk and beam, so the momenta stay as the plastic
    /// landing left them. `rest` is the state the disk flew over (as [`Self::land`] takes
    /// it); `mass` the beam's mass matrix (the model's unknowns), factorised. What rides with
    /// the beam takes the impulse with it: the train's moving masses at t, and the disks
    /// rolling beside k (then the bounce leaves them the velocities `Bounce::beam`, in the
    /// layout of `rest`).
    #[allow(clippy::too_many_arguments)]
    pub fn bounce(
        &self,
        k: usize,
        t: f64,
        rest: (&[f64], &[f64]),
        s: f64,
        velocity: [f64; 2],
        omega: f64,
        restitution: f64,
        landing: &Landing,
        mass: &SparseLu,
    ) -> Option<Bounce> {
        let n = self.n;
        let beam = self.beam();
        let d = &self.disks[k];
        let (m, a, c) = (d.spec.disk.mass, d.spec.disk.radius, d.spec.disk.inertia());
        let q = &rest.0[..n];
        let came = self.relative(k, (q, &rest.1[..n]), s, beam.to_local(velocity), omega)[1];
        let plastic = self.observe_all(t, &landing.z, &landing.zd)[k]?;
        let mut v_plastic = landing.zd[..rest.1.len()].to_vec();
        if let Some(slot) = d.slot.filter(|&i| i < v_plastic.len()) {
            v_plastic[slot] = 0.0;
        }
        let disk_plastic = beam.to_local([plastic.vx, plastic.vy]);
        let rel = self.relative(k, (q, &v_plastic[..n]), s, disk_plastic, plastic.omega);
        let mesh = self.loaded.to_mesh(q);
        let still = vec![0.0; mesh.len()];
        let at = AxisPoint::at(beam, &mesh, &still, s, 0.0, d.spec.patch);
        let (tg, nm) = (at.tangent(), at.normal());
        let axles = self.loaded.axle_inertia(t);
        let others = if rest.0.len() > n {
            self.others_inertia(k, t, &landing.z)
        } else {
            Vec::new()
        };
        let riding = self.riding_mass(k, rest.0.len(), &axles, &others, mass)?;
        // W, column by column: the relative velocity a unit impulse along t, then n, makes.
        let mut w = [[0.0; 2]; 2];
        for (col, dir) in [tg, nm].into_iter().enumerate() {
            let kick = self.kick(k, q, s, [-dir[0], -dir[1]], &riding);
            let track = self.relative(k, (q, &kick[..n]), s, [0.0, 0.0], 0.0);
            w[0][col] = track[0];
            w[1][col] = track[1];
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
        let kick = self.kick(k, q, s, [-j[0], -j[1]], &riding);
        let beam_after: Vec<f64> = v_plastic.iter().zip(&kick).map(|(a, b)| a + b).collect();
        let kinetic = |v: &[f64], d: [f64; 2], w: f64| {
            let mut mv = vec![0.0; n];
            linalg::mul(self.loaded.model_mass(), &v[..n], &mut mv);
            0.5 * v[..n].iter().zip(&mv).map(|(a, b)| a * b).sum::<f64>()
                + axle_kinetic(&axles, v)
                + quadratic(&others, v)
                + 0.5 * m * (d[0] * d[0] + d[1] * d[1])
                + 0.5 * c * w * w
        };
        let before = kinetic(rest.1, beam.to_local(velocity), omega);
        let after = kinetic(&beam_after, disk_after, omega_after);
        let leaving = self.relative(k, (q, &beam_after[..n]), s, disk_after, omega_after)[1];
        let axle_work = axle_kinetic(&axles, rest.1) - axle_kinetic(&axles, &beam_after);
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

    /// The inertia that rides through disk k's impulse, factorised, over `dim` unknowns (the
    /// beam's, or the model's where disks roll beside k): the beam's mass (`mass`, given
    /// factorised), the train's moving masses `axles` at t, the rolling disks' `others`, and
    /// under k's own contact coordinate a unit mass that keeps it at rest.
    fn riding_mass<'m>(
        &self,
        k: usize,
        dim: usize,
        axles: &LowRank,
        others: &LowRank,
        mass: &'m SparseLu,
    ) -> Option<Rest<'m>> {
        if axles.is_empty() && dim == self.n {
            return Some(Rest {
                given: mass,
                own: None,
                dim,
            });
        }
        let mut a = Assembly::new(dim);
        a.add_sparse(self.loaded.model_mass(), 1.0, 0, 0);
        linalg::low_rank_entries(axles).for_each(|(i, j, v)| a.add(i, j, v));
        linalg::low_rank_entries(others).for_each(|(i, j, v)| a.add(i, j, v));
        for (j, d) in self.disks.iter().enumerate() {
            match d.slot {
                Some(i) if i < dim && (j == k || self.has_left(j)) => a.add(i, i, 1.0),
                _ => {}
            }
        }
        Some(Rest {
            given: mass,
            own: Some(SparseLu::factor(&a.build(), None)?),
            dim,
        })
    }
}

/// The inertia of what rides on the beam through an impulse, factorised, over its unknowns:
/// the beam's mass as given, or its own where more rides with the beam.
struct Rest<'m> {
    given: &'m SparseLu,
    own: Option<SparseLu>,
    dim: usize,
}

impl Rest<'_> {
    fn lu(&self) -> &SparseLu {
        self.own.as_ref().unwrap_or(self.given)
    }
}

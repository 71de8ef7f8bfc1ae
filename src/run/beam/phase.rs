//! What a beam run integrates at a time: the beam with the disk riding on it (the state is
//! (z, ż) with z = (q, s) or q), or, once the disk has left, the beam alone. Besides slicing
//! the state, a phase computes what the outputs observe at an output time and the model does
//! not already give: the accelerations, the support reactions, inertia included, and on a
//! modal beam the mesh's displacements with the static correction of the modes left out.

use std::borrow::Cow;

use super::contact_mean::Seen;
use crate::beam::dynamics::LoadedBeam;
use crate::beam::Beam;
use crate::coupling::vehicles::{VehicleObservation, VehiclesOnBeam};
use crate::coupling::DiskOnBeam;
use crate::disk::DiskObservation;
use crate::linalg::{SparseLu, Woodbury};
use crate::ode::second_order::Structure;

pub(super) struct Phase<'a> {
    pub beam: &'a Beam,
    pub loaded: &'a LoadedBeam<'a>,
    /// The disks while one is on the beam.
    pub coupled: Option<&'a DiskOnBeam<'a>>,
    /// Unknowns of the phase's z.
    pub nz: usize,
    /// The beam's mass matrix (in the model's unknowns), factorised once: accelerations of
    /// the free beam.
    pub mass_lu: &'a SparseLu,
    /// Add the static correction of the modes a modal beam leaves out to its displacements.
    pub correct: bool,
    /// The disk while it flies over the beam.
    pub flying: Option<super::flight::FlyingDisk<'a>>,
    /// The vehicles, which ride the whole run (the state is then z = (q, vehicles')).
    pub vehicles: Option<&'a VehiclesOnBeam<'a>>,
}

impl<'a> Phase<'a> {
    /// (z, ż).
    pub fn split<'y>(&self, y: &'y [f64]) -> (&'y [f64], &'y [f64]) {
        y.split_at(self.nz)
    }

    /// The beam's (q, v) on the mesh: the state itself, or on a modal beam Φ (η, η̇). This is
    /// the state the equations of motion and the energy budget hold.
    pub fn beam_state<'y>(&self, y: &'y [f64]) -> (Cow<'y, [f64]>, Cow<'y, [f64]>) {
        let n = self.loaded.dim();
        (
            self.loaded.to_mesh(&y[..n]),
            self.loaded.to_mesh(&y[self.nz..self.nz + n]),
        )
    }

    /// The mesh's displacements as the outputs read them: on a modal beam Φ η plus the static
    /// response of the modes left out to what acts on the beam at t (its loads, the moving
    /// masses' inertia and the disks' contact forces, the disks as observed in `disks`).
    pub fn displaced<'y>(
        &self,
        t: f64,
        y: &'y [f64],
        disks: &[Option<DiskObservation>],
        rate: Option<&[f64]>,
    ) -> Cow<'y, [f64]> {
        let n = self.loaded.dim();
        let q = self.loaded.to_mesh(&y[..n]);
        let Some(modal) = self.loaded.modal.filter(|_| self.correct) else {
            return q;
        };
        let mut f = vec![0.0; self.beam.dim()];
        self.loaded.external(t, &mut f);
        if !self.loaded.riding(t).is_empty() {
            let a = match rate {
                Some(yp) => self.split(yp).1[..n].to_vec(),
                None => self.acceleration(t, y),
            };
            let (z, zd) = self.split(y);
            self.loaded
                .add_riding_inertia(t, &z[..n], &zd[..n], &a, &mut f);
        }
        if let Some(c) = self.coupled {
            let (z, zd) = self.split(y);
            c.add_contact_force_on_beam(t, z, zd, disks, &mut f);
        }
        for (x, p) in self.wheel_forces(t, y, rate) {
            self.beam.add_point_load(x, [0.0, p], 0.0, &mut f);
        }
        let mut q = q.into_owned();
        modal.add_static_correction(&f, &mut q);
        Cow::Owned(q)
    }

    /// The beam alone: vibrating freely from here on, or under the disk flying over it.
    pub fn free(&mut self) {
        self.coupled = None;
        self.nz = self.loaded.dim();
    }

    /// Each disk as it is at (t, y) while it is on the beam or flies over it (`None` once it
    /// has left), and the flying disk's gap to the beam (0 while it rolls or has left); no
    /// disks once they have all left.
    pub fn disks(&self, t: f64, y: &[f64]) -> (Vec<Option<DiskObservation>>, f64) {
        let (z, zd) = self.split(y);
        let mut disks = self
            .coupled
            .map_or_else(Vec::new, |c| c.observe_all(t, z, zd));
        let Some(f) = &self.flying else {
            return (disks, 0.0);
        };
        let (d, gap) = f.observe(t, &y[..self.loaded.dim()]);
        disks.resize(f.coupled.count(), None);
        disks[f.k] = Some(d);
        (disks, gap)
    }

    /// Each disk's centre velocity and contact frame at (t, y), as the contact force's means
    /// read them (`None` for a disk not on or over the beam, no frame while it flies).
    pub fn seen_disks(&self, t: f64, y: &[f64]) -> Vec<Option<Seen>> {
        let mut seen = self.seen_rolling(t, y);
        if let Some(f) = &self.flying {
            let (d, _) = f.observe(t, &y[..self.loaded.dim()]);
            seen.resize(f.coupled.count(), None);
            seen[f.k] = Some(Seen {
                velocity: [d.vx, d.vy],
                frame: None,
            });
        }
        seen
    }

    /// [`Self::seen_disks`] of the disks rolling on the beam.
    fn seen_rolling(&self, t: f64, y: &[f64]) -> Vec<Option<Seen>> {
        let (z, zd) = self.split(y);
        self.coupled.map_or_else(Vec::new, |c| {
            c.velocities_and_frames(t, z, zd)
                .into_iter()
                .map(|seen| {
                    seen.map(|(velocity, frame)| Seen {
                        velocity,
                        frame: Some(frame),
                    })
                })
                .collect()
        })
    }

    /// The disk rides on the beam again.
    pub fn couple(&mut self, c: &'a DiskOnBeam<'a>) {
        self.flying = None;
        self.coupled = Some(c);
        self.nz = c.dim();
    }

    /// The vehicles' wheels' forces on the beam at (t, y) (global Y, at their places on it).
    /// With `rate` (the dense output's ẏ) the accelerations are read off it, not solved for.
    fn wheel_forces(&self, t: f64, y: &[f64], rate: Option<&[f64]>) -> Vec<(f64, f64)> {
        let Some(v) = self.vehicles else {
            return Vec::new();
        };
        let (z, zd) = self.split(y);
        match rate {
            Some(yp) => v.forces_on_beam(t, z, zd, self.split(yp).1),
            None => v.forces_on_beam(t, z, zd, &v.acceleration_the_wheels_feel(t, z, zd)),
        }
    }

    /// The vehicles at (t, y), with the model's accelerations there.
    pub fn vehicles(&self, t: f64, y: &[f64]) -> Option<VehicleObservation> {
        let v = self.vehicles?;
        let (z, zd) = self.split(y);
        Some(v.observe(t, z, zd, &v.acceleration(t, z, zd)))
    }

    /// The vehicles at (t, y), with the accelerations read off `rate` (ẏ) where given.
    pub fn vehicles_at_rate(
        &self,
        t: f64,
        y: &[f64],
        rate: Option<&[f64]>,
    ) -> Option<VehicleObservation> {
        let v = self.vehicles?;
        let (z, zd) = self.split(y);
        match rate {
            Some(yp) => Some(v.observe(t, z, zd, self.split(yp).1)),
            None => self.vehicles(t, y),
        }
    }

    /// The model's accelerations at (t, y): with the disk on the beam, the coupled system's
    /// (from the disk's observation); with vehicles, theirs and the beam's together; the
    /// free beam's otherwise.
    pub fn acceleration(&self, t: f64, y: &[f64]) -> Vec<f64> {
        let n = self.loaded.dim();
        if let Some(v) = self.vehicles {
            let (z, zd) = self.split(y);
            let mut a = v.acceleration(t, z, zd);
            a.truncate(n);
            return a;
        }
        match self.coupled {
            Some(c) => {
                let (z, zd) = self.split(y);
                c.observe_with_acceleration(t, z, zd)
                    .1
                    .map(|a| a[..n].to_vec())
                    .unwrap_or_else(|| vec![f64::NAN; n])
            }
            None => {
                let mut a = vec![0.0; n];
                self.loaded
                    .force(t, &y[..n], &y[self.nz..self.nz + n], &mut a);
                // Moving masses add m g gᵀ to the factorised mass: taken in by Woodbury.
                match self.loaded.mass_split(t, &y[..n]) {
                    Some((_, added)) if !added.is_empty() => {
                        match Woodbury::new(self.mass_lu, added) {
                            Some(w) => w.solve_in_place(self.mass_lu, &mut a),
                            None => a.fill(f64::NAN),
                        }
                    }
                    _ => self.mass_lu.solve_in_place(&mut a),
                }
                a
            }
        }
    }

    /// What the supports exert on the beam, global (fx, fy, mz) at `from` and at `to`: the
    /// forces `acting` ([`Phase::acting`]) and the beam's inertia. `q` is the mesh's
    /// displacements, `a` the model's accelerations.
    pub fn reactions(
        &self,
        q: &[f64],
        acting: &[(f64, [f64; 2], f64)],
        a: &[f64],
    ) -> [[f64; 3]; 2] {
        self.beam
            .support_reactions(q, acting, Some(&self.loaded.to_mesh(a)))
    }

    /// The point forces on the beam at (t, y), global (x, force, moment): the loads acting
    /// then, a train's axles (moving masses with the model's accelerations `a`), the wheels'
    /// and the disks' contact forces (the disks as observed in `disks`).
    pub fn acting(
        &self,
        t: f64,
        y: &[f64],
        a: &[f64],
        disks: &[Option<DiskObservation>],
    ) -> Vec<(f64, [f64; 2], f64)> {
        let mut acting: Vec<(f64, [f64; 2], f64)> = self
            .loaded
            .active(t)
            .map(|l| (l.x, l.force, l.mz))
            .collect();
        let n = self.loaded.dim();
        acting.extend(
            self.loaded
                .axle_forces(t, &y[..n], &y[self.nz..self.nz + n], a)
                .into_iter()
                .map(|(x, f)| (x, f, 0.0)),
        );
        acting.extend(
            self.wheel_forces(t, y, None)
                .into_iter()
                .map(|(x, p)| (x, [0.0, p], 0.0)),
        );
        if let Some(c) = self.coupled {
            let (z, zd) = self.split(y);
            for (k, d) in disks.iter().enumerate() {
                let Some(d) = d else { continue };
                let at_s = c.contact_frame(k, t, z, zd);
                let on_disk = [
                    d.rt * at_s[0][0] + d.rn * at_s[1][0],
                    d.rt * at_s[0][1] + d.rn * at_s[1][1],
                ];
                acting.push((d.s, [-on_disk[0], -on_disk[1]], 0.0));
            }
        }
        acting
    }
}

//! What a beam run integrates at a time: the beam with the disk riding on it (the state is
//! (z, ż) with z = (q, s) or q), or, once the disk has left, the beam alone. Besides slicing
//! the state, a phase computes what the outputs observe at an output time and the model does
//! not already give: the support reactions, inertia included.

use crate::beam::dynamics::LoadedBeam;
use crate::beam::Beam;
use crate::coupling::DiskOnBeam;
use crate::linalg::SparseLu;
use crate::ode::second_order::Structure;
use crate::rolling::DiskObservation;

pub(super) struct Phase<'a> {
    pub beam: &'a Beam,
    pub loaded: &'a LoadedBeam<'a>,
    /// The disk while it is on the beam.
    pub coupled: Option<&'a DiskOnBeam<'a>>,
    /// Unknowns of the phase's z.
    pub nz: usize,
    /// The beam's mass matrix, factorised once: accelerations of the free beam.
    pub mass_lu: &'a SparseLu,
}

impl Phase<'_> {
    /// (z, ż).
    pub fn split<'y>(&self, y: &'y [f64]) -> (&'y [f64], &'y [f64]) {
        y.split_at(self.nz)
    }

    /// The beam's (q, v).
    pub fn beam_state<'y>(&self, y: &'y [f64]) -> (&'y [f64], &'y [f64]) {
        let n = self.beam.dim();
        (&y[..n], &y[self.nz..self.nz + n])
    }

    /// The beam alone, vibrating freely from here on.
    pub fn free(&mut self) {
        self.coupled = None;
        self.nz = self.beam.dim();
    }

    /// The disk as it is at (t, y), while it is on the beam.
    pub fn disk(&self, t: f64, y: &[f64]) -> Option<DiskObservation> {
        let (z, zd) = self.split(y);
        self.coupled.map(|c| c.observe(t, z, zd))
    }

    /// What the supports exert on the beam at (t, y), global (fx, fy, mz) at `from` and at
    /// `to`: the loads acting then, the disk's contact force, and the beam's inertia.
    pub fn reactions(&self, t: f64, y: &[f64], disk: Option<&DiskObservation>) -> [[f64; 3]; 2] {
        let n = self.beam.dim();
        let (q, v) = self.beam_state(y);
        let mut acting: Vec<(f64, [f64; 2], f64)> = self
            .loaded
            .active(t)
            .map(|l| (l.x, l.force, l.mz))
            .collect();
        let a = match self.coupled {
            Some(c) => {
                let d = disk.expect("observed while coupled");
                let (z, zd) = self.split(y);
                let at_s = c.contact_frame(t, z, zd);
                let on_disk = [
                    d.rt * at_s[0][0] + d.rn * at_s[1][0],
                    d.rt * at_s[0][1] + d.rn * at_s[1][1],
                ];
                acting.push((d.s, [-on_disk[0], -on_disk[1]], 0.0));
                c.observe_with_acceleration(t, z, zd)
                    .1
                    .map(|a| a[..n].to_vec())
                    .unwrap_or_else(|| vec![f64::NAN; n])
            }
            None => {
                let mut a = vec![0.0; n];
                self.loaded.force(t, q, v, &mut a);
                self.mass_lu.solve_in_place(&mut a);
                a
            }
        };
        self.beam.support_reactions(q, &acting, Some(&a))
    }
}

//! The support reactions as the history reports them: counted, as the deck's acceleration is,
//! up to the cutoff frequency (EN 1991-2 §6.4.6.3.3 takes a bridge's dynamic response to
//! max(30 Hz, 1.5 f1, f3)). The modes below the cutoff answer with their inertia, those above
//! it quasi-statically, at their static response to what acts on the beam at the time: the
//! mode-acceleration method. A support's shear weighs mode k about as k³ while the integrator
//! holds the modes by their deflections, so with their inertia the modes above the cutoff
//! carry the steps' error into the reactions magnified (Biggs' sprung mass at the defaults
//! reads them 6·10⁻³ of the largest off) and move them with the modes kept (1.9·10⁻³ from 14
//! to 28 modes).
//!
//! On a modal beam each mode above the cutoff is set to gₖ/ωₖ², gₖ its share of the forces
//! acting, and the modes it leaves out are taken static under the same forces; on the mesh
//! the same follows from one linear solve, q' = q + P K⁻¹(f − f_int(q) − M a' − C v'), a' and
//! v' the accelerations and velocities of the modes below the cutoff, K the tangent at q and
//! P what lies above the cutoff: the residual the modes above leave is what they would hold
//! statically.

use std::cell::{OnceCell, RefCell};

use super::acceleration::AccelerationFilter;
use super::phase::Phase;
use crate::disk::DiskObservation;
use crate::linalg::{self, SparseLu};
use crate::ode::second_order::Structure;

/// Reads the reactions of one run.
pub(super) struct Reactions {
    /// K₀ factorised on a linear mesh, formed at the first row: the tangent of every state.
    linear: OnceCell<Option<SparseLu>>,
    /// The last tangent factorised on an exact mesh, whose pattern the next one reuses.
    tangent: RefCell<Option<SparseLu>>,
}

impl Reactions {
    pub fn new() -> Self {
        Reactions {
            linear: OnceCell::new(),
            tangent: RefCell::new(None),
        }
    }

    /// What the supports exert on the beam at (t, y), `q` the mesh's displacements as
    /// [`Phase::displaced`] reads them, `a` the model's accelerations: to the `filter`'s
    /// cutoff where there is one and modes lie above it, in full otherwise.
    pub fn at(
        &self,
        phase: &Phase,
        filter: Option<&AccelerationFilter>,
        (t, y): (f64, &[f64]),
        (q, a): (&[f64], &[f64]),
        disks: &[Option<DiskObservation>],
    ) -> [[f64; 3]; 2] {
        let cut = filter.and_then(|f| self.to_the_cutoff(phase, f, (t, y), (q, a), disks));
        match cut {
            Some((q, a, acting)) => phase.reactions(&q, &acting, &a),
            None => phase.reactions(q, &phase.acting(t, y, a, disks), a),
        }
    }

    /// The displacements and the model's accelerations with the modes above the cutoff taken
    /// quasi-statically, and the forces acting then; `None` where every mode the model holds
    /// lies below it, or where the beam has no static response (a mechanism).
    fn to_the_cutoff(
        &self,
        phase: &Phase,
        filter: &AccelerationFilter,
        (t, y): (f64, &[f64]),
        (q, a): (&[f64], &[f64]),
        disks: &[Option<DiskObservation>],
    ) -> Option<(Vec<f64>, Vec<f64>, Vec<(f64, [f64; 2], f64)>)> {
        let loaded = phase.loaded;
        let n = loaded.dim();
        let below = match loaded.modal {
            Some(modal) => filter.kept.min(modal.dim()),
            None => filter.kept,
        };
        if below >= n {
            return None;
        }
        let slow = filter.below_in_model(loaded, a);
        let acting = phase.acting(t, y, &slow, disks);
        let mut f = vec![0.0; phase.beam.dim()];
        for &(x, force, mz) in &acting {
            phase.beam.add_point_load(x, force, mz, &mut f);
        }
        if let Some(weight) = phase.beam.weight() {
            f.iter_mut().zip(weight).for_each(|(a, w)| *a += w);
        }
        let q = match loaded.modal {
            Some(modal) => {
                if modal.omega[below..].iter().any(|w| !(*w > 0.0)) {
                    return None;
                }
                let mut g = vec![0.0; n];
                modal.project(&f, &mut g);
                let mut eta = y[..n].to_vec();
                for k in below..n {
                    eta[k] = g[k] / (modal.omega[k] * modal.omega[k]);
                }
                // The modes left out are taken static under the same forces: a moving mass's
                // force carries its inertia, which the loads alone leave out, and the end
                // element's shear reads its static share in full (HSLM-A1's moving masses at
                // 90 m/s: the pinned end's reaction 18 % off the linear mesh's without it).
                let mut out = vec![0.0; q.len()];
                modal.expand(&eta, &mut out);
                if phase.correct {
                    modal.add_static_correction(&f, &mut out);
                }
                out
            }
            None => {
                let beam = phase.beam;
                let mut r = vec![0.0; n];
                beam.internal_force(q, &mut r);
                let mut scratch = vec![0.0; n];
                linalg::mul(beam.mass(), &slow, &mut scratch);
                f.iter_mut()
                    .zip(r.iter().zip(&scratch))
                    .for_each(|(f, (r, m))| *f -= r + m);
                if let Some(c) = loaded.damping() {
                    let v = filter.below_in_model(loaded, &y[phase.nz..phase.nz + n]);
                    linalg::mul(&c, &v, &mut scratch);
                    f.iter_mut().zip(&scratch).for_each(|(f, d)| *f -= d);
                }
                if beam.is_linear() {
                    let lu = self
                        .linear
                        .get_or_init(|| SparseLu::factor(&beam.initial_stiffness(), None));
                    lu.as_ref()?.solve_in_place(&mut f);
                } else {
                    let mut last = self.tangent.borrow_mut();
                    *last = SparseLu::factor(&beam.tangent(q), last.take());
                    last.as_ref()?.solve_in_place(&mut f);
                }
                // The modes below the cutoff stay as the run has them: the forces here are
                // points where the equations spread a wheel over its patch.
                let slow_part = filter.below_in_model(loaded, &f);
                (q.iter().zip(f.iter().zip(&slow_part)))
                    .map(|(a, (b, s))| a + b - s)
                    .collect()
            }
        };
        Some((q, slow, acting))
    }
}

//! The deck acceleration as EN 1991-2 §6.4.6 counts it: the beam's acceleration with the modes
//! above a cutoff frequency left out (by default max(30 Hz, 1.5 f1, f3), f1 and f3 the first
//! and third bending modes: an axial mode, w ≡ 0, is not what the rule counts). On a modal beam that
//! is the modes kept below the cutoff; on the mesh (exact and linear beams) the acceleration is
//! projected on the linear beam's modes below it, a = Σ φ_k φ_kᵀ M a: the same filter, so the
//! models report the same quantity.

use nalgebra::DMatrix;

use crate::analysis::modes::{acceleration_cutoff, modes};
use crate::beam::dynamics::LoadedBeam;
use crate::beam::modal::{within_cutoff, MAX_MODES};
use crate::beam::Beam;
use crate::linalg;

/// What the recorded accelerations count (and the reactions with their inertia), for the
/// summary.
#[derive(Clone, Debug, serde::Serialize)]
pub struct CutoffReport {
    pub cutoff_hz: f64,
    /// The modes below the cutoff, which the accelerations are made of.
    pub modes: usize,
    pub rule: String,
    /// The modes of the mesh at or below the cutoff: more than `modes` where a modal beam
    /// keeps fewer, whose accelerations then leave the others out.
    #[serde(skip)]
    pub below: usize,
}

pub(super) struct AccelerationFilter {
    pub cutoff_hz: f64,
    /// How many modes are kept.
    pub kept: usize,
    /// How many modes of the mesh lie at or below the cutoff.
    below: usize,
    /// On the mesh, the kept modes' shapes and circular frequencies; on a modal beam, nothing
    /// more.
    mesh: Option<(DMatrix<f64>, Vec<f64>)>,
    /// Why the cutoff is what it is.
    pub rule: String,
}

impl AccelerationFilter {
    /// The filter for the beam's model, at `given` Hz or by EN 1991-2's rule; `None` where the
    /// modes cannot be computed.
    pub fn new(beam: &Beam, loaded: &LoadedBeam, given: Option<f64>) -> Option<AccelerationFilter> {
        let available = beam.dim().min(MAX_MODES);
        let mut m = modes(beam, available.min(3))?;
        let hz = |m: &crate::analysis::modes::Modes| -> Vec<f64> {
            m.omega.iter().map(|w| w / std::f64::consts::TAU).collect()
        };
        let (cutoff_hz, rule) = acceleration_cutoff(beam, given)?;
        // Modes until one is past the cutoff (or the mesh, or the bound, runs out).
        while m.omega.len() < available
            && hz(&m).last().is_some_and(|f| within_cutoff(*f, cutoff_hz))
        {
            m = modes(beam, (2 * m.omega.len()).min(available))?;
        }
        let below = hz(&m)
            .iter()
            .take_while(|f| within_cutoff(**f, cutoff_hz))
            .count();
        Some(match loaded.modal {
            Some(modal) => AccelerationFilter {
                cutoff_hz,
                kept: below.min(modal.dim()),
                below,
                mesh: None,
                rule,
            },
            None => AccelerationFilter {
                cutoff_hz,
                kept: below,
                below,
                mesh: Some((
                    m.shapes.columns(0, below).into_owned(),
                    m.omega[..below].to_vec(),
                )),
                rule,
            },
        })
    }

    /// On the mesh, the kept modes' shapes and circular frequencies.
    pub fn mesh_modes(&self) -> Option<(&DMatrix<f64>, &[f64])> {
        self.mesh.as_ref().map(|(s, w)| (s, w.as_slice()))
    }

    pub fn report(&self) -> CutoffReport {
        CutoffReport {
            cutoff_hz: self.cutoff_hz,
            modes: self.kept,
            rule: self.rule.clone(),
            below: self.below,
        }
    }

    /// The mesh's accelerations from the model's `a`, the modes above the cutoff left out.
    pub fn filtered(&self, loaded: &LoadedBeam, a: &[f64]) -> Vec<f64> {
        match &self.mesh {
            Some(_) => self.below_in_model(loaded, a),
            None => loaded.to_mesh(&self.below_in_model(loaded, a)).into_owned(),
        }
    }

    /// The model's accelerations (or velocities) `a`, the modes above the cutoff left out, in
    /// the model's own unknowns.
    pub fn below_in_model(&self, loaded: &LoadedBeam, a: &[f64]) -> Vec<f64> {
        match &self.mesh {
            Some((shapes, _)) => {
                let mut ma = vec![0.0; a.len()];
                linalg::mul(loaded.beam.mass(), a, &mut ma);
                let amplitudes = shapes.transpose() * nalgebra::DVector::from_vec(ma);
                (shapes * amplitudes).as_slice().to_vec()
            }
            None => {
                let mut kept = a.to_vec();
                kept[self.kept..].iter_mut().for_each(|v| *v = 0.0);
                kept
            }
        }
    }
}

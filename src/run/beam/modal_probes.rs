//! The probes of a modal beam read from its amplitudes: each probe's u, w and φ as a row over
//! the modes, and the static response of the modes left out as a row over the mesh's loads,
//! both formed once. A snapshot that reads the probes alone (a sweep's case, the envelope
//! unwatched, no disk or vehicle on the beam) then costs a few dot products over the modes
//! and, for the correction, a product at each unknown a load touches, where expanding the
//! modes over the mesh and solving for the static correction cost most of a snapshot.

use crate::beam::dynamics::LoadedBeam;

/// u, w and φ at one point, a row over the modes.
pub(super) type Rows = [Vec<f64>; 3];

pub(super) struct ModalProbes {
    /// Per probe, its u, w and φ per unit amplitude of each mode.
    modes: Vec<Rows>,
    /// Per probe, its u, w and φ under the left-out modes' static response to a unit force at
    /// each of the mesh's unknowns: the residual flexibility R is symmetric, so that row is R
    /// applied to a unit load at the probe. `None` where the basis keeps no flexibility.
    residual: Option<Vec<Rows>>,
}

impl ModalProbes {
    /// `None` on a beam that is not modal.
    pub fn new(loaded: &LoadedBeam, xs: &[f64]) -> Option<ModalProbes> {
        let modal = loaded.modal?;
        let beam = loaded.beam;
        let n = beam.dim();
        let modes = mode_rows(loaded, xs)?;
        let residual = xs
            .iter()
            .map(|&x| {
                let unit = |force: [f64; 2], moment: f64| {
                    let mut f = vec![0.0; n];
                    beam.add_point_load(x, force, moment, &mut f);
                    modal.residual_flexibility(&f)
                };
                Some([
                    unit([1.0, 0.0], 0.0)?,
                    unit([0.0, 1.0], 0.0)?,
                    unit([0.0, 0.0], 1.0)?,
                ])
            })
            .collect();
        Some(ModalProbes { modes, residual })
    }

    /// Per probe, its u, w and φ per unit amplitude of each mode.
    pub fn rows(&self) -> &[Rows] {
        &self.modes
    }

    /// Per probe (u, w, φ, the acceleration's w) from the amplitudes `z`, their accelerations
    /// `a` (the first `kept` of them: the acceleration's cutoff) and, to correct for the modes
    /// left out, the mesh's loads, which `loads` hands term by term to the function it is given.
    pub fn read(
        &self,
        z: &[f64],
        a: &[f64],
        kept: usize,
        loads: Option<&dyn Fn(&mut dyn FnMut(usize, f64))>,
    ) -> Vec<f64> {
        let dot = |r: &[f64], v: &[f64]| -> f64 { r.iter().zip(v).map(|(x, y)| x * y).sum() };
        let mut out = Vec::with_capacity(4 * self.modes.len());
        for (p, rows) in self.modes.iter().enumerate() {
            let mut corrected = [0.0; 3];
            if let (Some(r), Some(loads)) = (self.residual.as_ref().map(|r| &r[p]), loads) {
                loads(&mut |i, v| {
                    for (c, row) in r.iter().enumerate() {
                        corrected[c] += row[i] * v;
                    }
                });
            }
            for (row, correction) in rows.iter().zip(corrected) {
                out.push(dot(row, z) + correction);
            }
            out.push(dot(&rows[1][..kept], &a[..kept]));
        }
        out
    }
}

/// Per point x of `xs`, its u, w and φ per unit amplitude of each mode of a modal beam (`None`
/// on the mesh).
pub(super) fn mode_rows(loaded: &LoadedBeam, xs: &[f64]) -> Option<Vec<Rows>> {
    let modal = loaded.modal?;
    let beam = loaded.beam;
    let (m, n) = (modal.dim(), beam.dim());
    let shapes: Vec<Vec<f64>> = (0..m)
        .map(|k| {
            let mut eta = vec![0.0; m];
            eta[k] = 1.0;
            let mut q = vec![0.0; n];
            modal.expand(&eta, &mut q);
            q
        })
        .collect();
    Some(
        xs.iter()
            .map(|&x| {
                let d: Vec<_> = shapes.iter().map(|q| beam.displacement_at(q, x)).collect();
                [
                    d.iter().map(|p| p.u).collect(),
                    d.iter().map(|p| p.w).collect(),
                    d.iter().map(|p| p.phi).collect(),
                ]
            })
            .collect(),
    )
}

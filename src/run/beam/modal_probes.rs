//! The probes of a modal beam read from its amplitudes: each probe's u, w and φ as a row over
//! the modes, and the static response of the modes left out as a row over the mesh's loads,
//! both formed once. A snapshot that reads the probes alone (a sweep's case, the envelope
//! unwatched, no disk or vehicle on the beam) then costs a few dot products over the modes
//! and, for the correction, a product at each unknown a load touches, where expanding the
//! modes over the mesh and solving for the static correction cost most of a snapshot.

use crate::beam::dynamics::LoadedBeam;
use crate::beam::{Beam, RowAlong};
use std::cell::OnceCell;

/// u, w and φ at one point, a row over the modes.
pub(super) type Rows = [Vec<f64>; 3];

pub(super) struct ModalProbes {
    /// Per probe, its u, w and φ per unit amplitude of each mode.
    modes: Vec<Rows>,
    /// Per probe, its u, w and φ under the left-out modes' static response to a unit force at
    /// each of the mesh's unknowns: the residual flexibility R is symmetric, so that row is R
    /// applied to a unit load at the probe. `None` where the basis keeps no flexibility.
    residual: Option<Vec<Rows>>,
    /// Per probe, per u, w and φ, per direction of a point force (along the axis and across
    /// it), the residual row along each element as a polynomial in its ξ: formed where a step
    /// first asks for it.
    along: OnceCell<Vec<[RowAlong; 3]>>,
}

/// The probes' static correction over one step, each probe's u, w and φ a polynomial in the
/// step's own time σ = (t − t0)/h: the standing loads' constant, and each axle's moving
/// straight along its element.
pub(super) struct StepCorrection {
    t0: f64,
    h: f64,
    polys: Vec<Vec<f64>>,
}

impl StepCorrection {
    /// Add the correction at t to the probes' values `out`, four a probe (u, w, φ, a).
    pub fn add_to(&self, t: f64, out: &mut [f64]) {
        let sigma = ((t - self.t0) / self.h).clamp(0.0, 1.0);
        for (values, polys) in out.chunks_mut(4).zip(self.polys.chunks(3)) {
            for (value, poly) in values.iter_mut().zip(polys) {
                *value += poly.iter().rev().fold(0.0, |acc, c| acc * sigma + c);
            }
        }
    }
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
        Some(ModalProbes {
            modes,
            residual,
            along: OnceCell::new(),
        })
    }

    /// Per probe, its u, w and φ per unit amplitude of each mode.
    pub fn rows(&self) -> &[Rows] {
        &self.modes
    }

    /// Per probe (u, w, φ, the acceleration's w) from the amplitudes `z` and their
    /// accelerations `a` (the first `kept` of them: the acceleration's cutoff), before the
    /// static correction ([`Self::correct`]).
    pub fn read(&self, z: &[f64], a: &[f64], kept: usize) -> Vec<f64> {
        let dot = |r: &[f64], v: &[f64]| -> f64 { r.iter().zip(v).map(|(x, y)| x * y).sum() };
        let mut out = Vec::with_capacity(4 * self.modes.len());
        for rows in &self.modes {
            out.extend(rows.iter().map(|row| dot(row, z)));
            out.push(dot(&rows[1][..kept], &a[..kept]));
        }
        out
    }

    /// The sums over the modes [`Self::read`] takes, in its order: per probe u, w and φ of the
    /// amplitudes, then w of the first `kept` accelerations.
    pub fn form_rows(&self, kept: usize) -> Vec<(Vec<f64>, bool)> {
        self.modes
            .iter()
            .flat_map(|rows| {
                let mut a = rows[1].clone();
                a.iter_mut().skip(kept).for_each(|v| *v = 0.0);
                rows.iter()
                    .map(|row| (row.clone(), false))
                    .chain([(a, true)])
            })
            .collect()
    }

    /// Add to the probes' u, w and φ in `out` (four values a probe, as [`Self::read`] gives
    /// them) the static response of the modes left out to the `loads`.
    pub fn correct(&self, out: &mut [f64], loads: Loads) {
        let Some(residual) = &self.residual else {
            return;
        };
        for (r, values) in residual.iter().zip(out.chunks_mut(4)) {
            let mut corrected = [0.0; 3];
            loads(&mut |i, v| {
                for (c, row) in r.iter().enumerate() {
                    corrected[c] += row[i] * v;
                }
            });
            for (value, correction) in values.iter_mut().zip(corrected) {
                *value += correction;
            }
        }
    }
}

impl ModalProbes {
    /// The static correction over the step [t0, t1] under the `standing` loads and the axles
    /// moving along `paths` (place at t0, at t1, force): `None` where the basis keeps no
    /// flexibility. Within a step each axle stays in one element (a node crossing ends a
    /// step), where what a residual row reads of it is a polynomial in ξ, and ξ is linear in
    /// σ.
    pub fn correction_over(
        &self,
        beam: &Beam,
        (t0, t1): (f64, f64),
        standing: Loads,
        paths: &[(f64, f64, f64)],
    ) -> Option<StepCorrection> {
        let residual = self.residual.as_ref()?;
        let along = self.along.get_or_init(|| {
            residual
                .iter()
                .map(|rows| rows.each_ref().map(|row| beam.row_along(row)))
                .collect()
        });
        let mut constant = vec![0.0; 4 * residual.len()];
        self.correct(&mut constant, standing);
        let mut polys: Vec<Vec<f64>> = constant
            .chunks(4)
            .flat_map(|c| c[..3].iter().map(|&v| beam.polynomial_along_from(v)))
            .collect();
        beam.add_paths_along(along.as_flattened(), paths, &mut polys)?;
        Some(StepCorrection {
            t0,
            h: t1 - t0,
            polys,
        })
    }
}

/// The mesh's loads handed term by term (unknown, value) to the function given.
pub(super) type Loads<'a> = &'a dyn Fn(&mut dyn FnMut(usize, f64));

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::element::Section;
    use crate::beam::supports::Support;
    use crate::beam::{BeamModel, BeamSpec, Quadrature};

    /// A row's reading of a point force moving straight within an element, as the polynomial
    /// in the step's time a step's correction forms (the row along the element in powers of
    /// ξ, ξ linear in σ), against the force's own terms on the mesh at each time: within
    /// 10⁻¹³ of Σ|row| times the force, on an inclined beam (both of the force's local
    /// components) and across a whole element and a part of one.
    #[test]
    fn a_row_read_along_an_element_is_the_point_force_s_terms() {
        let beam = Beam::new(BeamSpec {
            from: [0.0, 0.0],
            to: [12.0, 5.0],
            section: Section {
                ea: 4.0e9,
                gav: 1.0e9,
                ei: 3.0e8,
                rho_a: 600.0,
                rho_i: 40.0,
            },
            depth: 0.5,
            supports: [Support::Pinned, Support::Roller],
            bearings: Vec::new(),
            elements: 6,
            order: 4,
            quadrature: Quadrature::Reduced,
            model: BeamModel::Exact,
            damping: None,
            self_weight: None,
        });
        let row: Vec<f64> = (0..beam.dim())
            .map(|i| ((i * 37 % 11) as f64 - 5.0) * 0.3)
            .collect();
        let size: f64 = row.iter().map(|v| v.abs()).sum();
        let force = [0.0, -2.5e5];
        let along = [beam.row_along(&row)];
        let h = beam.element_length();
        for (x0, x1) in [(2.0 * h, 3.0 * h), (4.1 * h, 4.9 * h), (1.0 * h, 0.2 * h)] {
            let mut poly = vec![Vec::new()];
            beam.add_paths_along(&along, &[(x0, x1, -force[1])], &mut poly)
                .expect("within an element");
            let poly = &poly[0];
            for sigma in [0.0, 0.25, 0.6, 1.0] {
                let x = x0 + sigma * (x1 - x0);
                let mut direct = 0.0;
                beam.point_load_terms(x, force, 0.0, |i, v| direct += row[i] * v);
                let read = poly.iter().rev().fold(0.0, |acc, c| acc * sigma + c);
                assert!(
                    (read - direct).abs() <= 1e-13 * size * 2.5e5,
                    "x {x}: {read} against {direct}"
                );
            }
        }
    }
}

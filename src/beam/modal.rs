//! The modal beam: the lowest m natural modes of the linear beam (K₀ φ = ω² M φ, supports
//! applied, φᵀ M φ = 1), whose amplitudes η replace the mesh's unknowns, q = Φ η. In them the
//! beam's equations are m uncoupled oscillators, η̈ + Ω² η = Φᵀ F, and whatever rides on the
//! beam sees it through the mesh's shape functions at the contact, projected by Φᵀ.
//!
//! What m modes leave out of a load's response is, for the modes well above the loading's
//! frequencies, its static part: the residual flexibility R = K₀⁻¹ − Φ Ω⁻² Φᵀ. Under a force
//! F the displacement Φ η + R F is the mode-acceleration method's: it recovers the deflection
//! under a moving load (the shear kink and the short waves of a point force, which a few modes
//! cannot hold) with the few modes that carry the dynamics. The correction is applied where
//! displacements are read (probes, envelopes, shapes); the equations of motion and the
//! energy budget keep Φ η, for which ½ ηᵀΩ²η + ½ η̇ᵀη̇ is the energy (R F does no work on
//! the modes: Φᵀ K₀ R F = 0).

use std::cell::RefCell;

use nalgebra::DMatrix;

use crate::linalg::{Assembly, Sparse, SparseLu};

/// Most modes a modal beam keeps: its matrices are dense in the modes, and on a large mesh
/// the sparse eigensolver computes at most this many.
pub const MAX_MODES: usize = 200;

/// How far past the cutoff a mode's frequency still counts as at it, relative. The cutoff is
/// most often f3 itself, and two eigensolutions of one mesh (the three lowest bending modes, and
/// every mode) give that mode 7·10⁻¹⁴ apart: compared exactly, a 6 m steel beam's plan counted
/// three modes below its cutoff instead of four, and left f3 out of the deck's acceleration (its
/// largest 26 % low). Far above round-off, far below the spacing of two modes.
const CUTOFF_ROUNDOFF: f64 = 1e-9;

/// Whether a mode's frequency lies at or below the deck acceleration's cutoff (both in Hz, or
/// both circular).
pub fn within_cutoff(frequency: f64, cutoff: f64) -> bool {
    frequency <= cutoff * (1.0 + CUTOFF_ROUNDOFF)
}

pub struct ModalBasis {
    /// Φ, mass-normalised, one column per mode, on the beam's free unknowns.
    shapes: DMatrix<f64>,
    /// Φ row by row: what one unknown of the mesh reads of every mode, contiguous, for the
    /// contact's few unknowns that every force evaluation expands and projects.
    by_unknown: Vec<f64>,
    /// Circular frequencies, ascending.
    pub omega: Vec<f64>,
    /// Φᵀ M: the amplitudes of a displacement, η = Φᵀ M q.
    amplitudes: DMatrix<f64>,
    /// The identity (the modes are mass-normalised) and Ω².
    mass: Sparse,
    stiffness: Sparse,
    /// K₀, factorised: the static part of the modes left out. `None` where the supports leave
    /// a mechanism, whose static response is not defined.
    flexibility: Option<SparseLu>,
    /// R's columns, each formed the first time a force acts on its unknown (on a mesh of at
    /// most [`KEPT_COLUMNS_UP_TO`] unknowns): a rider's force acts on the few unknowns under
    /// it, so R F is a sum of a few columns where a solve with K₀ would cost the whole mesh.
    columns_of_r: RefCell<Vec<Option<Box<[f64]>>>>,
}

/// Largest mesh (unknowns) whose residual flexibility is kept column by column: n² doubles
/// at most, 8 MB.
const KEPT_COLUMNS_UP_TO: usize = 1000;
/// Most unknowns a force may act on for R F to be summed from R's columns: a sparse solve
/// with K₀ costs about as much as this many columns (a beam's factor holds some tens of
/// entries per unknown); a distributed load (the beam's weight) takes the solve.
const FEW_FORCES: usize = 32;

impl ModalBasis {
    /// From the lowest modes of the linear beam with stiffness `k0` and mass `mass`.
    pub fn new(shapes: DMatrix<f64>, omega: Vec<f64>, k0: &Sparse, mass: &Sparse) -> ModalBasis {
        let m = omega.len();
        // Φᵀ M row by row, M sparse: no n × n matrix for a mesh of any size.
        let mut amplitudes = DMatrix::zeros(m, shapes.nrows());
        let mut column = vec![0.0; shapes.nrows()];
        for k in 0..m {
            crate::linalg::mul(mass, shapes.column(k).as_slice(), &mut column);
            amplitudes.row_mut(k).copy_from_slice(&column);
        }
        let diagonal = |values: &mut dyn Iterator<Item = f64>| {
            let mut a = Assembly::new(m);
            for (k, v) in values.enumerate() {
                a.add(k, k, v);
            }
            a.build()
        };
        let highest = omega.last().copied().unwrap_or(0.0);
        let rigid = omega.first().is_some_and(|&w| w <= 1e-6 * highest);
        ModalBasis {
            by_unknown: shapes.transpose().as_slice().to_vec(),
            mass: diagonal(&mut std::iter::repeat_n(1.0, m)),
            stiffness: diagonal(&mut omega.iter().map(|w| w * w)),
            shapes,
            omega,
            amplitudes,
            flexibility: if rigid {
                None
            } else {
                SparseLu::factor(k0, None)
            },
            columns_of_r: RefCell::new(Vec::new()),
        }
    }

    /// The number of modes.
    pub fn dim(&self) -> usize {
        self.omega.len()
    }

    pub fn mass(&self) -> &Sparse {
        &self.mass
    }

    /// Ω².
    pub fn stiffness(&self) -> &Sparse {
        &self.stiffness
    }

    /// q = Φ η. A mode whose amplitude is zero adds nothing: the deck acceleration keeps only
    /// the modes below its cutoff (three of D44's sixteen) and is expanded at every output row.
    pub fn expand(&self, eta: &[f64], q: &mut [f64]) {
        q.fill(0.0);
        for (e, column) in eta.iter().zip(self.columns()) {
            if *e == 0.0 {
                continue;
            }
            for (qi, p) in q.iter_mut().zip(column) {
                *qi += p * e;
            }
        }
    }

    /// q_i = Σ_k Φ_ik η_k for the unknowns `at` only.
    pub fn expand_at(&self, at: impl Iterator<Item = usize>, eta: &[f64], q: &mut [f64]) {
        for i in at {
            q[i] = self.value_at(i, eta);
        }
    }

    /// [`Self::expand_at`] of a displacement and a velocity together, each row of Φ read once.
    pub fn expand_pair_at(
        &self,
        at: impl Iterator<Item = usize>,
        (eta, eta_rate): (&[f64], &[f64]),
        (q, v): (&mut [f64], &mut [f64]),
    ) {
        for i in at {
            let row = self.row(i);
            q[i] = row.iter().zip(eta).map(|(p, e)| p * e).sum();
            v[i] = row.iter().zip(eta_rate).map(|(p, e)| p * e).sum();
        }
    }

    /// q_i = Σ_k Φ_ik η_k: one unknown of the mesh.
    pub fn value_at(&self, i: usize, eta: &[f64]) -> f64 {
        self.row(i).iter().zip(eta).map(|(p, e)| p * e).sum()
    }

    /// Row i of Φ.
    fn row(&self, i: usize) -> &[f64] {
        let m = self.omega.len();
        &self.by_unknown[i * m..(i + 1) * m]
    }

    /// out = Φᵀ f: a force on the mesh's unknowns as the modes feel it.
    pub fn project(&self, f: &[f64], out: &mut [f64]) {
        for (o, column) in out.iter_mut().zip(self.columns()) {
            *o = column.iter().zip(f).map(|(p, v)| p * v).sum();
        }
    }

    /// Φ's columns as contiguous slices (Φ is stored column by column): the expansions and
    /// projections run at every output row, where nalgebra's strided iterators cost twice.
    fn columns(&self) -> std::slice::ChunksExact<'_, f64> {
        self.shapes
            .as_slice()
            .chunks_exact(self.shapes.nrows().max(1))
    }

    /// Add v Φ_i· (row i of Φ, scaled) to `out`: one term of a sparse row projected.
    pub fn add_row(&self, i: usize, v: f64, out: &mut [f64]) {
        for (o, p) in out.iter_mut().zip(self.row(i)) {
            *o += p * v;
        }
    }

    /// η = Φᵀ M q: the modal amplitudes of a displacement (exact where q lies in the modes'
    /// span, the mass-orthogonal projection otherwise).
    pub fn amplitudes_of(&self, q: &[f64], eta: &mut [f64]) {
        for (k, e) in eta.iter_mut().enumerate() {
            *e = self
                .amplitudes
                .row(k)
                .iter()
                .zip(q)
                .map(|(a, b)| a * b)
                .sum();
        }
    }

    /// R f = K₀⁻¹ f − Φ Ω⁻² Φᵀ f, added to `q`: the static response of the modes left out.
    /// Nothing where the beam is a mechanism.
    pub fn add_static_correction(&self, f: &[f64], q: &mut [f64]) {
        let Some(lu) = &self.flexibility else { return };
        let acting = f.iter().filter(|v| **v != 0.0).count();
        if f.len() > KEPT_COLUMNS_UP_TO || acting > FEW_FORCES {
            if let Some(full) = self.residual_flexibility(f) {
                q.iter_mut().zip(&full).for_each(|(a, b)| *a += b);
            }
            return;
        }
        let mut columns = self.columns_of_r.borrow_mut();
        columns.resize(f.len(), None);
        for (j, &fj) in f.iter().enumerate() {
            if fj == 0.0 {
                continue;
            }
            let column = columns[j].get_or_insert_with(|| self.column_of_r(lu, j));
            q.iter_mut()
                .zip(column.iter())
                .for_each(|(a, r)| *a += r * fj);
        }
    }

    /// (R f)ᵢ at each unknown i of `at` for each of K forces acting on the unknowns `acting`
    /// (index, the K forces' values there): R is symmetric, so each is R's column i against
    /// the forces, a few products per unknown where [`Self::add_static_correction`] forms
    /// R f over the whole mesh, and the forces share each column as it is read. Vehicles'
    /// wheels read their track and its rates at the unknowns under them alone; `None` on a
    /// mesh past [`KEPT_COLUMNS_UP_TO`] unknowns or without a flexibility.
    pub fn static_corrections_at<const K: usize>(
        &self,
        acting: &[(usize, [f64; K])],
        at: &[usize],
    ) -> Option<Vec<[f64; K]>> {
        let lu = self.flexibility.as_ref()?;
        let n = self.shapes.nrows();
        if n > KEPT_COLUMNS_UP_TO {
            return None;
        }
        let mut columns = self.columns_of_r.borrow_mut();
        columns.resize(n, None);
        Some(
            at.iter()
                .map(|&i| {
                    let column = columns[i].get_or_insert_with(|| self.column_of_r(lu, i));
                    let mut out = [0.0; K];
                    for &(j, f) in acting {
                        let r = column[j];
                        out.iter_mut().zip(f).for_each(|(o, f)| *o += r * f);
                    }
                    out
                })
                .collect(),
        )
    }

    /// R's column j: K₀⁻¹ eⱼ less the modes' part of it.
    fn column_of_r(&self, lu: &SparseLu, j: usize) -> Box<[f64]> {
        let mut unit = vec![0.0; self.shapes.nrows()];
        unit[j] = 1.0;
        let mut r = unit.clone();
        lu.solve_in_place(&mut r);
        self.subtract_modal_part(&unit, &mut r);
        r.into_boxed_slice()
    }

    /// R f, the static response of the modes left out to f (`None` where no flexibility is
    /// kept: a beam free to move as a rigid body).
    pub fn residual_flexibility(&self, f: &[f64]) -> Option<Vec<f64>> {
        let lu = self.flexibility.as_ref()?;
        let mut full = f.to_vec();
        lu.solve_in_place(&mut full);
        self.subtract_modal_part(f, &mut full);
        Some(full)
    }

    /// x −= Φ Ω⁻² Φᵀ f.
    fn subtract_modal_part(&self, f: &[f64], x: &mut [f64]) {
        let mut p = vec![0.0; self.dim()];
        self.project(f, &mut p);
        for ((pk, w), column) in p.iter().zip(&self.omega).zip(self.columns()) {
            let w2 = w * w;
            if w2 > 0.0 {
                for (xi, s) in x.iter_mut().zip(column) {
                    *xi -= s * pk / w2;
                }
            }
        }
    }

    /// The largest displacement (or rotation) of the mesh that a unit amplitude of each mode
    /// makes: what an amplitude stands for in the error norm.
    pub fn displacement_per_amplitude(&self) -> Vec<f64> {
        (0..self.dim())
            .map(|k| {
                self.shapes
                    .column(k)
                    .iter()
                    .fold(0.0_f64, |m, v| m.max(v.abs()))
            })
            .collect()
    }
}

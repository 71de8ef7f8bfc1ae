//! Natural modes about the undeformed state: K φ = ω² M φ with the supports applied, solved
//! densely through the Cholesky factor of M (C = L⁻¹ K L⁻ᵀ is symmetric). Dense is fine at the
//! sizes a modal check uses (a few hundred unknowns).

use nalgebra::{DMatrix, SymmetricEigen};

use crate::beam::Beam;
use crate::linalg::{self, Sparse};

#[derive(Clone, Debug)]
pub struct Modes {
    /// Ascending circular frequencies (rad/s).
    pub omega: Vec<f64>,
    /// Mass-normalised shapes, one column per mode, on the free unknowns.
    pub shapes: DMatrix<f64>,
}

fn dense(m: &Sparse) -> DMatrix<f64> {
    let mut d = DMatrix::zeros(m.nrows(), m.ncols());
    for (j, (i, v)) in linalg::entries(m) {
        d[(i, j)] += v;
    }
    d
}

pub fn modes(beam: &Beam, count: usize) -> Option<Modes> {
    let n = beam.dim();
    let k = dense(&beam.tangent(&vec![0.0; n]));
    let m = dense(beam.mass());
    let l = m.cholesky()?.l();
    let l_inv = l.clone().try_inverse()?;
    let c = &l_inv * k * l_inv.transpose();
    let c = (&c + c.transpose()) * 0.5;
    let eig = SymmetricEigen::new(c);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let count = count.min(n);
    let omega = order[..count]
        .iter()
        .map(|&i| eig.eigenvalues[i].max(0.0).sqrt())
        .collect();
    let lt_inv = l_inv.transpose();
    let mut shapes = DMatrix::zeros(n, count);
    for (c, &i) in order[..count].iter().enumerate() {
        shapes.set_column(c, &(&lt_inv * eig.eigenvectors.column(i)));
    }
    Some(Modes { omega, shapes })
}

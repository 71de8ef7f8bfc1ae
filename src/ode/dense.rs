//! The one dense factorisation the integrators need: LU with partial pivoting, reused for as many
//! right-hand sides as the iteration asks.

use nalgebra::{DMatrix, DVector};

pub struct LinearSolve {
    lu: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
}

impl LinearSolve {
    /// `None` when the matrix is singular.
    pub fn factor(m: DMatrix<f64>) -> Option<LinearSolve> {
        let lu = m.lu();
        if !lu.is_invertible() {
            return None;
        }
        Some(LinearSolve { lu })
    }

    pub fn solve_in_place(&self, b: &mut [f64]) {
        let mut v = DVector::from_column_slice(b);
        self.lu.solve_mut(&mut v);
        b.copy_from_slice(v.as_slice());
    }
}

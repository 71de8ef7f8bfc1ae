//! Sparse matrices and the one factorisation every solver reuses. Assembled beam matrices are
//! banded, so a sparse LU with a fill-reducing ordering costs O(unknowns) per factorisation and
//! solve; the symbolic analysis is done once per sparsity pattern and kept.

use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMat, Triplet};
use faer::Par;

pub type Sparse = SparseColMat<usize, f64>;

/// Entries gathered for a square sparse matrix; duplicates are summed.
#[derive(Clone, Debug, Default)]
pub struct Assembly {
    n: usize,
    entries: Vec<Triplet<usize, usize, f64>>,
}

impl Assembly {
    pub fn new(n: usize) -> Self {
        Assembly {
            n,
            entries: Vec::new(),
        }
    }

    pub fn dim(&self) -> usize {
        self.n
    }

    pub fn add(&mut self, row: usize, col: usize, val: f64) {
        self.entries.push(Triplet::new(row, col, val));
    }

    /// Add every entry of `m` scaled by `scale`, shifted by `offset` rows and columns.
    pub fn add_sparse(&mut self, m: &Sparse, scale: f64, row_offset: usize, col_offset: usize) {
        for (j, (i, v)) in entries(m) {
            self.add(i + row_offset, j + col_offset, scale * v);
        }
    }

    pub fn build(&self) -> Sparse {
        SparseColMat::try_new_from_triplets(self.n, self.n, &self.entries)
            .expect("assembled indices lie inside the matrix")
    }

    /// Where each entry lands in the built matrix, for later assemblies of the same entries.
    pub fn pattern(&self) -> AssemblyPattern {
        let template = self.build();
        let at = self
            .entries
            .iter()
            .map(|e| position(&template, e.row, e.col).expect("every entry is in the pattern"))
            .collect();
        AssemblyPattern {
            template,
            at,
            cells: self.entries.iter().map(|e| (e.row, e.col)).collect(),
        }
    }
}

/// The pattern of an assembly whose entries come in the same order every time (a tangent
/// stiffness re-evaluated at a new state): the values are summed straight into place, with
/// none of the sorting that building from entries needs.
#[derive(Clone, Debug)]
pub struct AssemblyPattern {
    template: Sparse,
    at: Vec<usize>,
    cells: Vec<(usize, usize)>,
}

impl AssemblyPattern {
    /// The matrix of `a`; built afresh if its entries are not the ones this pattern was made of.
    pub fn build(&self, a: &Assembly) -> Sparse {
        let same = a.n == self.template.nrows()
            && a.entries.len() == self.cells.len()
            && a.entries
                .iter()
                .zip(&self.cells)
                .all(|(e, &(i, j))| e.row == i && e.col == j);
        if !same {
            return a.build();
        }
        let mut m = self.template.clone();
        m.val_mut().fill(0.0);
        for (e, &k) in a.entries.iter().zip(&self.at) {
            m.val_mut()[k] += e.val;
        }
        m
    }
}

/// (column, (row, value)) of every stored entry.
pub fn entries(m: &Sparse) -> impl Iterator<Item = (usize, (usize, f64))> + '_ {
    let col_ptr = m.symbolic().col_ptr();
    let row_idx = m.symbolic().row_idx();
    let val = m.val();
    (0..m.ncols())
        .flat_map(move |j| (col_ptr[j]..col_ptr[j + 1]).map(move |k| (j, (row_idx[k], val[k]))))
}

/// y = A x. Plain loops over the CSC arrays: this is the innermost operation of every
/// structural step.
pub fn mul(a: &Sparse, x: &[f64], y: &mut [f64]) {
    y.fill(0.0);
    let col_ptr = a.symbolic().col_ptr();
    let row_idx = a.symbolic().row_idx();
    let val = a.val();
    for (j, &xj) in x[..a.ncols()].iter().enumerate() {
        let column = col_ptr[j]..col_ptr[j + 1];
        for (&i, &v) in row_idx[column.clone()].iter().zip(&val[column]) {
            y[i] += v * xj;
        }
    }
}

/// A dense matrix as sparse (small problems: the rigid-track disk, finite-difference Jacobians).
pub fn from_dense(m: &nalgebra::DMatrix<f64>) -> Sparse {
    let mut a = Assembly::new(m.nrows());
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            if m[(i, j)] != 0.0 {
                a.add(i, j, m[(i, j)]);
            }
        }
    }
    a.build()
}

/// A + c B for matrices A and B assembled from the same kinds of entries: both are put on
/// their joint pattern once, after which a new c only rescales values (no sorting).
pub struct Combination {
    a: Vec<f64>,
    b: Vec<f64>,
    joint: Sparse,
    /// Where each stored entry of A (of B) sits in the joint pattern, and A's (B's) pattern.
    a_at: Vec<usize>,
    b_at: Vec<usize>,
    a_pattern: (Vec<usize>, Vec<usize>),
    b_pattern: (Vec<usize>, Vec<usize>),
}

impl Combination {
    pub fn new(a: &Sparse, b: &Sparse) -> Self {
        let n = a.nrows();
        let (mut pa, mut pb) = (Assembly::new(n), Assembly::new(n));
        pa.add_sparse(a, 1.0, 0, 0);
        pa.add_sparse(b, 0.0, 0, 0);
        pb.add_sparse(a, 0.0, 0, 0);
        pb.add_sparse(b, 1.0, 0, 0);
        let (ja, jb) = (pa.build(), pb.build());
        let at = |m: &Sparse| {
            entries(m)
                .map(|(j, (i, _))| position(&ja, i, j).expect("A and B lie in the joint pattern"))
                .collect()
        };
        Combination {
            a: ja.val().to_vec(),
            b: jb.val().to_vec(),
            a_at: at(a),
            b_at: at(b),
            a_pattern: pattern(a),
            b_pattern: pattern(b),
            joint: ja,
        }
    }

    /// New values of A on the pattern it had: no sorting. `false` if the pattern changed.
    pub fn update_a(&mut self, a: &Sparse) -> bool {
        refill(&mut self.a, &self.a_at, &self.a_pattern, a)
    }

    /// New values of B on the pattern it had: no sorting. `false` if the pattern changed.
    pub fn update_b(&mut self, b: &Sparse) -> bool {
        refill(&mut self.b, &self.b_at, &self.b_pattern, b)
    }

    pub fn at(&mut self, c: f64) -> &Sparse {
        for (v, (a, b)) in self
            .joint
            .val_mut()
            .iter_mut()
            .zip(self.a.iter().zip(&self.b))
        {
            *v = a + c * b;
        }
        &self.joint
    }
}

/// Σ c_k A_k for any number of operands whose patterns may differ or move (the mass of a
/// general problem, which may depend on its state), on the pattern of the last sum while the
/// operands fit in it: sums on one pattern share a factorisation's symbolic analysis, and
/// nothing is sorted. [`Combination`] is the two-operand case with fixed patterns, which
/// rescales without looking at the patterns again.
///
/// Where an operand no longer fits, the pattern is rebuilt from the operands alone, not widened:
/// an operand moving along the matrix (a body's inertia riding the length of a beam, assembled
/// into its mass) would otherwise leave the union of every position it passed, and an LU of
/// that fills in far beyond the band and the patch where the body is (the `bridge` bench
/// measures the factorisations this saves).
#[derive(Default)]
pub struct JointSum(Option<Sparse>);

impl JointSum {
    /// Σ c_k A_k on the last sum's pattern, or on the operands' own union where they leave it.
    pub fn combine(&mut self, parts: &[(&Sparse, f64)]) -> Sparse {
        if let Some(last) = &self.0 {
            let mut sum = last.clone();
            sum.val_mut().fill(0.0);
            if parts.iter().all(|&(a, c)| add_within(&mut sum, a, c)) {
                return sum;
            }
        }
        let mut union = Assembly::new(parts[0].0.nrows());
        parts
            .iter()
            .for_each(|&(a, c)| union.add_sparse(a, c, 0, 0));
        let sum = union.build();
        self.0 = Some(sum.clone());
        sum
    }
}

/// The entries of Σ w_k g_k g_kᵀ, term by term: (i, j, w g_i g_j) for every pair of entries of
/// a term's row (a pair two terms share comes once from each).
pub fn low_rank_entries(terms: &[RankOne]) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
    terms.iter().flat_map(|(w, row)| {
        row.iter()
            .flat_map(move |&(i, gi)| row.iter().map(move |&(j, gj)| (i, j, w * gi * gj)))
    })
}

/// One operand's values put in place on the joint pattern, if `m` still has the operand's
/// `pattern`; `at` says where each of its stored entries goes.
fn refill(
    joint: &mut [f64],
    at: &[usize],
    pattern_was: &(Vec<usize>, Vec<usize>),
    m: &Sparse,
) -> bool {
    if &pattern(m) != pattern_was {
        return false;
    }
    joint.fill(0.0);
    for (v, &k) in m.val().iter().zip(at) {
        joint[k] += v;
    }
    true
}

fn pattern(m: &Sparse) -> (Vec<usize>, Vec<usize>) {
    (
        m.symbolic().col_ptr().to_vec(),
        m.symbolic().row_idx().to_vec(),
    )
}

/// target += alpha · src in place, where src's pattern lies within target's: the sum keeps
/// target's pattern, so a factorisation of it reuses its symbolic analysis, and nothing is
/// sorted. `false` (target then untouched) where src has an entry outside it.
pub fn add_within(target: &mut Sparse, src: &Sparse, alpha: f64) -> bool {
    let (t_ptr, t_rows) = (target.symbolic().col_ptr(), target.symbolic().row_idx());
    let (s_ptr, s_rows) = (src.symbolic().col_ptr(), src.symbolic().row_idx());
    let mut at = Vec::with_capacity(s_rows.len());
    for j in 0..src.ncols() {
        let mut k = t_ptr[j];
        for &i in &s_rows[s_ptr[j]..s_ptr[j + 1]] {
            while k < t_ptr[j + 1] && t_rows[k] < i {
                k += 1;
            }
            if k == t_ptr[j + 1] || t_rows[k] != i {
                return false;
            }
            at.push(k);
        }
    }
    let values = target.val_mut();
    for (&k, v) in at.iter().zip(src.val()) {
        values[k] += alpha * v;
    }
    true
}

/// Index of entry (i, j) in the stored values of m, if it is in the pattern.
pub fn position(m: &Sparse, i: usize, j: usize) -> Option<usize> {
    let col_ptr = m.symbolic().col_ptr();
    let rows = &m.symbolic().row_idx()[col_ptr[j]..col_ptr[j + 1]];
    rows.binary_search(&i).ok().map(|k| col_ptr[j] + k)
}

/// Sparse LU that keeps its symbolic analysis while the pattern stays the same.
pub struct SparseLu {
    pattern: (Vec<usize>, Vec<usize>),
    symbolic: SymbolicLu<usize>,
    lu: Lu<usize, f64>,
}

impl SparseLu {
    /// `None` when the matrix is (numerically) singular.
    pub fn factor(m: &Sparse, previous: Option<SparseLu>) -> Option<SparseLu> {
        faer::set_global_parallelism(Par::Seq);
        let pattern = pattern(m);
        let symbolic = match previous {
            Some(p) if p.pattern == pattern => p.symbolic,
            _ => SymbolicLu::try_new(m.symbolic()).ok()?,
        };
        let lu = Lu::try_new_with_symbolic(symbolic.clone(), m.as_ref()).ok()?;
        let out = SparseLu {
            pattern,
            symbolic,
            lu,
        };
        let mut probe = vec![1.0; m.nrows()];
        out.solve_in_place(&mut probe);
        probe.iter().all(|v| v.is_finite()).then_some(out)
    }

    pub fn dim(&self) -> usize {
        self.pattern.0.len() - 1
    }

    pub fn solve_in_place(&self, b: &mut [f64]) {
        use faer::linalg::solvers::Solve;
        let n = b.len();
        self.lu
            .solve_in_place(faer::MatMut::from_column_major_slice_mut(b, n, 1));
    }
}

/// Terms w g gᵀ of a matrix, each g a sparse row: (unknown, coefficient).
pub type LowRank = Vec<RankOne>;
/// One term w g gᵀ of a [`LowRank`]: its weight and the sparse row g.
pub type RankOne = (f64, Vec<(usize, f64)>);

/// (A + G W Gᵀ)⁻¹ x from A's factorisation (Woodbury): with Z = A⁻¹ G,
/// x ← A⁻¹x − Z (W⁻¹ + Gᵀ Z)⁻¹ Gᵀ A⁻¹x. W is diagonal, the columns of G sparse and few.
pub struct Woodbury {
    rows: Vec<Vec<(usize, f64)>>,
    /// A⁻¹ g_k.
    z: Vec<Vec<f64>>,
    capacitance: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
}

impl Woodbury {
    /// `None` when the capacitance matrix is singular, i.e. so is the whole.
    pub fn new(lu: &SparseLu, terms: LowRank) -> Option<Woodbury> {
        let n = lu.dim();
        let z: Vec<Vec<f64>> = terms
            .iter()
            .map(|(_, g)| {
                let mut c = vec![0.0; n];
                g.iter().for_each(|&(i, v)| c[i] += v);
                lu.solve_in_place(&mut c);
                c
            })
            .collect();
        let r = terms.len();
        let capacitance = nalgebra::DMatrix::from_fn(r, r, |i, j| {
            let gz: f64 = terms[i].1.iter().map(|&(k, v)| v * z[j][k]).sum();
            gz + if i == j { 1.0 / terms[i].0 } else { 0.0 }
        })
        .lu();
        if r > 0 && !capacitance.is_invertible() {
            return None;
        }
        Some(Woodbury {
            rows: terms.into_iter().map(|(_, g)| g).collect(),
            z,
            capacitance,
        })
    }

    pub fn solve_in_place(&self, lu: &SparseLu, x: &mut [f64]) {
        lu.solve_in_place(x);
        if self.rows.is_empty() {
            return;
        }
        let mut coef = nalgebra::DVector::from_iterator(
            self.rows.len(),
            self.rows
                .iter()
                .map(|g| g.iter().map(|&(k, v)| v * x[k]).sum::<f64>()),
        );
        // In place: every Newton iteration of a rider's run comes through here.
        let solved = self.capacitance.solve_mut(&mut coef);
        debug_assert!(solved, "checked invertible when built");
        for (c, z) in coef.iter().zip(&self.z) {
            x.iter_mut().zip(z).for_each(|(xi, zi)| *xi -= c * zi);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// n × n with diag(i) on the diagonal and constants below and above it.
    fn tridiagonal(n: usize, diag: impl Fn(usize) -> f64, lower: f64, upper: f64) -> Sparse {
        let mut a = Assembly::new(n);
        for i in 0..n {
            a.add(i, i, diag(i));
            if i > 0 {
                a.add(i, i - 1, lower);
                a.add(i - 1, i, upper);
            }
        }
        a.build()
    }

    /// A tridiagonal system with a known solution, solved twice through one symbolic analysis.
    #[test]
    fn tridiagonal_solve_and_reuse() {
        let n = 50;
        let m = tridiagonal(n, |_| 4.0, -1.0, -2.0);
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.3).sin()).collect();
        let mut b = vec![0.0; n];
        mul(&m, &x, &mut b);
        let lu = SparseLu::factor(&m, None).unwrap();
        let lu = SparseLu::factor(&m, Some(lu)).unwrap();
        lu.solve_in_place(&mut b);
        for i in 0..n {
            assert!((b[i] - x[i]).abs() < 1e-13);
        }
        let mut s = Assembly::new(2);
        s.add(0, 0, 1.0);
        s.add(1, 0, 1.0);
        s.add(0, 1, 1.0);
        s.add(1, 1, 1.0);
        assert!(SparseLu::factor(&s.build(), None).is_none());
    }

    /// A sum made in place on a wider pattern equals the one assembled from triplets, entry
    /// by entry (exactly: each entry is the same two products added in the same order); an
    /// operand with an entry outside the pattern is refused and leaves the target as it was.
    #[test]
    fn add_within_matches_assembly() {
        let n = 6;
        let (mut wide, mut narrow, mut outside) =
            (Assembly::new(n), Assembly::new(n), Assembly::new(n));
        for i in 0..n {
            wide.add(i, i, 2.0 + i as f64);
            narrow.add(i, i, -0.5 * i as f64);
            if i > 0 {
                wide.add(i, i - 1, 1.0);
                wide.add(i - 1, i, 0.25);
                narrow.add(i, i - 1, 3.0);
            }
        }
        outside.add(0, n - 1, 1.0);
        let (wide, narrow) = (wide.build(), narrow.build());
        let mut sum = wide.clone();
        assert!(add_within(&mut sum, &narrow, 0.3));
        let mut whole = Assembly::new(n);
        whole.add_sparse(&wide, 1.0, 0, 0);
        whole.add_sparse(&narrow, 0.3, 0, 0);
        let whole = whole.build();
        for j in 0..n {
            for i in 0..n {
                let at = |m: &Sparse| position(m, i, j).map_or(0.0, |k| m.val()[k]);
                assert_eq!(at(&sum), at(&whole), "({i}, {j})");
            }
        }
        let before = sum.val().to_vec();
        assert!(!add_within(&mut sum, &outside.build(), 1.0));
        assert_eq!(sum.val(), &before[..]);
    }

    /// A rider's rank-one block moving along a tridiagonal matrix, as a disk's inertia
    /// assembled into a beam's mass: every sum equals the one assembled from its operands, and
    /// after the block has moved from one end to the other the pattern holds no more than the
    /// band and the block where it now is. Had the pattern kept every place the block passed,
    /// it would be a band seven wide (about 7n entries, against the 3n + 16 here).
    #[test]
    fn joint_sum_follows_a_moving_rider() {
        let n = 20;
        let band = tridiagonal(n, |_| 2.0, -1.0, -1.0);
        let mut joint = JointSum::default();
        let mut last = None;
        for at in 0..n - 3 {
            let terms: LowRank = vec![(0.7, (at..at + 4).map(|i| (i, 1.0 + i as f64)).collect())];
            let mut block = Assembly::new(n);
            low_rank_entries(&terms).for_each(|(i, j, v)| block.add(i, j, v));
            let sum = joint.combine(&[(&band, 1.5), (&block.build(), 1.0)]);
            for j in 0..n {
                for i in 0..n {
                    let at_m = |m: &Sparse| position(m, i, j).map_or(0.0, |k| m.val()[k]);
                    let g = |k: usize| {
                        if (at..at + 4).contains(&k) {
                            1.0 + k as f64
                        } else {
                            0.0
                        }
                    };
                    let expected = 1.5 * at_m(&band) + 0.7 * g(i) * g(j);
                    assert!((at_m(&sum) - expected).abs() < 1e-12, "at {at}: ({i}, {j})");
                }
            }
            last = Some(sum);
        }
        let last = last.expect("summed above");
        let (band_nnz, block) = (3 * n - 2, 16);
        assert!(
            last.compute_nnz() <= band_nnz + 2 * block,
            "{} entries after the rider's ride",
            last.compute_nnz()
        );
    }

    /// The Woodbury solve against the assembled matrix: a tridiagonal A, unsymmetric, plus
    /// three rank-one terms whose rows overlap, one with a negative weight (as the unit mass
    /// standing in on a contact coordinate is taken back out). Round-off only, so 1e-12.
    #[test]
    fn woodbury_solves_the_assembled_system() {
        let n = 12;
        let mut a = Assembly::new(n);
        for i in 0..n {
            a.add(i, i, 4.0 + i as f64 * 0.1);
            if i > 0 {
                a.add(i, i - 1, -1.0);
                a.add(i - 1, i, -1.5);
            }
        }
        let terms: LowRank = vec![
            (2.0, vec![(3, 1.0), (4, 0.5), (11, -0.3)]),
            (0.7, vec![(4, 1.0), (5, 2.0)]),
            (-0.5, vec![(11, 1.0)]),
        ];
        let mut whole = a.clone();
        for (w, g) in &terms {
            for &(i, gi) in g {
                for &(j, gj) in g {
                    whole.add(i, j, w * gi * gj);
                }
            }
        }
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).cos()).collect();
        let mut b = vec![0.0; n];
        mul(&whole.build(), &x, &mut b);
        let lu = SparseLu::factor(&a.build(), None).expect("A is regular");
        let w = Woodbury::new(&lu, terms).expect("the whole is regular");
        w.solve_in_place(&lu, &mut b);
        for (bi, xi) in b.iter().zip(&x) {
            assert!((bi - xi).abs() < 1e-12, "{bi} against {xi}");
        }
    }
}

//! Natural modes about the undeformed state: K φ = ω² M φ with the supports applied. Up to
//! [`DENSE_LIMIT`] unknowns every mode is solved densely through the Cholesky factor of M
//! (C = L⁻¹ K L⁻ᵀ is symmetric); a larger mesh, whose dense matrices would take n² memory and
//! n³ time, gets the lowest modes by subspace iteration on the sparse matrices (Bathe's
//! method: inverse iteration of a block of vectors with a Rayleigh–Ritz step each pass).

use nalgebra::{DMatrix, SymmetricEigen};

use crate::beam::damping::{DampingSpec, Rayleigh};
use crate::beam::supports::rigid_motions;
use crate::beam::{Beam, BeamModel, BeamSpec};
use crate::linalg::{self, Combination, Sparse, SparseLu};
use crate::recent::SharedRecent;

/// Largest mesh (unknowns) solved densely: 2000² doubles are 32 MB and a second of work.
pub const DENSE_LIMIT: usize = 2000;
/// Most modes the sparse path computes: its block holds count + 8 vectors of the mesh's size.
pub const MAX_SPARSE_MODES: usize = 200;
/// A sparse eigenvalue is taken as settled when an iteration moves it by less than this,
/// relative: its round-off jitter from pass to pass is about 2e-10.
const SETTLED: f64 = 1e-8;
/// A sparse eigenvalue within this fraction of the shift σ of zero is a rigid-body motion,
/// settled: its round-off jitter is about 3e-7 σ from pass to pass (a pinned–free D44 beam on
/// 40 elements), where D44's lowest bending mode lies at 3·10⁵ σ on that mesh and, σ growing
/// with the square of the mesh's density, at about σ on the finest mesh allowed.
const RIGID: f64 = 1e-3;
/// Subspace iterations before the sparse path gives up.
const MAX_ITERATIONS: usize = 300;

#[derive(Clone, Debug)]
pub struct Modes {
    /// Ascending circular frequencies (rad/s).
    pub omega: Vec<f64>,
    /// Mass-normalised shapes, one column per mode, on the free unknowns.
    pub shapes: DMatrix<f64>,
}

/// What a mode of the straight beam is: the unknowns of the axis' stretch and those of its
/// bending are coupled only through the deformation, so about the undeformed state each mode
/// moves one kind or the other.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ModeKind {
    /// Transverse displacement and rotation: what EN 1991-2's f1, f3 and the deck's
    /// acceleration mean.
    Bending,
    /// Stretch along the axis, w ≡ 0.
    Axial,
    /// A motion the supports leave free (sliding, moving across, turning), at zero frequency:
    /// no rule on bending modes counts it.
    Rigid,
}

impl ModeKind {
    pub fn name(self) -> &'static str {
        match self {
            ModeKind::Bending => "bending",
            ModeKind::Axial => "axial",
            ModeKind::Rigid => "rigid",
        }
    }
}

impl Modes {
    /// Each mode's kind: the lowest as many as the supports leave rigid-body motions are
    /// those (their frequencies are round-off); of the others, by where the kinetic energy
    /// φᵀ M φ lies, mostly in the axial displacements u an axial mode, otherwise a bending one.
    pub fn kinds(&self, beam: &Beam) -> Vec<ModeKind> {
        let axial: Vec<usize> = (0..beam.nodes())
            .filter_map(|node| beam.eq_of(node, 0))
            .collect();
        let rigid = rigid_motions(beam.spec.supports, beam.spec.bearings.len());
        let mass = beam.mass();
        (0..self.shapes.ncols())
            .map(|j| {
                if j < rigid {
                    return ModeKind::Rigid;
                }
                let phi = self.shapes.column(j);
                let mut m_phi = vec![0.0; phi.len()];
                linalg::mul(mass, phi.as_slice(), &mut m_phi);
                let total: f64 = phi.iter().zip(&m_phi).map(|(a, b)| a * b).sum();
                let along: f64 = axial.iter().map(|&i| phi[i] * m_phi[i]).sum();
                if along > 0.5 * total {
                    ModeKind::Axial
                } else {
                    ModeKind::Bending
                }
            })
            .collect()
    }

    /// The circular frequencies of the bending modes, ascending.
    pub fn bending_omega(&self, beam: &Beam) -> Vec<f64> {
        self.kinds(beam)
            .iter()
            .zip(&self.omega)
            .filter(|(k, _)| **k == ModeKind::Bending)
            .map(|(_, w)| *w)
            .collect()
    }
}

/// A square matrix read entry by entry, (row, column, value): the mesh's sparse K and M, or
/// the dense ones a subspace iteration reduces them to. Entries that are exactly zero may be
/// left out; a repeated entry adds.
trait Entries {
    fn dim(&self) -> usize;
    fn for_each_entry(&self, f: impl FnMut(usize, usize, f64));
}

impl Entries for Sparse {
    fn dim(&self) -> usize {
        self.nrows()
    }
    fn for_each_entry(&self, mut f: impl FnMut(usize, usize, f64)) {
        for (j, (i, v)) in linalg::entries(self) {
            f(i, j, v);
        }
    }
}

impl Entries for DMatrix<f64> {
    fn dim(&self) -> usize {
        self.nrows()
    }
    fn for_each_entry(&self, mut f: impl FnMut(usize, usize, f64)) {
        for j in 0..self.ncols() {
            for i in 0..self.nrows() {
                f(i, j, self[(i, j)]);
            }
        }
    }
}

/// The dense block of `a` on the unknowns `rows` (ascending); `at[i]` is unknown i's place in
/// the block, or `usize::MAX` outside it.
fn block(a: &impl Entries, rows: &[usize], at: &[usize]) -> faer::Mat<f64> {
    let mut b = faer::Mat::zeros(rows.len(), rows.len());
    a.for_each_entry(|i, j, v| {
        if at[i] != usize::MAX && at[j] != usize::MAX {
            b[(at[i], at[j])] += v;
        }
    });
    b
}

/// Dense eigensolutions kept for the meshes last solved: planning a scene (the mesh and the
/// model it chooses) and running it (a modal beam's basis) ask for the modes of the same mesh
/// several times, and a sweep's cases share their beam.
const KEPT: usize = 8;
/// Largest mesh (unknowns) whose dense eigensolution is kept: n² doubles each.
const KEPT_LIMIT: usize = 400;
/// Past [`KEPT_LIMIT`] unknowns, this many modes or fewer come from the sparse path.
const FEW_MODES: usize = 48;

type Eigen = std::sync::Arc<(Vec<f64>, DMatrix<f64>)>;

static KEPT_SOLUTIONS: SharedRecent<Eigen> = SharedRecent::new(KEPT);

/// The beam's Rayleigh damping, a ratio anchored on the natural frequencies of the bending
/// modes its mesh has; `Err` names a mode the mesh does not have.
pub fn rayleigh(beam: &Beam) -> Result<Option<Rayleigh>, String> {
    let Some(spec) = beam.spec.damping else {
        return Ok(None);
    };
    // α and β as given are checked where a ratio is: at the lowest bending mode, whose ratio
    // α/(2ω₁) + βω₁/2 of 1 or more leaves no vibration to damp.
    // (A beam free to move as a rigid body has no lowest vibration to check.)
    let needed = Rayleigh::modes_needed(spec);
    let omega = lowest_bending(beam, needed.max(1))
        .ok_or("the natural modes the damping is checked on could not be computed")?;
    if let (DampingSpec::Rayleigh { alpha, beta }, Some(&w1)) = (spec, omega.first()) {
        let zeta = (Rayleigh { alpha, beta }).ratio_at(w1);
        if w1.is_normal() && w1 > 0.0 && (zeta >= 1.0 || zeta.is_nan()) {
            return Err(format!(
                "`track.beam.damping` {{alpha: {alpha:e}, beta: {beta:e}}} damps the lowest bending mode (f = {:.4} Hz) at a ratio of {zeta:.4e} (α/(2ω) + βω/2); a ratio of 1 or more is no longer a vibration: give α < {:.4e} 1/s or β < {:.4e} s",
                w1 / std::f64::consts::TAU,
                2.0 * w1,
                2.0 / w1
            ));
        }
    }
    if omega.len() < needed {
        return Err(format!(
            "`track.beam.damping.modes` names bending mode {needed}, but the mesh has {} bending modes",
            omega.len()
        ));
    }
    let r = Rayleigh::resolve(spec, &omega)
        .filter(|r| r.alpha.is_finite() && r.beta.is_finite() && r.alpha >= 0.0 && r.beta >= 0.0);
    match r {
        Some(r) if needed == 0 || omega[..needed].iter().all(|w| w.is_normal()) => Ok(Some(r)),
        _ => Err(format!(
            "`track.beam.damping` is anchored on modes whose frequencies ({}) are not positive numbers: the beam moves as a rigid body, or its values are too extreme",
            crate::error::short_numbers(&format!("{:?} rad/s", &omega[..needed]))
        )),
    }
}

/// EN 1991-2's lower bound of the deck acceleration's cutoff (Hz).
const CUTOFF_FLOOR_HZ: f64 = 30.0;

/// The frequency (Hz) above which the deck's acceleration leaves the modes out, and why: `given`,
/// or EN 1991-2 §6.4.6.4's max(30 Hz, 1.5 f1, f3), f1 and f3 the first and third bending modes.
/// `None` where the modes cannot be computed.
pub fn acceleration_cutoff(beam: &Beam, given: Option<f64>) -> Option<(f64, String)> {
    if let Some(f) = given {
        return Some((
            f,
            "as the scene gives (output.acceleration_cutoff_hz)".to_string(),
        ));
    }
    let f: Vec<f64> = lowest_bending(beam, 3)?
        .iter()
        .map(|w| w / std::f64::consts::TAU)
        .collect();
    let f1 = f.first().copied().unwrap_or(0.0);
    let f3 = f.get(2).copied().unwrap_or(f1);
    Some((
        CUTOFF_FLOOR_HZ.max(1.5 * f1).max(f3),
        format!(
            "EN 1991-2 §6.4.6.4: max(30 Hz, 1.5 f1 = {:.2} Hz, f3 = {f3:.2} Hz), f1 and f3 the first and third bending modes",
            1.5 * f1
        ),
    ))
}

/// The circular frequencies of the lowest `count` bending modes (fewer where the mesh has
/// fewer), ascending: the modes EN 1991-2's rules and a damping ratio's anchors mean.
pub fn lowest_bending(beam: &Beam, count: usize) -> Option<Vec<f64>> {
    let n = beam.dim();
    let mut asked = count.min(n);
    loop {
        let bending = modes(beam, asked)?.bending_omega(beam);
        if bending.len() >= count || asked >= n {
            return Some(bending.into_iter().take(count).collect());
        }
        asked = (2 * asked).min(n);
    }
}

/// Every eigenpair of the beam's K₀ φ = λ M φ, dense, from the kept ones where the same mesh
/// was solved before. K₀ is the tangent at the undeformed state whatever the model, so the
/// key leaves the model out.
fn dense_all(beam: &Beam) -> Option<Eigen> {
    let n = beam.dim();
    let key = format!(
        "{:?}",
        BeamSpec {
            model: BeamModel::Exact,
            damping: None,
            self_weight: None,
            ..beam.spec.clone()
        }
    );
    if let Some(hit) = KEPT_SOLUTIONS.get(&key) {
        return Some(hit);
    }
    let k = beam.tangent(&vec![0.0; n]);
    let solved: Eigen = std::sync::Arc::new(generalized(&k, beam.mass(), n)?);
    if n <= KEPT_LIMIT {
        KEPT_SOLUTIONS.keep(key, solved.clone());
    }
    Some(solved)
}

/// The lowest `count` modes; `None` when M is not positive definite or the sparse iteration
/// does not settle. Beyond [`DENSE_LIMIT`] unknowns `count` is capped at [`MAX_SPARSE_MODES`].
pub fn modes(beam: &Beam, count: usize) -> Option<Modes> {
    let n = beam.dim();
    // A few modes of a mesh past what is kept are found by subspace iteration: a dense
    // solution would cost n³ for every run that asks (the acceleration filter asks each run).
    let few = n > KEPT_LIMIT && count <= FEW_MODES;
    let (lambda, shapes) = if n <= DENSE_LIMIT && !few {
        let all = dense_all(beam)?;
        let count = count.min(n);
        (
            all.0[..count].to_vec(),
            all.1.columns(0, count).into_owned(),
        )
    } else {
        let k = beam.tangent(&vec![0.0; n]);
        subspace(&k, beam.mass(), count.min(MAX_SPARSE_MODES).min(n))?
    };
    let omega = lambda.iter().map(|l| l.max(0.0).sqrt()).collect();
    Some(Modes { omega, shapes })
}

/// The lowest `count` eigenpairs of K φ = λ M φ, dense, φ mass-normalised. Where the supports
/// hold every rigid motion (K positive definite) the problem is solved inverted: with
/// K = L Lᵀ, B = L⁻¹ M L⁻ᵀ is symmetric with eigenvalues μ = 1/λ, so the lowest modes are its
/// largest, which a dense symmetric solver resolves to round-off of themselves. Solved directly
/// (C = L_M⁻¹ K L_M⁻ᵀ) they are resolved only to round-off of the highest mode, 10⁸–10¹⁰ times
/// larger on a beam: measured against the inverted form, nalgebra's direct solution is off by
/// up to 2.5·10⁻⁸ (D44's second mode with G × 10⁴) and faer's by 8·10⁻⁶ (B1's tenth), where the
/// inverted forms of the two agree to 10⁻¹⁰ on every study's beam. faer solves the inverted
/// form, three to eight times faster than nalgebra on these meshes; a mechanism is solved
/// directly ([`direct`]).
///
/// The unknowns that K and M couple are solved apart (a straight beam's axial unknowns are
/// coupled to its bending ones only through the deformation, so about its undeformed state
/// they form their own block): the dense work falls from n³ to the sum of the blocks' cubes.
/// Each block's modes are modes of the whole.
fn generalized<A: Entries>(k: &A, m: &A, count: usize) -> Option<(Vec<f64>, DMatrix<f64>)> {
    let blocks = coupled_blocks(k, m);
    let n = k.dim();
    let mut at = vec![usize::MAX; n];
    let mut solved = Vec::with_capacity(blocks.len());
    for rows in &blocks {
        for (p, &r) in rows.iter().enumerate() {
            at[r] = p;
        }
        let wanted = if blocks.len() == 1 { count } else { rows.len() };
        solved.push(one_block(block(k, rows, &at), block(m, rows, &at), wanted)?);
        for &r in rows {
            at[r] = usize::MAX;
        }
    }
    if blocks.len() == 1 {
        return solved.pop();
    }
    // Every block's modes, (λ, block, column), merged in ascending λ.
    let mut order: Vec<(f64, usize, usize)> = solved
        .iter()
        .enumerate()
        .flat_map(|(b, (lambda, _))| lambda.iter().enumerate().map(move |(c, &l)| (l, b, c)))
        .collect();
    order.sort_by(|x, y| x.0.total_cmp(&y.0));
    order.truncate(count.min(n));
    let mut shapes = DMatrix::zeros(n, order.len());
    for (j, &(_, b, c)) in order.iter().enumerate() {
        for (i, &r) in blocks[b].iter().enumerate() {
            shapes[(r, j)] = solved[b].1[(i, c)];
        }
    }
    Some((order.iter().map(|o| o.0).collect(), shapes))
}

/// Every mode of K φ = λ M φ (a beam's K₀ and M) as a truncation estimate reads it: the eigenvalues λ ascending
/// and, per mode, the projections vᵀφ of `vectors` on its mass-normalised shape, without the
/// shapes. In the inverted form (K = L Lᵀ, B = L⁻¹ M L⁻ᵀ = Q T Qᵀ, T tridiagonal, φ = L⁻ᵀ Q z
/// / √μ) the projections are (Qᵀ L⁻¹ v)ᵀ z / √μ, so T's rotations are applied to the few rows
/// (Qᵀ L⁻¹ v)ᵀ instead of accumulated into n eigenvectors, which D44's mesh choice spent
/// most of its time on. `None` where K or B is not positive definite (a mechanism: see [`modes`]) or
/// the tridiagonal iteration does not settle.
pub fn projected(
    k: &Sparse,
    m: &Sparse,
    vectors: &[Vec<f64>],
) -> Option<(Vec<f64>, Vec<Vec<f64>>)> {
    let n = k.nrows();
    let mut solved: Vec<(f64, Vec<f64>)> = Vec::with_capacity(n);
    let mut at = vec![usize::MAX; n];
    for rows in coupled_blocks(k, m) {
        for (p, &r) in rows.iter().enumerate() {
            at[r] = p;
        }
        let on_block: Vec<Vec<f64>> = vectors
            .iter()
            .map(|v| rows.iter().map(|&r| v[r]).collect())
            .collect();
        let (mu, projections) =
            projected_block(&block(k, &rows, &at), block(m, &rows, &at), on_block)?;
        for (j, mu) in mu.into_iter().enumerate() {
            if !(mu > 0.0) {
                return None;
            }
            let scale = 1.0 / mu.sqrt();
            solved.push((1.0 / mu, projections.iter().map(|p| p[j] * scale).collect()));
        }
        for &r in &rows {
            at[r] = usize::MAX;
        }
    }
    solved.sort_by(|a, b| a.0.total_cmp(&b.0));
    let lambda = solved.iter().map(|m| m.0).collect();
    let projections = (0..vectors.len())
        .map(|p| solved.iter().map(|m| m.1[p]).collect())
        .collect();
    Some((lambda, projections))
}

/// One block of [`projected`]: B's eigenvalues μ and, per vector v, (L⁻¹ v)ᵀ y for each of
/// B's orthonormal eigenvectors y.
fn projected_block(
    k: &faer::Mat<f64>,
    m: faer::Mat<f64>,
    vectors: Vec<Vec<f64>>,
) -> Option<(Vec<f64>, Vec<Vec<f64>>)> {
    use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
    use faer::linalg::evd::tridiag::{tridiag_in_place, tridiag_in_place_scratch};
    use faer::linalg::householder::{
        apply_block_householder_sequence_transpose_on_the_left_in_place_scratch,
        apply_block_householder_sequence_transpose_on_the_left_in_place_with_conj,
    };
    use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
    use faer::{Conj, Mat, Par};
    let n = k.nrows();
    let (llt, mut b) = inverted_form(k, m).ok()?;
    let p = vectors.len();
    let mut v = Mat::from_fn(n, p, |i, j| vectors[j][i]);
    solve_lower_triangular_in_place(llt.L(), v.as_mut(), Par::Seq);
    let (mut diagonal, mut sub) = (vec![b[(0, 0)]; n], vec![0.0; n]);
    if n > 1 {
        let bs = faer::linalg::qr::no_pivoting::factor::recommended_block_size::<f64>(n, n);
        let mut householder = Mat::zeros(bs, n - 1);
        let mut memory = MemBuffer::new(StackReq::any_of(&[
            tridiag_in_place_scratch::<f64>(n, Par::Seq, Default::default()),
            apply_block_householder_sequence_transpose_on_the_left_in_place_scratch::<f64>(
                n - 1,
                bs,
                p,
            ),
        ]));
        let stack = MemStack::new(&mut memory);
        tridiag_in_place(
            b.as_mut(),
            householder.as_mut(),
            Par::Seq,
            stack,
            Default::default(),
        );
        apply_block_householder_sequence_transpose_on_the_left_in_place_with_conj(
            b.submatrix(1, 0, n - 1, n - 1),
            householder.as_ref(),
            Conj::No,
            v.as_mut().subrows_mut(1, n - 1),
            Par::Seq,
            stack,
        );
        for i in 0..n {
            diagonal[i] = b[(i, i)];
            if i + 1 < n {
                sub[i] = b[(i + 1, i)];
            }
        }
    }
    // T scaled to entries of at most 1 for the rotations (see [`tridiagonal_ql`]).
    let size = diagonal
        .iter()
        .chain(&sub)
        .fold(0.0_f64, |m, d| m.max(d.abs()));
    if !(size > 0.0 && size.is_finite()) {
        return None;
    }
    for x in diagonal.iter_mut().chain(sub.iter_mut()) {
        *x /= size;
    }
    let mut rows: Vec<Vec<f64>> = (0..p).map(|j| v.col(j).iter().copied().collect()).collect();
    tridiagonal_ql(&mut diagonal, &mut sub, &mut rows)?;
    for d in &mut diagonal {
        *d *= size;
    }
    Some((diagonal, rows))
}

/// Most QL iterations one eigenvalue of a tridiagonal matrix may take; two or three is usual.
const QL_ITERATIONS: usize = 60;

/// The eigenvalues of the symmetric tridiagonal matrix with diagonal `d` and subdiagonal `e`
/// (e[i] = T[i+1][i], the last entry unused), left in `d` unordered, by the implicit QL method
/// with Wilkinson's shift. Each plane rotation the method applies to T's eigenvector basis is
/// applied to the entries of every row of `rows` instead: a row entering as wᵀ leaves as the
/// projections of w on T's eigenvectors, in the order of `d`. `None` if an eigenvalue does
/// not settle in [`QL_ITERATIONS`].
fn tridiagonal_ql(d: &mut [f64], e: &mut [f64], rows: &mut [Vec<f64>]) -> Option<()> {
    let n = d.len();
    e[n - 1] = 0.0;
    for l in 0..n {
        let mut iterations = 0;
        loop {
            // The first negligible subdiagonal entry at or after l splits T there.
            let mut m = l;
            while m + 1 < n && e[m].abs() > f64::EPSILON * (d[m].abs() + d[m + 1].abs()) {
                m += 1;
            }
            if m == l {
                break;
            }
            iterations += 1;
            if iterations > QL_ITERATIONS {
                return None;
            }
            // Wilkinson's shift: the eigenvalue of T's leading 2 × 2 block nearer d[l].
            let g = (d[l + 1] - d[l]) / (2.0 * e[l]);
            let r = g.hypot(1.0);
            let mut g = d[m] - d[l] + e[l] / (g + r.copysign(g));
            let (mut s, mut c, mut p) = (1.0, 1.0, 0.0);
            let mut deflated = false;
            // Chase the bulge from m up to l.
            for i in (l..m).rev() {
                let f = s * e[i];
                let b = c * e[i];
                // Not `hypot`, whose care for overflow cost a fifth of the estimate: T's
                // entries are scaled to at most 1 ([`projected_block`]), so f² + g² neither
                // overflows nor underflows where it matters.
                let r = (f * f + g * g).sqrt();
                e[i + 1] = r;
                if r == 0.0 {
                    // An exact zero split T: restart on the shorter block.
                    d[i + 1] -= p;
                    e[m] = 0.0;
                    deflated = true;
                    break;
                }
                s = f / r;
                c = g / r;
                g = d[i + 1] - p;
                let r = (d[i] - g) * s + 2.0 * c * b;
                p = s * r;
                d[i + 1] = g + p;
                g = c * r - b;
                for row in rows.iter_mut() {
                    let (a, b) = (row[i], row[i + 1]);
                    row[i + 1] = s * a + c * b;
                    row[i] = c * a - s * b;
                }
            }
            if !deflated {
                d[l] -= p;
                e[l] = g;
                e[m] = 0.0;
            }
        }
    }
    Some(())
}

/// The unknowns in the groups that K and M couple (an entry that is exactly zero couples
/// nothing), each group ascending, the groups in the order of their first unknown.
fn coupled_blocks(k: &impl Entries, m: &impl Entries) -> Vec<Vec<usize>> {
    fn root_of(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    let n = k.dim();
    let mut root: Vec<usize> = (0..n).collect();
    let mut join = |i: usize, j: usize, v: f64| {
        if v != 0.0 && i != j {
            let (a, b) = (root_of(&mut root, i), root_of(&mut root, j));
            root[a.max(b)] = a.min(b);
        }
    };
    k.for_each_entry(&mut join);
    m.for_each_entry(&mut join);
    let mut blocks: Vec<Vec<usize>> = Vec::new();
    let mut block_of = vec![usize::MAX; n];
    for i in 0..n {
        let r = root_of(&mut root, i);
        if block_of[r] == usize::MAX {
            block_of[r] = blocks.len();
            blocks.push(Vec::new());
        }
        blocks[block_of[r]].push(i);
    }
    blocks
}

/// [`generalized`] for one coupled block.
fn one_block(
    k: faer::Mat<f64>,
    m: faer::Mat<f64>,
    count: usize,
) -> Option<(Vec<f64>, DMatrix<f64>)> {
    match inverted_form(&k, m) {
        Ok((llt, b)) => inverted(&llt, b, count),
        Err(m) => direct(&k, &m, count),
    }
}

/// K = L Lᵀ and B = L⁻¹ M L⁻ᵀ, formed in M's place; M handed back where K is not positive
/// definite (a mechanism).
fn inverted_form(
    k: &faer::Mat<f64>,
    mut b: faer::Mat<f64>,
) -> Result<(faer::linalg::solvers::Llt<f64>, faer::Mat<f64>), faer::Mat<f64>> {
    use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
    use faer::{Par, Side};
    let n = k.nrows();
    let Ok(llt) = k.llt(Side::Lower) else {
        return Err(b);
    };
    let l = llt.L();
    // A mechanism can pass the factorisation in floating point, with a pivot at round-off of
    // its diagonal entry.
    if (0..n).any(|i| !(l[(i, i)] * l[(i, i)] > 1e-10 * k[(i, i)].abs())) {
        return Err(b);
    }
    // L⁻¹ M, transposed in place, L⁻¹ again, then symmetrised in place.
    solve_lower_triangular_in_place(l, b.as_mut(), Par::Seq);
    for j in 0..n {
        for i in 0..j {
            let (x, y) = (b[(i, j)], b[(j, i)]);
            b[(i, j)] = y;
            b[(j, i)] = x;
        }
    }
    solve_lower_triangular_in_place(l, b.as_mut(), Par::Seq);
    for j in 0..n {
        for i in 0..j {
            let mean = 0.5 * (b[(i, j)] + b[(j, i)]);
            b[(i, j)] = mean;
            b[(j, i)] = mean;
        }
    }
    Ok((llt, b))
}

/// [`generalized`] from K = L Lᵀ and B = L⁻¹ M L⁻ᵀ ([`inverted_form`]); `None` where B is
/// not positive definite.
fn inverted(
    llt: &faer::linalg::solvers::Llt<f64>,
    b: faer::Mat<f64>,
    count: usize,
) -> Option<(Vec<f64>, DMatrix<f64>)> {
    use faer::linalg::triangular_solve::solve_upper_triangular_in_place;
    use faer::{Mat, Par, Side};
    let n = b.nrows();
    let l = llt.L();
    // B scaled to a largest entry between 1 and 2 (B is positive definite: its largest entry
    // is on the diagonal), by a power of two, which leaves every digit as it was. faer's
    // symmetric solver resolves small eigenvalues only to about 10⁻¹⁶ in absolute terms:
    // unscaled, a 1 m beam of density 1 kg/m³ on 33 elements, whose μ run from 10⁻⁹ down to
    // 10⁻¹⁷, had its highest mode come out negative, and so had D44's beam at 10⁻⁸ of its
    // density (a density in tonnes per cubic millimetre is of that order).
    let largest = (0..n).fold(0.0_f64, |m, i| m.max(b[(i, i)].abs()));
    if !(largest > 0.0 && largest.is_finite()) {
        return None;
    }
    let size = 2.0_f64.powi(largest.log2().floor() as i32);
    let eig = Mat::from_fn(n, n, |i, j| b[(i, j)] / size)
        .self_adjoint_eigen(Side::Lower)
        .ok()?;
    let (mu, y) = (eig.S(), eig.U());
    let count = count.min(n);
    let mut lambda = Vec::with_capacity(count);
    let mut shapes = Mat::zeros(n, count);
    for c in 0..count {
        // Ascending μ: the lowest modes are at the end.
        let i = n - 1 - c;
        let mu = mu[i] * size;
        if !(mu > 0.0) {
            return None;
        }
        lambda.push(1.0 / mu);
        let scale = 1.0 / mu.sqrt();
        for r in 0..n {
            shapes[(r, c)] = y[(r, i)] * scale;
        }
    }
    solve_upper_triangular_in_place(l.transpose(), shapes.as_mut(), Par::Seq);
    let mut out = DMatrix::from_fn(n, count, |i, j| shapes[(i, j)]);
    for mut column in out.column_iter_mut() {
        // A sign for every shape: its largest component positive.
        let largest = column
            .iter()
            .copied()
            .fold(0.0_f64, |a, v| if v.abs() > a.abs() { v } else { a });
        if largest < 0.0 {
            column.neg_mut();
        }
    }
    Some((lambda, out))
}

/// [`generalized`] directly: with M = L Lᵀ, C = L⁻¹ K L⁻ᵀ is symmetric, found by two
/// triangular solves, and φ = L⁻ᵀ y.
fn direct(
    k: &faer::Mat<f64>,
    m: &faer::Mat<f64>,
    count: usize,
) -> Option<(Vec<f64>, DMatrix<f64>)> {
    let n = k.nrows();
    let l = DMatrix::from_fn(n, n, |i, j| m[(i, j)]).cholesky()?.l();
    let mut c = DMatrix::from_fn(n, n, |i, j| k[(i, j)]);
    if !l.solve_lower_triangular_mut(&mut c) {
        return None;
    }
    let mut c = c.transpose();
    if !l.solve_lower_triangular_mut(&mut c) {
        return None;
    }
    let c = (&c + c.transpose()) * 0.5;
    let eig = SymmetricEigen::new(c);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let lambda = order[..count].iter().map(|&i| eig.eigenvalues[i]).collect();
    let mut shapes = DMatrix::zeros(n, count);
    for (c, &i) in order[..count].iter().enumerate() {
        shapes.set_column(c, &eig.eigenvectors.column(i));
    }
    if !l.tr_solve_lower_triangular_mut(&mut shapes) {
        return None;
    }
    Some((lambda, shapes))
}

/// Subspace iteration for the lowest `count` eigenpairs of K φ = λ M φ. K is shifted by a
/// round-off-sized σ M so that a beam with rigid-body motions (K singular) factorises too.
fn subspace(k: &Sparse, m: &Sparse, count: usize) -> Option<(Vec<f64>, DMatrix<f64>)> {
    let n = k.nrows();
    let q = (2 * count).min(count + 8).min(n);
    let diagonal = |a: &Sparse| -> f64 {
        linalg::entries(a)
            .filter(|(j, (i, _))| i == j)
            .map(|(_, (_, v))| v.abs())
            .sum()
    };
    let sigma = 1e-12 * diagonal(k) / diagonal(m);
    let shifted = Combination::new(k, m).at(sigma).clone();
    let lu = SparseLu::factor(&shifted, None)?;
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut x = DMatrix::from_fn(n, q, |_, _| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    });
    let product = |a: &Sparse, x: &DMatrix<f64>| {
        let mut y = DMatrix::zeros(n, x.ncols());
        for j in 0..x.ncols() {
            linalg::mul(a, x.column(j).as_slice(), y.column_mut(j).as_mut_slice());
        }
        y
    };
    let mut previous: Option<Vec<f64>> = None;
    for _ in 0..MAX_ITERATIONS {
        let mut y = product(m, &x);
        for j in 0..q {
            lu.solve_in_place(y.column_mut(j).as_mut_slice());
        }
        // Orthonormal, or the shift's 1/σ gain along a rigid-body motion turns every column
        // towards it and the block's mass Yᵀ M Y is singular from the first pass.
        let y = y.qr().q();
        let kr = y.transpose() * product(&shifted, &y);
        let mr = y.transpose() * product(m, &y);
        let (mu, phi) = generalized(
            &((&kr + kr.transpose()) * 0.5),
            &((&mr + mr.transpose()) * 0.5),
            q,
        )?;
        x = y * phi;
        let rigid = |mu: f64| (mu - sigma).abs() <= RIGID * sigma;
        let settled = previous.as_ref().is_some_and(|p: &Vec<f64>| {
            mu.iter()
                .zip(p)
                .take(count)
                .all(|(&a, &b)| (a - b).abs() <= SETTLED * a.abs() || (rigid(a) && rigid(b)))
        });
        if settled {
            let lambda = mu.iter().take(count).map(|mu| mu - sigma).collect();
            return Some((lambda, x.columns(0, count).into_owned()));
        }
        previous = Some(mu);
    }
    None
}

#[cfg(test)]
mod tests;

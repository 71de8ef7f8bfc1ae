//! The eigensolutions checked: the paths against one another, and against what scaling,
//! supports and blocks must give.

use super::*;

/// D44's beam (HEB 360, 20 m, pinned and roller) on `elements` elements of degree 4.
fn d44_beam(elements: usize) -> Beam {
    use crate::beam::element::Section;
    use crate::beam::supports::Support;
    use crate::beam::{BeamSpec, Quadrature};
    Beam::new(BeamSpec {
        from: [0.0, 0.0],
        to: [20.0, 0.0],
        section: Section {
            ea: 210e9 * 181e-4,
            gav: 81e9 * 46.8e-4,
            ei: 210e9 * 43190e-8,
            rho_a: 7850.0 * 181e-4,
            rho_i: 7850.0 * 43190e-8,
        },
        depth: 0.36,
        supports: [Support::Pinned, Support::Roller],
        bearings: Vec::new(),
        elements,
        order: 4,
        quadrature: Quadrature::Reduced,
        model: crate::beam::BeamModel::Exact,
        damping: None,
        self_weight: None,
    })
}

/// The projections without shapes against the shapes themselves, on D44's 16-element
/// mesh (its axial and bending blocks): every eigenvalue, compared as μ = 1/λ to 10⁻¹²
/// of the largest (both solve the same B, to its round-off), and every mode's share
/// (vᵀφ)(fᵀφ)/λ of the static response v·K⁻¹f (free of the shapes' signs; what a
/// truncation estimate reads) to 10⁻¹⁰ of the largest share. Shares, not projections:
/// the highest modes' shapes are resolved only to round-off of B's largest eigenvalue,
/// 10⁸ times theirs, but their shares are as small.
#[test]
fn projections_without_shapes_match_the_shapes() {
    let beam = d44_beam(16);
    let n = beam.dim();
    let mut f = vec![0.0; n];
    beam.add_point_load(7.3, [0.2, -1.0], 0.1, &mut f);
    let mut w_mid = vec![0.0; n];
    beam.add_point_load(10.0, [0.0, 1.0], 0.0, &mut w_mid);
    let mut u_quarter = vec![0.0; n];
    beam.add_point_load(5.0, [1.0, 0.0], 0.0, &mut u_quarter);
    let k = beam.tangent(&vec![0.0; n]);
    let (lambda, p) = projected(
        &k,
        beam.mass(),
        &[f.clone(), w_mid.clone(), u_quarter.clone()],
    )
    .expect("a supported beam");
    let full = modes(&beam, n).unwrap();
    assert_eq!(lambda.len(), n);
    let dot = |a: &[f64], j: usize| -> f64 {
        a.iter()
            .zip(full.shapes.column(j).iter())
            .map(|(x, y)| x * y)
            .sum()
    };
    let mu_max = 1.0 / lambda[0];
    for (j, (l, w)) in lambda.iter().zip(&full.omega).enumerate() {
        assert!(
            (1.0 / l - 1.0 / (w * w)).abs() <= 1e-12 * mu_max,
            "mode {}: λ {l} against {}",
            j + 1,
            w * w
        );
    }
    for (v, row) in [(&w_mid, &p[1]), (&u_quarter, &p[2])] {
        let shares: Vec<(f64, f64)> = (0..n)
            .map(|j| {
                let w2 = full.omega[j] * full.omega[j];
                (row[j] * p[0][j] / lambda[j], dot(v, j) * dot(&f, j) / w2)
            })
            .collect();
        let largest = shares.iter().fold(0.0_f64, |m, x| m.max(x.1.abs()));
        for (j, (got, want)) in shares.iter().enumerate() {
            assert!(
                (got - want).abs() <= 1e-10 * largest,
                "mode {}: {got} against {want}",
                j + 1
            );
        }
    }
}

/// The sparse path against the dense one on the same matrices: a mesh small enough to
/// solve both ways, its lowest eigenvalues to 1e-8 (what the iteration settles to) and
/// its shapes up to sign.
#[test]
fn subspace_iteration_finds_the_dense_modes() {
    let beam = d44_beam(40);
    let n = beam.dim();
    let k = beam.tangent(&vec![0.0; n]);
    let (dense_l, dense_x) = generalized(&k, beam.mass(), 6).unwrap();
    let (sparse_l, sparse_x) = subspace(&k, beam.mass(), 6).unwrap();
    for j in 0..6 {
        assert!(
            (dense_l[j] - sparse_l[j]).abs() <= 1e-8 * dense_l[j],
            "mode {}: {} {}",
            j + 1,
            dense_l[j],
            sparse_l[j]
        );
        let dot: f64 = dense_x.column(j).dot(&sparse_x.column(j));
        let scale = dense_x.column(j).norm() * sparse_x.column(j).norm();
        assert!((dot.abs() / scale - 1.0).abs() < 1e-6, "shape {}", j + 1);
    }
}

/// The rigid-body motions the supports leave, counted from the supports alone, against
/// the null space of the mesh's K₀ (its eigenvalues at round-off of the largest, every
/// other above 10⁻⁷ of it on four elements): the same count on every pair of ends with
/// and without bearings, and the kinds name exactly those modes rigid.
#[test]
fn the_modes_at_zero_are_the_motions_the_supports_leave() {
    use crate::beam::supports::Support::*;
    for (ends, bearings) in [
        ([Pinned, Roller], vec![]),
        ([Pinned, Free], vec![]),
        ([Roller, Free], vec![]),
        ([Roller, Roller], vec![10.0]),
        ([Free, Free], vec![]),
        ([Free, Free], vec![5.0, 15.0]),
        ([Clamped, Free], vec![]),
    ] {
        let mut spec = d44_beam(4).spec.clone();
        spec.supports = ends;
        spec.bearings = bearings.clone();
        let beam = Beam::new(spec);
        let n = beam.dim();
        let all = modes(&beam, n).unwrap();
        let largest = all.omega[n - 1].powi(2);
        let at_zero = all
            .omega
            .iter()
            .filter(|w| w.powi(2) <= 1e-10 * largest)
            .count();
        let case = format!("{ends:?} with bearings at {bearings:?}");
        assert_eq!(at_zero, rigid_motions(ends, bearings.len()), "{case}");
        let kinds = all.kinds(&beam);
        assert!(
            kinds[..at_zero].iter().all(|k| *k == ModeKind::Rigid),
            "{case}"
        );
        assert!(
            kinds[at_zero..].iter().all(|k| *k != ModeKind::Rigid),
            "{case}"
        );
    }
}

/// A beam its supports leave free to turn (pinned–free) through the sparse path against
/// the dense solution of the same mesh: its rigid-body rotation at zero (within the
/// round-off of the shift, 10⁻⁹ of the first bending mode's λ) and its bending modes to
/// 10⁻⁸, what the iteration settles to. Without orthonormal iterates the shift turned
/// every column towards the rotation and no mode came out.
#[test]
fn subspace_iteration_finds_a_free_beam_s_rigid_motion_and_its_modes() {
    use crate::beam::supports::Support;
    let mut spec = d44_beam(40).spec.clone();
    spec.supports = [Support::Pinned, Support::Free];
    let beam = Beam::new(spec);
    let n = beam.dim();
    let k = beam.tangent(&vec![0.0; n]);
    let (dense, _) = generalized(&k, beam.mass(), 6).unwrap();
    let (sparse, _) = subspace(&k, beam.mass(), 6).expect("the free beam's modes");
    assert!(sparse[0].abs() <= 1e-9 * dense[1], "rigid: {}", sparse[0]);
    for j in 1..6 {
        assert!(
            (dense[j] - sparse[j]).abs() <= 1e-8 * dense[j],
            "mode {}: {} {}",
            j + 1,
            dense[j],
            sparse[j]
        );
    }
}

/// K φ = λ M φ with M scaled by s has the eigenvalues λ/s and the shapes φ/√s: D44's beam
/// at 10⁻⁸ of its density (its μ = 1/λ then run from 10⁻¹¹ down to 10⁻²⁰, as a beam given
/// in millimetres and tonnes has them) against itself, every mode of the mesh. The lowest
/// thirty to 10⁻¹⁰; every one to 10⁻⁶, the round-off of the inverted form on the highest
/// (ε μ_max/μ_min). Unscaled, the symmetric solver's absolute round-off of 10⁻¹⁶ turned the
/// highest modes' μ negative and no mode came out.
#[test]
fn the_modes_scale_with_the_density_however_light_the_beam() {
    let beam = d44_beam(40);
    let mut spec = beam.spec.clone();
    let s = 1e-8;
    spec.section.rho_a *= s;
    spec.section.rho_i *= s;
    let light = Beam::new(spec);
    let n = beam.dim();
    let k = beam.tangent(&vec![0.0; n]);
    let (l, _) = generalized(&k, beam.mass(), n).unwrap();
    let (l_light, _) = generalized(&k, light.mass(), n).expect("the light beam's modes");
    for j in 0..n {
        let within = if j < 30 { 1e-10 } else { 1e-6 };
        let scaled = l_light[j] * s;
        assert!(
            (scaled - l[j]).abs() <= within * l[j],
            "mode {}: {} against {}",
            j + 1,
            scaled,
            l[j]
        );
    }
}

/// The blocks solved apart against the whole solved at once: the straight beam splits
/// into its axial and its bending unknowns, and every mode of the whole comes out of one
/// block, its frequency to 1e-10 (round-off of the inverted form on the lowest modes,
/// which both solve) and its shape to 1e-8 up to sign.
#[test]
fn blocks_solved_apart_give_the_modes_of_the_whole() {
    let beam = d44_beam(10);
    let n = beam.dim();
    let (k, m) = (beam.tangent(&vec![0.0; n]), beam.mass());
    let blocks = coupled_blocks(&k, m);
    assert_eq!(blocks.len(), 2, "axial and bending unknowns");
    assert_eq!(blocks[0].len() + blocks[1].len(), n);
    let count = 30;
    let (apart_l, apart_x) = generalized(&k, m, count).unwrap();
    let all: Vec<usize> = (0..n).collect();
    let (whole_k, whole_m) = (block(&k, &all, &all), block(m, &all, &all));
    let m = DMatrix::from_fn(n, n, |i, j| whole_m[(i, j)]);
    let (whole_l, whole_x) = one_block(whole_k, whole_m, count).unwrap();
    for j in 0..count {
        assert!(
            (apart_l[j] - whole_l[j]).abs() <= 1e-10 * whole_l[j],
            "mode {}: {} {}",
            j + 1,
            apart_l[j],
            whole_l[j]
        );
        let dot: f64 = apart_x.column(j).dot(&(&m * whole_x.column(j)));
        assert!((dot.abs() - 1.0).abs() < 1e-8, "shape {}: {dot}", j + 1);
    }
}

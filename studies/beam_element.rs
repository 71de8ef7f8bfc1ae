//! Verification of the Reissner beam element: analytic tangent against finite differences of
//! the internal forces; statics against Timoshenko closed forms; geometric exactness under an
//! end moment; shear locking; natural frequencies against Euler–Bernoulli with their measured
//! rates of convergence, and a continuous beam's against its single spans'.

use rollbeam::analysis::{modes, statics};
use rollbeam::beam::element::Section;
use rollbeam::beam::supports::Support;
use rollbeam::beam::{Beam, BeamModel, BeamSpec, Quadrature};
use rollbeam::linalg;

/// Steel SHS 200 of study 2 (E = 210 GPa, G = 81 GPa, ρ = 7850, A = 59.8 cm², Av = A/2,
/// I = 3620 cm⁴).
fn shs200() -> Section {
    let (e, g, rho, a, i) = (210e9, 81e9, 7850.0, 59.8e-4, 3620e-8);
    Section {
        ea: e * a,
        gav: g * a / 2.0,
        ei: e * i,
        rho_a: rho * a,
        rho_i: rho * i,
    }
}

fn beam(
    length: f64,
    supports: [Support; 2],
    elements: usize,
    order: usize,
    quadrature: Quadrature,
    section: Section,
) -> Beam {
    Beam::new(BeamSpec {
        from: [0.0, 0.0],
        to: [length, 0.0],
        section,
        depth: 0.1,
        supports,
        bearings: Vec::new(),
        elements,
        order,
        quadrature,
        model: BeamModel::Exact,
        damping: None,
        self_weight: None,
    })
}

/// The tangent is the exact derivative of the internal force: central differences at a
/// strongly deformed state agree to 1e-6 of the matrix' largest entry (the difference error
/// is O(δ²) with δ = 1e-6 of the state's size).
#[test]
fn tangent_matches_finite_differences() {
    for (order, quadrature) in [
        (1, Quadrature::Reduced),
        (3, Quadrature::Full),
        (5, Quadrature::Lobatto),
    ] {
        let b = beam(
            3.0,
            [Support::Clamped, Support::Free],
            3,
            order,
            quadrature,
            shs200(),
        );
        let n = b.dim();
        let q: Vec<f64> = (0..n).map(|i| 0.3 * ((i as f64) * 0.7).sin()).collect();
        let k = b.tangent(&q);
        let mut dense = vec![0.0; n * n];
        for (j, (i, v)) in linalg::entries(&k) {
            dense[i * n + j] += v;
        }
        let biggest = dense.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
        for j in 0..n {
            let d = 1e-6;
            let mut qp = q.clone();
            qp[j] += d;
            let mut qm = q.clone();
            qm[j] -= d;
            b.internal_force(&qp, &mut fp);
            b.internal_force(&qm, &mut fm);
            for i in 0..n {
                let fd = (fp[i] - fm[i]) / (2.0 * d);
                assert!(
                    (fd - dense[i * n + j]).abs() <= 1e-6 * biggest,
                    "p = {order}: K[{i},{j}] = {} vs {fd}",
                    dense[i * n + j]
                );
            }
        }
    }
}

/// Timoshenko cantilever, tip load P: w = P L³/(3EI) + P L/(GAv). The load is small (w/L ~ 1e-6)
/// so the geometrically nonlinear answer differs from the linear one by ~1e-12; the element
/// reproduces the polynomial solution exactly, so 1e-6 relative is generous.
#[test]
fn cantilever_tip_deflection_with_shear() {
    let s = shs200();
    let (l, p) = (3.0, -100.0);
    let b = beam(
        l,
        [Support::Clamped, Support::Free],
        4,
        4,
        Quadrature::Reduced,
        s,
    );
    let mut f = vec![0.0; b.dim()];
    b.add_point_load(l, [0.0, p], 0.0, &mut f);
    let sol = statics::solve(&b, &f).expect("converges");
    let w = b.displacement_at(&sol.q, l).w;
    let exact = p * l.powi(3) / (3.0 * s.ei) + p * l / s.gav;
    assert!((w / exact - 1.0).abs() < 1e-6, "tip {w} vs {exact}");
}

/// A linear beam stiff in shear solves statically to Euler–Bernoulli. G Av 10⁵ times the
/// section's is held at `shear_rigid_limit` (G Av L²/(E I) = 1.9·10⁷ here), where the assembled
/// K q still loses part of the shear strain w′ − φ to cancellation and Newton's corrections stop
/// shrinking above the 10⁻⁹ of the solution a converging Newton reaches (at 10⁻⁶ to 10⁻⁹ of it):
/// the first solve is the answer to the solve's round-off, and the solver takes it rather than
/// halving its load steps to a failure ("the structure may buckle or snap"). Simply
/// supported, P at midspan on a node: w = P L³/(48 EI) + P L/(4 G Av), which the element
/// reproduces to round-off; 10⁻⁶ allows the limit's shear and as much round-off (6·10⁻⁷ each).
#[test]
fn a_shear_rigid_linear_beam_solves_statically() {
    let mut s = shs200();
    s.gav *= 1e5;
    let (l, p) = (8.0, -1.0e4);
    let exact_model = beam(
        l,
        [Support::Pinned, Support::Roller],
        8,
        4,
        Quadrature::Reduced,
        s,
    );
    let b = Beam::new(BeamSpec {
        model: BeamModel::Linear,
        ..exact_model.spec.clone()
    });
    let mut f = vec![0.0; b.dim()];
    b.add_point_load(0.5 * l, [0.0, p], 0.0, &mut f);
    let q = statics::solve(&b, &f).expect("converges").q;
    let w = b.displacement_at(&q, 0.5 * l).w;
    let exact = p * l.powi(3) / (48.0 * s.ei) + p * l / (4.0 * s.gav);
    assert!((w / exact - 1.0).abs() < 1e-6, "w {w} vs {exact}");
}

/// Clamped at 0, pinned at L, load P at a: by compatibility of a Timoshenko cantilever, the
/// prop force is R = P[a²(3L − a)/(6EI) + a/GAv] / [L³/(3EI) + L/GAv] and the deflection under
/// the load P a³/(3EI) + P a/GAv − R[a²(3L − a)/(6EI) + a/GAv]. With a mesh node under the
/// load (the study positions 0.75 L and 0.5 L) the piecewise-cubic solution is reproduced to
/// round-off. Inside an element the Dirac load leaves a kink the polynomial cannot follow: the
/// shear strain jumps by P/GAv there, so the error under the load is bounded by h·|P|/GAv and
/// falls as the mesh is refined.
#[test]
fn clamped_pinned_deflection_under_the_load() {
    let s = shs200();
    let (l, p) = (8.0, -100.0);
    let exact = |a: f64| {
        let r = p * (a * a * (3.0 * l - a) / (6.0 * s.ei) + a / s.gav)
            / (l.powi(3) / (3.0 * s.ei) + l / s.gav);
        p * a.powi(3) / (3.0 * s.ei) + p * a / s.gav
            - r * (a * a * (3.0 * l - a) / (6.0 * s.ei) + a / s.gav)
    };
    let relative_error = |a: f64, elements: usize| {
        let b = beam(
            l,
            [Support::Clamped, Support::Pinned],
            elements,
            4,
            Quadrature::Reduced,
            s,
        );
        let mut f = vec![0.0; b.dim()];
        b.add_point_load(a, [0.0, p], 0.0, &mut f);
        (b.displacement_at(&statics::solve(&b, &f).expect("converges").q, a)
            .w
            / exact(a)
            - 1.0)
            .abs()
    };
    for a in [0.75 * l, 0.5 * l] {
        let e = relative_error(a, 8);
        assert!(e < 1e-6, "a = {a}: relative error {e:.2e}");
        // The pinned end carries the prop force R of the closed form (upwards on the beam:
        // −R), and the clamp the rest of the load.
        let b = beam(
            l,
            [Support::Clamped, Support::Pinned],
            8,
            4,
            Quadrature::Reduced,
            s,
        );
        let mut f = vec![0.0; b.dim()];
        b.add_point_load(a, [0.0, p], 0.0, &mut f);
        let q = statics::solve(&b, &f).expect("converges").q;
        let [clamp, pin] = b.support_reactions(&q, &[(a, [0.0, p], 0.0)], None);
        let prop = p * (a * a * (3.0 * l - a) / (6.0 * s.ei) + a / s.gav)
            / (l.powi(3) / (3.0 * s.ei) + l / s.gav);
        assert!(
            (pin[1] + prop).abs() < 1e-6 * p.abs(),
            "prop {} vs {}",
            pin[1],
            -prop
        );
        assert!((clamp[1] + pin[1] + p).abs() < 1e-9 * p.abs() && pin[2] == 0.0);
    }
    let a = 0.3 * l + 0.01;
    let meshes = [10, 20, 40, 80];
    let e: Vec<f64> = meshes.iter().map(|&n| relative_error(a, n)).collect();
    eprintln!("load inside elements: relative errors {e:?}");
    for (&n, err) in meshes.iter().zip(&e) {
        let kink_bound = l / n as f64 * (p / s.gav).abs() / exact(a).abs();
        assert!(
            *err < kink_bound,
            "{n} elements: {err:.2e} above {kink_bound:.2e}"
        );
    }
    assert!(e[3] < e[0], "errors {e:?}");
}

/// A continuous beam over two equal spans L (pinned, an intermediate bearing, a roller) with
/// a load P at each midspan. By symmetry the section over the bearing does not turn, so each
/// span is the clamped–pinned beam above: the bearing carries twice its clamp's share, the ends
/// its prop force, and the deflection under each load is the closed form's. With nodes under
/// the loads and at the bearing the cubic solution is reproduced to round-off (1e-6 allows
/// for the load steps' Newton tolerance); the small-load case keeps the nonlinearity at 1e-9.
#[test]
fn continuous_beam_over_an_intermediate_bearing() {
    let s = shs200();
    let (l, p) = (8.0, -100.0);
    let b = Beam::new(BeamSpec {
        from: [0.0, 0.0],
        to: [2.0 * l, 0.0],
        section: s,
        depth: 0.2,
        supports: [Support::Pinned, Support::Roller],
        bearings: vec![l],
        elements: 8,
        order: 4,
        quadrature: Quadrature::Reduced,
        model: BeamModel::Exact,
        damping: None,
        self_weight: None,
    });
    let loads = [(0.5 * l, [0.0, p], 0.0), (1.5 * l, [0.0, p], 0.0)];
    let mut f = vec![0.0; b.dim()];
    for (x, force, mz) in loads {
        b.add_point_load(x, force, mz, &mut f);
    }
    let q = statics::solve(&b, &f).expect("converges").q;
    let a = 0.5 * l;
    let flexibility = a * a * (3.0 * l - a) / (6.0 * s.ei) + a / s.gav;
    let prop = p * flexibility / (l.powi(3) / (3.0 * s.ei) + l / s.gav);
    let under = p * a.powi(3) / (3.0 * s.ei) + p * a / s.gav - prop * flexibility;
    let [from, to] = b.support_reactions(&q, &loads, None);
    let bearing = b.bearing_reactions(&q, &loads, None);
    for (x, w) in [(0.5 * l, under), (1.5 * l, under), (l, 0.0)] {
        let got = b.displacement_at(&q, x).w;
        assert!(
            (got - w).abs() < 1e-6 * under.abs(),
            "w({x}) = {got} vs {w}"
        );
    }
    for end in [from, to] {
        assert!(
            (end[1] + prop).abs() < 1e-6 * p.abs(),
            "end {} vs {}",
            end[1],
            -prop
        );
    }
    let middle = -2.0 * (p - prop);
    assert!(
        (bearing[0][1] - middle).abs() < 1e-6 * p.abs(),
        "bearing {} vs {middle}",
        bearing[0][1]
    );
}

/// Geometric exactness: an end moment M = t·EI/L bends the cantilever into an arc,
/// u = L(sin t/t − 1), w = (L/t)(1 − cos t); at t = 2π the tip returns to the root. Pure
/// bending has no axial or shear strain, so this is exact for the Reissner beam; the
/// discretisation error of the trigonometric displacements is below 1e-6 L on this mesh.
#[test]
fn end_moment_rolls_a_cantilever_into_a_circle() {
    let s = shs200();
    let l = 3.0;
    for t in [1.0, std::f64::consts::PI, 2.0 * std::f64::consts::PI] {
        let b = beam(
            l,
            [Support::Clamped, Support::Free],
            8,
            8,
            Quadrature::Reduced,
            s,
        );
        let mut f = vec![0.0; b.dim()];
        b.add_point_load(l, [0.0, 0.0], t * s.ei / l, &mut f);
        let sol = statics::solve(&b, &f).expect("load stepping reaches the full moment");
        let tip = b.displacement_at(&sol.q, l);
        let (u, w) = (l * (t.sin() / t - 1.0), l / t * (1.0 - t.cos()));
        assert!(
            (tip.u - u).abs() < 1e-6 * l && (tip.w - w).abs() < 1e-6 * l,
            "t = {t}: ({}, {}) vs ({u}, {w})",
            tip.u,
            tip.w
        );
        assert!((tip.phi - t).abs() < 1e-9);
    }
}

/// Shear locking: a thin cantilever (L/h = 1000, square section) with linear elements and full
/// integration is far too stiff (its deflection a small fraction of the true one), while the
/// default reduced integration is within 1 % with the same mesh.
#[test]
fn shear_locking_full_linear_locks_reduced_does_not() {
    let (l, h): (f64, f64) = (10.0, 0.01);
    let (e, g) = (210e9, 81e9);
    let (a, i) = (h * h, h.powi(4) / 12.0);
    let s = Section {
        ea: e * a,
        gav: g * a * 5.0 / 6.0,
        ei: e * i,
        rho_a: 1.0,
        rho_i: 1.0,
    };
    let p = -1e-6;
    let exact = p * l.powi(3) / (3.0 * s.ei) + p * l / s.gav;
    let tip = |q: Quadrature| {
        let b = beam(l, [Support::Clamped, Support::Free], 20, 1, q, s);
        let mut f = vec![0.0; b.dim()];
        b.add_point_load(l, [0.0, p], 0.0, &mut f);
        b.displacement_at(&statics::solve(&b, &f).expect("converges").q, l)
            .w
            / exact
    };
    let (locked, free) = (tip(Quadrature::Full), tip(Quadrature::Reduced));
    assert!(
        locked < 0.01,
        "full integration gives {locked} of the true deflection"
    );
    assert!(
        (free - 1.0).abs() < 0.01,
        "reduced integration gives {free}"
    );
}

/// How a single span's spec is laid out into the beam tested.
type Layout = Box<dyn Fn(BeamSpec) -> BeamSpec>;

/// Lowest bending frequencies against Euler–Bernoulli, ω = (βL)² √(EI/(ρA L⁴)). Shear and
/// rotary inertia lower them by about ½ (βL)² (r/L)² (1 + E A/(G Av)), r² = I/A (first-order
/// Timoshenko correction); the test allows that full amount, and checks that the difference
/// has the right sign. Two equal spans L over an intermediate bearing (pinned, bearing, roller)
/// vibrate in each span's own modes: antisymmetric, the bearing a node of a simply supported
/// span (βL = nπ), or symmetric, the section over it held from turning, a clamped–pinned span
/// (βL = 3.9266, 7.0686, 10.2102), interleaved.
#[test]
fn frequencies_against_euler_bernoulli() {
    let s = shs200();
    let l = 8.0;
    let pi = std::f64::consts::PI;
    let two_spans = move |mut b: BeamSpec| {
        b.to = [2.0 * l, 0.0];
        b.bearings = vec![l];
        b.elements *= 2;
        b
    };
    let cases: [(_, Layout, Vec<f64>); 3] = [
        (
            [Support::Clamped, Support::Pinned],
            Box::new(|b| b),
            vec![3.9266, 7.0686, 10.2102],
        ),
        (
            [Support::Clamped, Support::Free],
            Box::new(|b| b),
            vec![1.8751, 4.6941, 7.8548],
        ),
        (
            [Support::Pinned, Support::Roller],
            Box::new(two_spans),
            vec![pi, 3.9266, 2.0 * pi, 7.0686, 3.0 * pi, 10.2102],
        ),
    ];
    let r2 = s.ei / s.ea;
    for (supports, layout, beta) in cases {
        let b = Beam::new(layout(
            beam(l, supports, 16, 4, Quadrature::Reduced, s)
                .spec
                .clone(),
        ));
        let m = modes::modes(&b, 12).expect("modes");
        let bending: Vec<f64> = (m.bending_omega(&b).into_iter())
            .filter(|w| *w > 1e-3)
            .collect();
        for (k, bl) in beta.iter().enumerate() {
            let eb = bl * bl * (s.ei / (s.rho_a * l.powi(4))).sqrt();
            let bound = bl * bl * r2 / (l * l) * (1.0 + s.ea / s.gav);
            let rel = bending[k] / eb - 1.0;
            assert!(
                rel < 1e-4 && rel > -bound,
                "{:?} mode {k}: {rel:.3e} (bound {bound:.3e})",
                supports
            );
        }
    }
}

/// The same two equal spans on the same mesh per span, exactly: each antisymmetric mode is the
/// simply supported span's on that mesh, each symmetric one the clamped–pinned span's (the
/// bearing's section held from turning by symmetry), so the lowest six bending frequencies
/// of the two spans are those of the two single spans, merged, to the eigensolver's
/// round-off (1e-9 allows it).
#[test]
fn two_equal_spans_vibrate_in_their_single_spans_modes() {
    let s = shs200();
    let l = 8.0;
    let bending = |spec: BeamSpec, count: usize| {
        let b = Beam::new(spec);
        modes::modes(&b, 2 * count)
            .expect("modes")
            .bending_omega(&b)
            .into_iter()
            .take(count)
            .collect::<Vec<f64>>()
    };
    let span = |supports| {
        beam(l, supports, 16, 4, Quadrature::Reduced, s)
            .spec
            .clone()
    };
    let mut singles = bending(span([Support::Pinned, Support::Pinned]), 3);
    singles.extend(bending(span([Support::Clamped, Support::Pinned]), 3));
    singles.sort_by(f64::total_cmp);
    let mut two = span([Support::Pinned, Support::Roller]);
    two.to = [2.0 * l, 0.0];
    two.bearings = vec![l];
    two.elements *= 2;
    for (k, (a, b)) in bending(two, 6).iter().zip(&singles).enumerate() {
        assert!(
            (a / b - 1.0).abs() < 1e-9,
            "mode {k}: two spans {a}, the single spans {b}"
        );
    }
}

/// Convergence of the first frequency of the clamped–pinned beam (steel SHS 200, L = 8 m,
/// default reduced integration) against a p = 10 reference: under h-refinement the error falls
/// as h^{2p}; under p-refinement on two elements, faster than any power: each degree gains a
/// factor larger than the one before it, until round-off.
#[test]
fn frequency_error_rates() {
    let s = shs200();
    let l: f64 = 8.0;
    let omega1 = |elements: usize, order: usize| {
        let b = beam(
            l,
            [Support::Clamped, Support::Pinned],
            elements,
            order,
            Quadrature::Reduced,
            s,
        );
        modes::modes(&b, 1).expect("modes").omega[0]
    };
    let exact = omega1(8, 10);
    for p in [1usize, 2, 3] {
        let e: Vec<f64> = [4, 8, 16]
            .iter()
            .map(|&n| (omega1(n, p) / exact - 1.0).abs())
            .collect();
        let rate = (e[1] / e[2]).log2();
        eprintln!("p = {p}: errors {e:?}, rate {rate:.3}");
        assert!(
            (rate - 2.0 * p as f64).abs() < 0.3,
            "p = {p}: errors {e:?}, rate {rate}"
        );
    }
    // Algebraic convergence e ~ p^-k would let the gain per degree tend to 1; here every
    // degree gains more than a factor 10.
    let e: Vec<f64> = (1..=6)
        .map(|p| (omega1(2, p) / exact - 1.0).abs())
        .collect();
    eprintln!("p-refinement on 2 elements: {e:?}");
    for w in e.windows(2) {
        assert!(w[1] < 0.1 * w[0], "no exponential convergence: {e:?}");
    }
}

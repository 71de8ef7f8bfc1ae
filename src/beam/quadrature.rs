//! Quadrature rules on [−1, 1]: Gauss–Legendre (exact to degree 2n − 1) and Gauss–Lobatto
//! (endpoints included, exact to degree 2n − 3), nodes by Newton's method on Legendre
//! polynomials.

#[derive(Clone, Debug)]
pub struct Rule {
    pub points: Vec<f64>,
    pub weights: Vec<f64>,
}

/// P_n(x) and P_n'(x) by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let k = k as f64;
        let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    let dp = if (x * x - 1.0).abs() < 1e-300 {
        0.0
    } else {
        n as f64 * (x * p1 - p0) / (x * x - 1.0)
    };
    (p1, dp)
}

pub fn gauss(n: usize) -> Rule {
    let mut points = vec![0.0; n];
    let mut weights = vec![0.0; n];
    for i in 0..n {
        let mut x = -(std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        for _ in 0..100 {
            let (p, dp) = legendre(n, x);
            let dx = p / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        let (_, dp) = legendre(n, x);
        points[i] = x;
        weights[i] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
    Rule { points, weights }
}

/// n ≥ 2 points: ±1 and the roots of P'_{n−1}.
pub fn lobatto(n: usize) -> Rule {
    assert!(n >= 2, "a Lobatto rule has at least the two endpoints");
    let m = n - 1;
    let mut points = vec![0.0; n];
    let mut weights = vec![0.0; n];
    points[0] = -1.0;
    points[m] = 1.0;
    for i in 1..m {
        // Chebyshev–Gauss–Lobatto guess, then Newton on P'_m using P''_m from the Legendre ODE.
        let mut x = -(std::f64::consts::PI * i as f64 / m as f64).cos();
        for _ in 0..100 {
            let (p, dp) = legendre(m, x);
            let ddp = (2.0 * x * dp - (m * (m + 1)) as f64 * p) / (1.0 - x * x);
            let dx = dp / ddp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        points[i] = x;
    }
    for i in 0..n {
        let (p, _) = legendre(m, points[i]);
        weights[i] = 2.0 / ((m * n) as f64 * p * p);
    }
    Rule { points, weights }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exactness: Gauss with n points integrates x^k exactly for k ≤ 2n − 1, Lobatto for
    /// k ≤ 2n − 3; for few points the next even degree is visibly not exact.
    #[test]
    fn exactness_degrees() {
        let exact = |k: i32| {
            if k % 2 == 1 {
                0.0
            } else {
                2.0 / (k as f64 + 1.0)
            }
        };
        let integrate = |r: &Rule, k: i32| {
            r.points
                .iter()
                .zip(&r.weights)
                .map(|(x, w)| w * x.powi(k))
                .sum::<f64>()
        };
        for n in 1..=11 {
            let g = gauss(n);
            for k in 0..=(2 * n as i32 - 1) {
                assert!(
                    (integrate(&g, k) - exact(k)).abs() < 1e-13,
                    "gauss {n} x^{k}"
                );
            }
            if n <= 4 {
                assert!((integrate(&g, 2 * n as i32) - exact(2 * n as i32)).abs() > 1e-6);
            }
        }
        for n in 2..=11 {
            let l = lobatto(n);
            for k in 0..=(2 * n as i32 - 3) {
                assert!(
                    (integrate(&l, k) - exact(k)).abs() < 1e-13,
                    "lobatto {n} x^{k}"
                );
            }
        }
    }
}

//! Lagrange shape functions of degree p on one element, through the Gauss–Lobatto points
//! (well conditioned up to p = 10, unlike equally spaced nodes).

use super::quadrature::lobatto;

#[derive(Clone, Debug)]
pub struct Lagrange {
    /// Nodes on [−1, 1], ascending, both ends included.
    pub nodes: Vec<f64>,
    /// 1 / Π_{b≠a} (ξ_a − ξ_b) for every node a: the basis is evaluated at every contact and
    /// output row, where a division per factor was its cost.
    scale: Vec<f64>,
}

impl Lagrange {
    pub fn new(degree: usize) -> Self {
        let nodes = lobatto(degree + 1).points;
        let scale = (0..nodes.len())
            .map(|a| {
                1.0 / (0..nodes.len())
                    .filter(|&b| b != a)
                    .map(|b| nodes[a] - nodes[b])
                    .product::<f64>()
            })
            .collect();
        Lagrange { nodes, scale }
    }

    pub fn count(&self) -> usize {
        self.nodes.len()
    }

    /// Every shape function's coefficients in powers of ξ, lowest first.
    pub fn monomials(&self) -> Vec<Vec<f64>> {
        (0..self.nodes.len())
            .map(|a| {
                let mut c = vec![self.scale[a]];
                for (_, node) in self.nodes.iter().enumerate().filter(|&(b, _)| b != a) {
                    // c(ξ)·(ξ − ξ_b): shifted up a degree, less ξ_b times itself.
                    c.insert(0, 0.0);
                    for j in 0..c.len() - 1 {
                        c[j] -= node * c[j + 1];
                    }
                }
                c
            })
            .collect()
    }

    /// Values and derivatives (in ξ) of every shape function at ξ.
    pub fn eval(&self, xi: f64, n: &mut [f64], dn: &mut [f64]) {
        let k = self.nodes.len();
        for a in 0..k {
            let mut value = self.scale[a];
            let mut deriv = 0.0;
            for b in 0..k {
                if b == a {
                    continue;
                }
                // Product rule: the derivative of a product of linear factors.
                deriv = deriv * (xi - self.nodes[b]) + value;
                value *= xi - self.nodes[b];
            }
            n[a] = value;
            dn[a] = deriv;
        }
    }

    /// Every shape function's value at ξ, the same products as [`Self::eval`]'s without the
    /// derivatives: a point load or a probe on the axis reads these alone.
    pub fn values(&self, xi: f64, n: &mut [f64]) {
        // Π_{b≠a} (ξ − ξ_b) as the product of the factors before a and after a: 3k
        // multiplications instead of k².
        let n = &mut n[..self.nodes.len()];
        let mut before = 1.0;
        for ((value, scale), node) in n.iter_mut().zip(&self.scale).zip(&self.nodes) {
            *value = scale * before;
            before *= xi - node;
        }
        let mut after = 1.0;
        for (value, node) in n.iter_mut().zip(&self.nodes).rev() {
            *value *= after;
            after *= xi - node;
        }
    }

    /// Every shape function and its first three derivatives (in ξ) at ξ: the rolling disk
    /// needs the axis' curvature and how fast it changes.
    pub fn eval_derivatives(&self, xi: f64, out: &mut [[f64; 4]]) {
        let k = self.nodes.len();
        for a in 0..k {
            let mut d = [self.scale[a], 0.0, 0.0, 0.0];
            for b in 0..k {
                if b == a {
                    continue;
                }
                // (P·ℓ)^(j) = P^(j) ℓ + j P^(j−1) ℓ' for the linear factor ℓ.
                for j in (0..4).rev() {
                    let lower = if j > 0 { j as f64 * d[j - 1] } else { 0.0 };
                    d[j] = d[j] * (xi - self.nodes[b]) + lower;
                }
            }
            out[a] = d;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each shape function's powers of ξ against its values, on degrees 1 to 8 over the
    /// element: within 10⁻¹² (the coefficients of degree 8 reach about 10², their sum at
    /// |ξ| ≤ 1 cancels to the value).
    #[test]
    fn monomials_are_the_shape_functions() {
        for p in 1..=8 {
            let b = Lagrange::new(p);
            let monomials = b.monomials();
            let mut n = vec![0.0; p + 1];
            for xi in [-1.0, -0.71, 0.0, 0.3127, 0.95, 1.0] {
                b.values(xi, &mut n);
                for (a, c) in monomials.iter().enumerate() {
                    let value = c.iter().rev().fold(0.0, |acc, cj| acc * xi + cj);
                    assert!((value - n[a]).abs() < 1e-12, "p = {p}, N_{a}({xi})");
                }
            }
        }
    }

    /// Partition of unity, Kronecker property at the nodes, and exact derivatives of ξ^p.
    #[test]
    fn interpolation_properties() {
        for p in 1..=10 {
            let b = Lagrange::new(p);
            let mut n = vec![0.0; p + 1];
            let mut dn = vec![0.0; p + 1];
            b.eval(0.3127, &mut n, &mut dn);
            let mut values = vec![0.0; p + 1];
            b.values(0.3127, &mut values);
            // The same products in another order: equal to a few round-offs (|N_a| < 1.1
            // at Gauss–Lobatto nodes up to degree 10).
            for (v, e) in values.iter().zip(&n) {
                assert!(
                    (v - e).abs() < 1e-14,
                    "p = {p}: the values alone are eval's"
                );
            }
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            assert!(dn.iter().sum::<f64>().abs() < 1e-10);
            let interp: f64 = (0..=p).map(|a| dn[a] * b.nodes[a].powi(p as i32)).sum();
            assert!(
                (interp - p as f64 * 0.3127f64.powi(p as i32 - 1)).abs() < 1e-9,
                "p = {p}"
            );
            let mut all = vec![[0.0; 4]; p + 1];
            b.eval_derivatives(0.3127, &mut all);
            for j in 0..3.min(p) {
                let expect =
                    (p - j..=p).product::<usize>() as f64 * 0.3127f64.powi((p - j - 1) as i32);
                let got: f64 = (0..=p)
                    .map(|a| all[a][j + 1] * b.nodes[a].powi(p as i32))
                    .sum();
                assert!(
                    (got - expect).abs() < 1e-8 * expect.abs().max(1.0),
                    "p = {p}, d{}",
                    j + 1
                );
            }
            b.eval(b.nodes[1], &mut n, &mut dn);
            assert!((n[1] - 1.0).abs() < 1e-14 && n[0].abs() < 1e-14);
        }
    }
}

//! A natural cubic spline Y(X) through measured points: C2, so the curvature the rolling
//! equations need is continuous. The curve parameter is s = X.

#[derive(Clone, Debug)]
pub struct Spline {
    x: Vec<f64>,
    y: Vec<f64>,
    /// Second derivatives at the knots (zero at both ends: natural spline).
    m: Vec<f64>,
}

impl Spline {
    /// `points` must hold at least 2 points with strictly increasing X (the scene checks both
    /// with a message that names the point).
    pub fn new(points: &[[f64; 2]]) -> Spline {
        let n = points.len();
        let x: Vec<f64> = points.iter().map(|p| p[0]).collect();
        let y: Vec<f64> = points.iter().map(|p| p[1]).collect();
        let mut m = vec![0.0; n];
        if n > 2 {
            // Tridiagonal system for the interior second derivatives (Thomas algorithm).
            let k = n - 2;
            let mut diag = vec![0.0; k];
            let mut rhs = vec![0.0; k];
            let mut upper = vec![0.0; k];
            for i in 1..n - 1 {
                let h0 = x[i] - x[i - 1];
                let h1 = x[i + 1] - x[i];
                diag[i - 1] = 2.0 * (h0 + h1);
                upper[i - 1] = h1;
                rhs[i - 1] = 6.0 * ((y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0);
            }
            for i in 1..k {
                let lower = x[i + 1] - x[i];
                let w = lower / diag[i - 1];
                diag[i] -= w * upper[i - 1];
                rhs[i] -= w * rhs[i - 1];
            }
            m[k] = rhs[k - 1] / diag[k - 1];
            for i in (0..k - 1).rev() {
                m[i + 1] = (rhs[i] - upper[i] * m[i + 2]) / diag[i];
            }
        }
        Spline { x, y, m }
    }

    pub fn domain(&self) -> (f64, f64) {
        (self.x[0], self.x[self.x.len() - 1])
    }

    /// The interior knots: there Y'' is continuous but Y''' jumps, so the curvature has a kink.
    pub fn interior_knots(&self) -> &[f64] {
        &self.x[1..self.x.len() - 1]
    }

    /// Y, Y', Y'' at X = s (clamped to the last interval at the ends).
    pub fn eval(&self, s: f64) -> (f64, f64, f64) {
        let n = self.x.len();
        let i = match self.x.partition_point(|&xi| xi <= s) {
            0 => 0,
            p if p >= n => n - 2,
            p => p - 1,
        };
        let h = self.x[i + 1] - self.x[i];
        let a = (self.x[i + 1] - s) / h;
        let b = (s - self.x[i]) / h;
        let (m0, m1) = (self.m[i], self.m[i + 1]);
        let y = a * self.y[i]
            + b * self.y[i + 1]
            + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6.0;
        let dy = (self.y[i + 1] - self.y[i]) / h
            + ((1.0 - 3.0 * a * a) * m0 + (3.0 * b * b - 1.0) * m1) * h / 6.0;
        let ddy = a * m0 + b * m1;
        (y, dy, ddy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A natural spline reproduces a straight line exactly, and through samples of a cubic it is
    /// C2 at the knots.
    #[test]
    fn line_exact_and_c2_at_knots() {
        let pts: Vec<[f64; 2]> = (0..6)
            .map(|i| [i as f64 * 0.7, 2.0 - 0.3 * i as f64 * 0.7])
            .collect();
        let sp = Spline::new(&pts);
        let (y, dy, ddy) = sp.eval(1.234);
        assert!(
            (y - (2.0 - 0.3 * 1.234)).abs() < 1e-14
                && (dy + 0.3).abs() < 1e-14
                && ddy.abs() < 1e-14
        );
        let pts: Vec<[f64; 2]> = (0..8)
            .map(|i| {
                let x = i as f64 * 0.5;
                [x, x.powi(3) - x]
            })
            .collect();
        let sp = Spline::new(&pts);
        for &xk in &[0.5, 1.0, 2.5] {
            let l = sp.eval(xk - 1e-12);
            let r = sp.eval(xk + 1e-12);
            assert!((l.1 - r.1).abs() < 1e-9 && (l.2 - r.2).abs() < 1e-9);
        }
    }
}

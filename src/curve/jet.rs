//! Second-order forward-mode dual numbers ("jets"): a value with its first and second
//! derivatives with respect to the curve parameter. They give the exact r'(s) and r''(s) of any
//! curve written as a formula, which the rolling equations need for the tangent and curvature.

use std::ops::{Add, Div, Mul, Neg, Sub};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jet {
    pub v: f64,
    pub d1: f64,
    pub d2: f64,
}

impl Jet {
    pub fn constant(v: f64) -> Self {
        Jet {
            v,
            d1: 0.0,
            d2: 0.0,
        }
    }

    pub fn variable(v: f64) -> Self {
        Jet {
            v,
            d1: 1.0,
            d2: 0.0,
        }
    }

    /// Chain rule for a scalar function f with f(v), f'(v), f''(v) given.
    fn chain(self, f: f64, df: f64, ddf: f64) -> Self {
        Jet {
            v: f,
            d1: df * self.d1,
            d2: ddf * self.d1 * self.d1 + df * self.d2,
        }
    }

    pub fn sin(self) -> Self {
        let (s, c) = self.v.sin_cos();
        self.chain(s, c, -s)
    }
    pub fn cos(self) -> Self {
        let (s, c) = self.v.sin_cos();
        self.chain(c, -s, -c)
    }
    pub fn tan(self) -> Self {
        let t = self.v.tan();
        let sec2 = 1.0 + t * t;
        self.chain(t, sec2, 2.0 * t * sec2)
    }
    pub fn exp(self) -> Self {
        let e = self.v.exp();
        self.chain(e, e, e)
    }
    pub fn ln(self) -> Self {
        let x = self.v;
        self.chain(x.ln(), 1.0 / x, -1.0 / (x * x))
    }
    pub fn sqrt(self) -> Self {
        let r = self.v.sqrt();
        self.chain(r, 0.5 / r, -0.25 / (r * self.v))
    }
    pub fn sinh(self) -> Self {
        self.chain(self.v.sinh(), self.v.cosh(), self.v.sinh())
    }
    pub fn cosh(self) -> Self {
        self.chain(self.v.cosh(), self.v.sinh(), self.v.cosh())
    }
    pub fn tanh(self) -> Self {
        let t = self.v.tanh();
        let d = 1.0 - t * t;
        self.chain(t, d, -2.0 * t * d)
    }
    pub fn asin(self) -> Self {
        let x = self.v;
        let q = 1.0 - x * x;
        self.chain(x.asin(), 1.0 / q.sqrt(), x / (q * q.sqrt()))
    }
    pub fn acos(self) -> Self {
        let x = self.v;
        let q = 1.0 - x * x;
        self.chain(x.acos(), -1.0 / q.sqrt(), -x / (q * q.sqrt()))
    }
    pub fn atan(self) -> Self {
        let x = self.v;
        let q = 1.0 + x * x;
        self.chain(x.atan(), 1.0 / q, -2.0 * x / (q * q))
    }
    pub fn abs(self) -> Self {
        let sign = if self.v < 0.0 { -1.0 } else { 1.0 };
        self.chain(self.v.abs(), sign, 0.0)
    }

    /// u^p. A constant integer exponent uses the power rule with `powi`, so that 0^1 and 0^2
    /// keep finite derivatives; anything else goes through exp(p ln u).
    pub fn pow(self, p: Jet) -> Self {
        if p.d1 == 0.0 && p.d2 == 0.0 {
            let c = p.v;
            if c.fract() == 0.0 && c.abs() <= 64.0 {
                let n = c as i32;
                let f = self.v.powi(n);
                let df = if n == 0 { 0.0 } else { c * self.v.powi(n - 1) };
                let ddf = if n == 0 || n == 1 {
                    0.0
                } else {
                    c * (c - 1.0) * self.v.powi(n - 2)
                };
                return self.chain(f, df, ddf);
            }
            let f = self.v.powf(c);
            return self.chain(
                f,
                c * self.v.powf(c - 1.0),
                c * (c - 1.0) * self.v.powf(c - 2.0),
            );
        }
        (p * self.ln()).exp()
    }
}

impl Add for Jet {
    type Output = Jet;
    fn add(self, o: Jet) -> Jet {
        Jet {
            v: self.v + o.v,
            d1: self.d1 + o.d1,
            d2: self.d2 + o.d2,
        }
    }
}
impl Sub for Jet {
    type Output = Jet;
    fn sub(self, o: Jet) -> Jet {
        Jet {
            v: self.v - o.v,
            d1: self.d1 - o.d1,
            d2: self.d2 - o.d2,
        }
    }
}
impl Neg for Jet {
    type Output = Jet;
    fn neg(self) -> Jet {
        Jet {
            v: -self.v,
            d1: -self.d1,
            d2: -self.d2,
        }
    }
}
impl Mul for Jet {
    type Output = Jet;
    fn mul(self, o: Jet) -> Jet {
        Jet {
            v: self.v * o.v,
            d1: self.d1 * o.v + self.v * o.d1,
            d2: self.d2 * o.v + 2.0 * self.d1 * o.d1 + self.v * o.d2,
        }
    }
}
impl Div for Jet {
    type Output = Jet;
    fn div(self, o: Jet) -> Jet {
        let q = self.v / o.v;
        let q1 = (self.d1 - q * o.d1) / o.v;
        let q2 = (self.d2 - 2.0 * q1 * o.d1 - q * o.d2) / o.v;
        Jet {
            v: q,
            d1: q1,
            d2: q2,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Derivatives of a composite function against hand-derived closed forms.
    #[test]
    fn composite_derivatives_match_closed_forms() {
        let x = 0.7;
        let s = Jet::variable(x);
        let f = (s * s).sin() / (Jet::constant(1.0) + s.exp());
        let g = x * x;
        let d = 1.0 + x.exp();
        let num = g.sin();
        let num1 = 2.0 * x * g.cos();
        let num2 = 2.0 * g.cos() - 4.0 * x * x * g.sin();
        let d1 = x.exp();
        let expect1 = (num1 * d - num * d1) / (d * d);
        let expect2 =
            (num2 * d - num * d1) / (d * d) - 2.0 * d1 * (num1 * d - num * d1) / (d * d * d);
        assert!((f.v - num / d).abs() < 1e-15);
        assert!((f.d1 - expect1).abs() < 1e-14);
        assert!((f.d2 - expect2).abs() < 1e-13);
        let p = s.pow(Jet::constant(3.0));
        assert!((p.d2 - 6.0 * x).abs() < 1e-14);
        let zero = Jet::variable(0.0).pow(Jet::constant(1.0));
        assert_eq!((zero.v, zero.d1, zero.d2), (0.0, 1.0, 0.0));
    }
}

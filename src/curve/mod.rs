//! The rigid track: a plane curve r(s) = (X(s), Y(s)) with its first two derivatives, and the
//! frame the rolling equations are written in (unit tangent, left normal, curvature).

pub mod expr;
pub mod jet;
pub mod spline;

use expr::Formula;
use spline::Spline;

/// A point of the curve with its first and second derivatives in the parameter s.
#[derive(Clone, Copy, Debug)]
pub struct CurvePoint {
    pub r: [f64; 2],
    pub d1: [f64; 2],
    pub d2: [f64; 2],
}

impl CurvePoint {
    /// |r'(s)|: arc length per unit of parameter.
    pub fn speed(&self) -> f64 {
        self.d1[0].hypot(self.d1[1])
    }

    /// Unit tangent e_t = r'/|r'|.
    pub fn tangent(&self) -> [f64; 2] {
        let g = self.speed();
        [self.d1[0] / g, self.d1[1] / g]
    }

    /// Left normal e_n = E_Z × e_t: the side the disk sits on.
    pub fn normal(&self) -> [f64; 2] {
        let t = self.tangent();
        [-t[1], t[0]]
    }

    /// ψ'(s), the rate of turn of the tangent per unit parameter, in the curvature form
    /// (X'Y'' − Y'X'')/(X'² + Y'²) (erratum 1: the thesis' arccos form has the wrong sign on
    /// descending branches).
    pub fn psi_prime(&self) -> f64 {
        let [x1, y1] = self.d1;
        let [x2, y2] = self.d2;
        (x1 * y2 - y1 * x2) / (x1 * x1 + y1 * y1)
    }

    /// Signed curvature κ = ψ'/|r'|, positive where the curve turns towards the disk.
    pub fn curvature(&self) -> f64 {
        self.psi_prime() / self.speed()
    }
}

#[derive(Clone, Debug)]
pub enum Curve {
    /// Y = k X², s = X.
    Parabola {
        k: f64,
    },
    /// s = arc length from `from`.
    Line {
        from: [f64; 2],
        to: [f64; 2],
    },
    Expr {
        x: Formula,
        y: Formula,
    },
    /// A C2 spline through points, s = X.
    Points(Spline),
}

impl Curve {
    pub fn at(&self, s: f64) -> CurvePoint {
        match self {
            Curve::Parabola { k } => CurvePoint {
                r: [s, k * s * s],
                d1: [1.0, 2.0 * k * s],
                d2: [0.0, 2.0 * k],
            },
            Curve::Line { from, to } => {
                let len = (to[0] - from[0]).hypot(to[1] - from[1]);
                let t = [(to[0] - from[0]) / len, (to[1] - from[1]) / len];
                CurvePoint {
                    r: [from[0] + s * t[0], from[1] + s * t[1]],
                    d1: t,
                    d2: [0.0, 0.0],
                }
            }
            Curve::Expr { x, y } => {
                let (x, y) = (x.eval(s), y.eval(s));
                CurvePoint {
                    r: [x.v, y.v],
                    d1: [x.d1, y.d1],
                    d2: [x.d2, y.d2],
                }
            }
            Curve::Points(sp) => {
                let (y, dy, ddy) = sp.eval(s);
                CurvePoint {
                    r: [s, y],
                    d1: [1.0, dy],
                    d2: [0.0, ddy],
                }
            }
        }
    }

    /// The parameter range of a finite curve; unbounded curves have none.
    pub fn domain(&self) -> Option<(f64, f64)> {
        match self {
            Curve::Line { from, to } => Some((0.0, (to[0] - from[0]).hypot(to[1] - from[1]))),
            Curve::Points(sp) => Some(sp.domain()),
            Curve::Parabola { .. } | Curve::Expr { .. } => None,
        }
    }

    /// The parameters where the curvature has a kink (a spline's interior knots): a contact
    /// force's extreme may sit there, where no turning point of a smooth fit finds it.
    pub fn curvature_kinks(&self) -> &[f64] {
        match self {
            Curve::Points(sp) => sp.interior_knots(),
            Curve::Parabola { .. } | Curve::Line { .. } | Curve::Expr { .. } => &[],
        }
    }

    pub fn kind(&self) -> &'static str {
        match self {
            Curve::Parabola { .. } => "parabola",
            Curve::Line { .. } => "line",
            Curve::Expr { .. } => "expr",
            Curve::Points(_) => "points",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The parabola's curvature 2k/(1+4k²s²)^{3/2} and the circle's 1/R, both from the generic
    /// frame code, the circle through the formula path.
    #[test]
    fn curvature_closed_forms() {
        let p = Curve::Parabola { k: 1.5 };
        let s: f64 = -0.4;
        let expect = 3.0 / (1.0 + 9.0 * s * s).powf(1.5);
        assert!((p.at(s).curvature() - expect).abs() < 1e-14);
        let c = Curve::Expr {
            x: Formula::parse("2*cos(s)").unwrap(),
            y: Formula::parse("2*sin(s)").unwrap(),
        };
        assert!((c.at(0.3).curvature() - 0.5).abs() < 1e-14);
    }
}

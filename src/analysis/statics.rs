//! Static equilibrium f_int(q) = λ f_ext by Newton's method with load stepping: the load
//! factor λ goes to 1 in steps that halve when Newton fails and grow again when it converges
//! quickly, so strongly nonlinear cases (a cantilever rolled into a circle) are reached.

use std::fmt;

use crate::beam::{Beam, BeamModel};
use crate::linalg::SparseLu;

#[derive(Clone, Debug)]
pub struct StaticSolution {
    pub q: Vec<f64>,
    pub iterations: usize,
    pub load_steps: usize,
}

#[derive(Clone, Debug, PartialEq)]
pub enum StaticError {
    Singular,
    NoConvergence { reached: f64 },
}

impl fmt::Display for StaticError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StaticError::Singular => write!(f, "the stiffness matrix is singular: the beam is not supported enough for a static solution"),
            StaticError::NoConvergence { reached } => write!(
                f,
                "Newton's method did not converge beyond {:.1} % of the load even with load steps of 1/1024; the structure may buckle or snap there",
                100.0 * reached
            ),
        }
    }
}

const MAX_ITERATIONS: usize = 30;

pub fn solve(beam: &Beam, f_ext: &[f64]) -> Result<StaticSolution, StaticError> {
    let n = beam.dim();
    let mut q = vec![0.0; n];
    let mut f_int = vec![0.0; n];
    let mut lambda = 0.0;
    let mut step: f64 = 1.0;
    let mut iterations = 0;
    let mut load_steps = 0;
    // The tangent's pattern stays: its ordering is found once.
    let mut factored: Option<SparseLu> = None;
    let linear = beam.spec.model != BeamModel::Exact;
    while lambda < 1.0 {
        let target = (lambda + step).min(1.0);
        let mut trial = q.clone();
        let mut converged = false;
        let mut its = 0;
        let mut last_dq = f64::INFINITY;
        for _ in 0..MAX_ITERATIONS {
            its += 1;
            beam.internal_force(&trial, &mut f_int);
            let mut r: Vec<f64> = (0..n).map(|i| target * f_ext[i] - f_int[i]).collect();
            let k = beam.tangent(&trial);
            let Some(lu) = SparseLu::factor(&k, factored.take()) else {
                if lambda == 0.0 {
                    return Err(StaticError::Singular);
                }
                break;
            };
            lu.solve_in_place(&mut r);
            factored = Some(lu);
            let dq = r.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            if !dq.is_finite() {
                break;
            }
            trial.iter_mut().zip(&r).for_each(|(t, d)| *t += d);
            let size = trial.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            // Newton converges quadratically: a correction of 1e-9 of the solution leaves an
            // error near round-off after it is applied.
            // A linear beam's first solve is its answer, and what follows refines it while
            // the residual K q − f has digits left: where the shear stiffness dwarfs the
            // bending one (up to `beam::shear_rigid_limit`), the assembled K q loses the
            // shear strain w′ − φ to cancellation and the corrections stop shrinking at 10⁻⁶
            // to 10⁻⁹ of the deflection, the solve's own round-off.
            let stalled = linear && dq >= 0.5 * last_dq;
            if dq <= 1e-9 * size || size == 0.0 || stalled {
                converged = true;
                break;
            }
            last_dq = dq;
        }
        iterations += its;
        if converged {
            q = trial;
            lambda = target;
            load_steps += 1;
            if its <= 6 {
                step *= 2.0;
            }
        } else {
            step *= 0.5;
            if step < 1.0 / 1024.0 {
                return Err(StaticError::NoConvergence { reached: lambda });
            }
        }
    }
    Ok(StaticSolution {
        q,
        iterations,
        load_steps,
    })
}

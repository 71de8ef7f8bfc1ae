//! Weighted sums of the oscillators' displacements or accelerations over an exact step, each
//! in closed form: one polynomial in σ, the series' and the particular solutions' weighted
//! and added, and one complex amplitude per under-damped oscillator's free motion. A watch
//! that reads a few such sums at many times within a step (a sweep's probes) then pays one
//! Horner pass for all sums at once and one phasor product per oscillator, where reading the
//! state would evaluate every oscillator's motion and rate and form the accelerations.

use super::{Motion, StepMotion};
use crate::ode::second_order::LinearModal;
use crate::ode::{FormRow, StepForms};
use std::cell::RefCell;

type C64 = nalgebra::Complex<f64>;

/// The phasors e^{λ_k τ} at the τ last read, and e^{λ_k δ} for the spacing δ read last: an
/// even grid of samples takes one product per oscillator a sample instead of an exponential,
/// a sine and a cosine.
pub(crate) struct Carry {
    tau: f64,
    phasors: Vec<C64>,
    by: Option<(f64, Vec<C64>)>,
}

/// The sums `rows` over the accepted step `m`; `None` where an oscillator's motion is not one
/// series piece or an under-damped particular form (over-damped, or a long series), which the
/// state then reads.
pub(super) fn forms(m: &StepMotion, linear: &LinearModal, rows: &[FormRow]) -> Option<StepForms> {
    let n = m.motions.len();
    if n == 0 || !(m.h > 0.0) || n != linear.stiffness.len() {
        return None;
    }
    // Per oscillator its polynomial part in σ and, under-damped, its free motion
    // Re A e^{λτ}: e^{−cτ/2}(e₀ cos ω_d τ + b sin ω_d τ / ω_d) with A = e₀ − i b/ω_d.
    let mut parts: Vec<(&[f64], Option<(C64, C64)>)> = Vec::with_capacity(n);
    for (k, motion) in m.motions.iter().enumerate() {
        match motion {
            Motion::Series(pieces) if pieces.len() == 1 => parts.push((&pieces[0], None)),
            Motion::Particular { p, e0, e1 } => {
                let half = 0.5 * linear.damping[k];
                let kappa = half * half - linear.stiffness[k];
                if !(kappa < 0.0) {
                    return None;
                }
                let wd = (-kappa).sqrt();
                let b = e1 + half * e0;
                parts.push((p, Some((C64::new(*e0, -b / wd), C64::new(-half, wd)))));
            }
            Motion::Rest => parts.push((&[], None)),
            Motion::Series(_) => return None,
        }
    }
    let lambda: Vec<C64> = parts.iter().filter_map(|(_, f)| f.map(|f| f.1)).collect();
    let lambda_count = lambda.len();
    let count = rows.len();
    let degree = parts.iter().map(|(p, _)| p.len()).max().unwrap_or(0);
    let mut polys = vec![0.0; degree * count];
    let mut free = vec![C64::new(0.0, 0.0); lambda.len() * count];
    let h2 = m.h * m.h;
    for (r, row) in rows.iter().enumerate() {
        let mut k = 0;
        for (&weight, (p, f)) in row.weights.iter().zip(&parts) {
            // x'' in t is the polynomial's second derivative in σ over h², and λ² A e^{λτ}.
            if row.accelerations {
                for (j, &pj) in p.iter().enumerate().skip(2) {
                    polys[(j - 2) * count + r] += weight * (j * (j - 1)) as f64 / h2 * pj;
                }
            } else {
                for (j, &pj) in p.iter().enumerate() {
                    polys[j * count + r] += weight * pj;
                }
            }
            if let Some((a, l)) = f {
                let a = if row.accelerations { a * l * l } else { *a };
                free[k * count + r] = a * weight;
                k += 1;
            }
        }
    }
    Some(StepForms {
        t0: m.t0,
        h: m.h,
        lambda,
        count,
        polys,
        free,
        carry: RefCell::new(Carry {
            tau: 0.0,
            phasors: vec![C64::new(1.0, 0.0); lambda_count],
            by: None,
        }),
    })
}

impl StepForms {
    /// Every sum at t (held to the step, as the state's reading is).
    pub fn at(&self, t: f64, out: &mut [f64]) {
        let sigma = ((t - self.t0) / self.h).clamp(0.0, 1.0);
        let tau = sigma * self.h;
        let mut carry = self.carry.borrow_mut();
        self.phasors_at(tau, &mut carry);
        let count = self.count;
        // The sums four at a time (a probe's u, w, φ and a), their Horner passes side by side:
        // four independent chains of products in the registers, not one after another.
        for (r, out) in out[..count].chunks_mut(LANES).enumerate() {
            let mut acc = [0.0; LANES];
            for coefficients in self.polys.chunks_exact(count).rev() {
                let c = &coefficients[r * LANES..];
                for (a, c) in acc.iter_mut().zip(c) {
                    *a = *a * sigma + c;
                }
            }
            for (amplitudes, z) in self.free.chunks_exact(count).zip(&carry.phasors) {
                for (a, b) in acc.iter_mut().zip(&amplitudes[r * LANES..]) {
                    *a += b.re * z.re - b.im * z.im;
                }
            }
            out.copy_from_slice(&acc[..out.len()]);
        }
    }

    /// The phasors at τ into `carry`: carried on from the last τ read (the step's start, at
    /// first), by the spacing read last where τ lies that far on (within a few ulps: the
    /// samples' own rounding) and by a new one where it lies farther; formed afresh before it.
    fn phasors_at(&self, tau: f64, carry: &mut Carry) {
        let exp = |dt: f64| -> Vec<C64> {
            self.lambda
                .iter()
                .map(|l| {
                    let (sin, cos) = (l.im * dt).sin_cos();
                    C64::new(cos, sin) * (l.re * dt).exp()
                })
                .collect()
        };
        let near = |a: f64, b: f64| (a - b).abs() <= 8.0 * f64::EPSILON * self.h;
        let step = tau - carry.tau;
        match &carry.by {
            Some((by, factors)) if near(*by, step) => {
                carry
                    .phasors
                    .iter_mut()
                    .zip(factors)
                    .for_each(|(z, f)| *z *= f);
            }
            _ if step > 0.0 => {
                let factors = exp(step);
                carry
                    .phasors
                    .iter_mut()
                    .zip(&factors)
                    .for_each(|(z, f)| *z *= f);
                carry.by = Some((step, factors));
            }
            _ => carry.phasors = exp(tau),
        }
        carry.tau = tau;
    }

    /// How many sums it holds.
    pub fn len(&self) -> usize {
        self.count
    }
}

/// Sums read side by side.
const LANES: usize = 4;

#[cfg(test)]
mod tests {
    use super::super::{evaluate, horner, motion, TEST_MODES, TEST_STEPS};
    use super::*;

    /// Two oscillators' weighted displacement and acceleration in closed form against the
    /// motion itself, x from [`evaluate`] and ẍ = g − c ẋ − ω² x from the equation: on an even
    /// grid (the phasors carried on), then back and forth off it (formed afresh), for every
    /// test mode and step whose motion has a form. Within 10⁻¹¹ of the sum's scale (each
    /// oscillator's amplitude and its acceleration's, weighted): the phase carries the
    /// round-off of t, ω·ε·t ≈ 10⁻¹² on the fastest mode, and the carried phasors a few ulps
    /// more a sample (the worst measured is below 10⁻¹²).
    #[test]
    fn weighted_sums_in_closed_form_match_the_motion() {
        let g = [1.0, -2.0, 0.5, 3.0, -1.0];
        let weights = [0.7, -1.3];
        let rows = [
            FormRow {
                weights: &weights,
                accelerations: false,
            },
            FormRow {
                weights: &weights,
                accelerations: true,
            },
        ];
        let mut checked = 0;
        for (i, &(w2, c)) in TEST_MODES.iter().enumerate() {
            let other = TEST_MODES[(i + 1) % TEST_MODES.len()];
            for &h in &TEST_STEPS {
                let modes = [(w2, c), other];
                let m = StepMotion {
                    t0: 2.0,
                    h,
                    force: vec![g.to_vec(); 2],
                    motions: modes
                        .iter()
                        .map(|&(w2, c)| motion(w2, c, h, &g, 0.3, -1.7))
                        .collect(),
                };
                let linear = LinearModal {
                    stiffness: modes.iter().map(|m| m.0).collect(),
                    damping: modes.iter().map(|m| m.1).collect(),
                    degree: g.len() - 1,
                };
                let Some(f) = forms(&m, &linear, &rows) else {
                    continue;
                };
                checked += 1;
                let grid = (0..=8).map(|j| j as f64 / 8.0);
                for sigma in grid.chain([0.37, 0.05, 0.99, 0.5]) {
                    let (mut x, mut a, mut scale) = (0.0, 0.0, [0.0; 2]);
                    for (k, &(w2, c)) in modes.iter().enumerate() {
                        let (xk, vk) = evaluate(&m.motions[k], w2, c, h, sigma);
                        let ak = horner(&g, sigma) - c * vk - w2 * xk;
                        x += weights[k] * xk;
                        a += weights[k] * ak;
                        // The motion's amplitude, not its value: a sample near a zero
                        // crossing of a fast mode carries its phase's round-off, ω δt.
                        let w = w2.sqrt();
                        let amplitude =
                            xk.abs() + if w > 0.0 { vk.abs() / w } else { vk.abs() * h };
                        let forced = horner(&g, sigma).abs() + c * vk.abs();
                        scale[0] += weights[k].abs() * amplitude;
                        scale[1] += weights[k].abs() * (forced + w2 * amplitude);
                    }
                    let mut out = [0.0; 2];
                    f.at(2.0 + sigma * h, &mut out);
                    let case = format!("ω² {w2}, c {c}, beside {other:?}, h {h}, σ {sigma}");
                    assert!(
                        (out[0] - x).abs() <= 1e-11 * scale[0],
                        "{case}: x {} against {x}",
                        out[0]
                    );
                    assert!(
                        (out[1] - a).abs() <= 1e-11 * scale[1],
                        "{case}: a {} against {a}",
                        out[1]
                    );
                }
            }
        }
        assert!(checked >= 10, "only {checked} steps had a closed form");
    }
}

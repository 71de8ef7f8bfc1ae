//! Each oscillator's work ∫ g ẋ dt and the energy its damping takes, c ∫ ẋ² dt, over an exact
//! step, as functions of time in closed form: the series and the particular polynomial
//! integrate as polynomials; the free response is split into its two exponentials e^{λτ},
//! λ = −c/2 ± √κ, κ = c²/4 − ω², against which a polynomial P integrates as Q(σ)e^{μσ} − Q(0)
//! (μ = λh, Q' + μQ = P). The energy ledger reads them where the step's force is the moving
//! loads' alone.

use super::{horner, shifted_into, Motion, SERIES_TERMS};
use crate::ode::PowerIntegrals;

/// Below this |κ|^½ h (κ = c²/4 − ω²) a mode is too near critical damping for its free motion
/// to be split into two exponentials: their coefficients, ±b/(2√κ), cancel by about 1/(√κ h)
/// of round-off, 20 here.
const SPLIT_REACH: f64 = 0.05;

/// One oscillator's ∫₀^σh g ẋ dt and c ∫₀^σh ẋ² dt over its motion in a step, as functions of
/// σ formed once a step: the ledger reads them at every output time within it. Its buffers
/// are kept from step to step and refilled ([`ModeEnergy::refill`]): a sweep forms one per
/// mode at every step.
#[derive(Clone, Debug, Default)]
pub(super) struct ModeEnergy {
    form: Form,
    /// Per piece of a series, the antiderivatives in its own time of g ẋ dt/dς and of
    /// c ẋ² dt/dς, and what the pieces before it added; only the first `Form::Series` count.
    pieces: Vec<SeriesPiece>,
    /// The particular form's antiderivatives of g p' and of p'².
    polynomial: (Vec<f64>, Vec<f64>),
    /// The particular form's roots: both, or the first of a conjugate pair.
    roots: Vec<Root>,
    /// Scratch: the force in a piece's own time, and the slope of a piece or of p.
    force: Vec<f64>,
    slope: Vec<f64>,
}

#[derive(Clone, Copy, Debug, Default)]
enum Form {
    /// Not formed: a free motion too near critical damping to split ([`SPLIT_REACH`]).
    #[default]
    Unsplit,
    /// The series' first `count` pieces.
    Series(usize),
    /// x = p(σ) + Σ A e^{λτ} over the roots λ = −c/2 ± √κ, ẋ = p'(σ)/h + Σ V e^{μσ}, μ = λh.
    Particular { h: f64, c: f64 },
    /// A mode at rest under no force ([`Motion::Rest`]): no work, no loss.
    Rest,
}

/// A root of a free motion: its term's rate V, μ = λh, and g and p' against e^{μσ}.
#[derive(Clone, Debug, Default)]
struct Root {
    v: C64,
    mu: C64,
    g: Against,
    slope: Against,
}

#[derive(Clone, Debug, Default)]
struct SeriesPiece {
    work: Vec<f64>,
    dissipated: Vec<f64>,
    before: (f64, f64),
}

/// ∫₀^σ P(σ) e^{μσ} dσ for a polynomial P: Q(σ) e^{μσ} − Q(0) with Q' + μQ = P, formed from the
/// top degree down (an error carried on by (j + 1)/|μ| a degree), where |μ| ≥ 2; by the series
/// of [`exp_moments`] at each σ where |μ| is smaller (`moments` then holds P).
#[derive(Clone, Debug, Default)]
struct Against {
    moments: bool,
    q: Vec<C64>,
    poly: Vec<f64>,
}

impl Against {
    fn refill(&mut self, poly: &[f64], mu: C64) {
        self.moments = mu.norm_sqr() < 4.0;
        if self.moments {
            self.poly.clear();
            self.poly.extend_from_slice(poly);
            return;
        }
        let inverse = mu.inv();
        self.q.clear();
        self.q.resize(poly.len(), C64::new(0.0, 0.0));
        let mut above = C64::new(0.0, 0.0);
        for j in (0..poly.len()).rev() {
            above = (C64::new(poly[j], 0.0) - above * (j + 1) as f64) * inverse;
            self.q[j] = above;
        }
    }

    /// The integral to σ, with e^{μσ} given.
    fn at(&self, mu: C64, sigma: f64, e: C64) -> C64 {
        if self.moments {
            return exp_moments(mu, sigma, self.poly.len())
                .iter()
                .zip(&self.poly)
                .map(|(k, a)| k * *a)
                .sum();
        }
        let value = (self.q.iter().rev()).fold(C64::new(0.0, 0.0), |acc, qj| acc * sigma + qj);
        value * e - self.q.first().copied().unwrap_or_default()
    }
}

impl ModeEnergy {
    /// Form the energies of the motion `m` under `g` into the kept buffers; `false` for a free
    /// motion too near critical damping to split ([`SPLIT_REACH`]).
    pub(super) fn refill(&mut self, m: &Motion, g: &[f64], (w2, c): (f64, f64), h: f64) -> bool {
        self.form = Form::Unsplit;
        match m {
            Motion::Series(pieces) => {
                let count = pieces.len();
                let part = 1.0 / count as f64;
                let hp = h * part;
                let mut before = (0.0, 0.0);
                if self.pieces.len() < count {
                    self.pieces.resize_with(count, SeriesPiece::default);
                }
                for (i, (s, piece)) in pieces.iter().zip(&mut self.pieces).enumerate() {
                    // The force and the rate in the piece's own time ς, as `motion` formed
                    // them: dt = hp dς and ẋ = x'(ς)/hp.
                    shifted_into(g, i as f64 * part, &mut self.force);
                    let mut scale = 1.0;
                    for coefficient in self.force.iter_mut() {
                        *coefficient *= scale;
                        scale *= part;
                    }
                    derivative_into(s, &mut self.slope);
                    antiderivative_of_product(&self.force, &self.slope, 1.0, &mut piece.work);
                    antiderivative_of_square(&self.slope, c / hp, &mut piece.dissipated);
                    piece.before = before;
                    before.0 += horner(&piece.work, 1.0);
                    before.1 += horner(&piece.dissipated, 1.0);
                }
                self.form = Form::Series(count);
            }
            Motion::Particular { p, e0, e1 } => {
                let half = 0.5 * c;
                let kappa = half * half - w2;
                let root = if kappa < 0.0 {
                    C64::new(0.0, (-kappa).sqrt())
                } else {
                    C64::new(kappa.sqrt(), 0.0)
                };
                if kappa.abs().sqrt() * h < SPLIT_REACH {
                    return false;
                }
                let b = e1 + half * e0;
                derivative_into(p, &mut self.slope);
                // Under-damped, the second root and its term are the first's conjugates: the
                // first alone is kept.
                let signs: &[f64] = if kappa < 0.0 { &[1.0] } else { &[1.0, -1.0] };
                self.roots.resize_with(signs.len(), Root::default);
                for (&sign, r) in signs.iter().zip(&mut self.roots) {
                    let lambda = C64::new(-half, 0.0) + root * sign;
                    let amplitude = (C64::new(*e0, 0.0) + C64::new(b, 0.0) / root * sign) * 0.5;
                    r.v = lambda * amplitude;
                    r.mu = lambda * h;
                    r.g.refill(g, r.mu);
                    r.slope.refill(&self.slope, r.mu);
                }
                antiderivative_of_product(g, &self.slope, 1.0, &mut self.polynomial.0);
                antiderivative_of_square(&self.slope, 1.0, &mut self.polynomial.1);
                self.form = Form::Particular { h, c };
            }
            Motion::Rest => self.form = Form::Rest,
        }
        true
    }

    /// (∫ g ẋ dt, c ∫ ẋ² dt) from the step's start to σ.
    pub(super) fn at(&self, sigma: f64) -> (f64, f64) {
        match self.form {
            Form::Unsplit | Form::Rest => (0.0, 0.0),
            Form::Series(count) => {
                let at = sigma * count as f64;
                let i = (at as usize).min(count - 1);
                let piece = &self.pieces[i];
                let local = at - i as f64;
                (
                    piece.before.0 + horner(&piece.work, local),
                    piece.before.1 + horner(&piece.dissipated, local),
                )
            }
            Form::Particular { h, c } => {
                let (roots, polynomial) = (&self.roots, &self.polynomial);
                let a = &roots[0];
                let pair = roots.len() == 1;
                let ea = (a.mu * sigma).exp();
                let terms = |r: &Root, e: C64| {
                    (
                        r.v * r.g.at(r.mu, sigma, e),
                        r.v * r.slope.at(r.mu, sigma, e),
                    )
                };
                let (wa, ca) = terms(a, ea);
                let (work, cross, vb, mb, eb) = match roots.get(1) {
                    Some(b) => {
                        let eb = (b.mu * sigma).exp();
                        let (wb, cb) = terms(b, eb);
                        ((wa + wb).re, (ca + cb).re, b.v, b.mu, eb)
                    }
                    None => (2.0 * wa.re, 2.0 * ca.re, a.v.conj(), a.mu.conj(), ea.conj()),
                };
                let (va, ma) = (a.v, a.mu);
                // ∫ (Σ V e^{μσ})² dσ: the roots' squares and their product twice, each
                // ∫₀^σ e^{νσ} dσ = (e^{νσ} − 1)/ν from the roots' own exponentials where |ν| ≥ 2
                // (the error of the difference is then a round-off of 1/|ν|, of the step's).
                let exp_integral = |nu: C64, e: C64| {
                    if nu.norm_sqr() >= 4.0 {
                        (e - 1.0) / nu
                    } else {
                        sigma * exp_m1_over(nu * sigma)
                    }
                };
                let squares = if pair {
                    2.0 * (va * va * exp_integral(ma * 2.0, ea * ea)).re
                        + 2.0 * (va * vb * exp_integral(ma + mb, ea * eb)).re
                } else {
                    (va * va * exp_integral(ma * 2.0, ea * ea)
                        + vb * vb * exp_integral(mb * 2.0, eb * eb)
                        + va * vb * exp_integral(ma + mb, ea * eb) * 2.0)
                        .re
                };
                (
                    horner(&polynomial.0, sigma) + h * work,
                    c * (horner(&polynomial.1, sigma) / h + 2.0 * cross + h * squares),
                )
            }
        }
    }
}

/// Every mode's work and dissipation from the step's start to σ.
pub(super) fn sum_at(modes: &[ModeEnergy], sigma: f64) -> PowerIntegrals {
    modes
        .iter()
        .map(|m| m.at(sigma))
        .fold(PowerIntegrals::default(), |acc, (w, d)| PowerIntegrals {
            work: acc.work + w,
            dissipated: acc.dissipated + d,
        })
}

type C64 = nalgebra::Complex<f64>;

/// (e^z − 1)/z (1 at z = 0) without the cancellation of the difference at small |z|: its real
/// part as expm1(x) cos y − 2 sin²(y/2), each term to its own round-off.
fn exp_m1_over(z: C64) -> C64 {
    if z.re == 0.0 && z.im == 0.0 {
        return C64::new(1.0, 0.0);
    }
    let (sin, cos) = z.im.sin_cos();
    let half = (0.5 * z.im).sin();
    let e_m1 = C64::new(z.re.exp_m1() * cos - 2.0 * half * half, z.re.exp() * sin);
    e_m1 / z
}

/// ∫₀ˢ σʲ e^{μσ} dσ for j < count, Re μ ≤ 0: by the series of e^{μσ} where |μs| ≤ 2 (every
/// term bounded by 2^m/m!), else by the recurrence K_j = (sʲ e^{μs} − j K_{j−1})/μ, which
/// carries an error on by j/|μs| < count/2 a degree.
fn exp_moments(mu: C64, s: f64, count: usize) -> Vec<C64> {
    let z = mu * s;
    let mut out = vec![C64::new(0.0, 0.0); count];
    if s == 0.0 {
        return out;
    }
    if z.norm_sqr() <= 4.0 {
        // K_j = s^{j+1} Σ_m z^m / (m! (j + m + 1)).
        let mut term = C64::new(1.0, 0.0);
        for m in 0..SERIES_TERMS {
            for (j, k) in out.iter_mut().enumerate() {
                *k += term / (j + m + 1) as f64;
            }
            term = term * z / (m + 1) as f64;
            if term.norm_sqr() < 1e-36 {
                break;
            }
        }
        let mut power = s;
        for k in out.iter_mut() {
            *k *= power;
            power *= s;
        }
        return out;
    }
    let e = z.exp();
    let mut previous = (e - 1.0) / mu;
    out[0] = previous;
    let mut power = 1.0;
    for (j, k) in out.iter_mut().enumerate().skip(1) {
        power *= s;
        previous = (e * power - previous * j as f64) / mu;
        *k = previous;
    }
    out
}

/// The coefficients of a polynomial's derivative, into `out`.
fn derivative_into(c: &[f64], out: &mut Vec<f64>) {
    out.clear();
    out.extend(c.iter().enumerate().skip(1).map(|(j, a)| j as f64 * a));
}

/// 1/k for the degrees an antiderivative of a product of two series reaches: a division in
/// its last pass costs several multiplications.
const RECIPROCALS: [f64; 2 * SERIES_TERMS + 1] = {
    let mut r = [0.0; 2 * SERIES_TERMS + 1];
    let mut k = 1;
    while k <= 2 * SERIES_TERMS {
        r[k] = 1.0 / k as f64;
        k += 1;
    }
    r
};

/// Turn Σ c_k σ^k, each c_k the coefficient of σ^(k−1) in the integrand, into the
/// antiderivative's coefficients.
fn divide_by_degree(out: &mut [f64]) {
    for (k, c) in out.iter_mut().enumerate().skip(2) {
        *c *= RECIPROCALS.get(k).copied().unwrap_or(1.0 / k as f64);
    }
}

/// The antiderivative that vanishes at 0 of `scale` times the product of two polynomials,
/// into `out`.
fn antiderivative_of_product(a: &[f64], b: &[f64], scale: f64, out: &mut Vec<f64>) {
    out.clear();
    if a.is_empty() || b.is_empty() {
        return;
    }
    out.resize(a.len() + b.len(), 0.0);
    for (i, ai) in a.iter().enumerate() {
        let ai = scale * ai;
        // Slices zipped, not indexed: the inner loop runs without bounds checks, vectorised.
        for (o, bj) in out[i + 1..=i + b.len()].iter_mut().zip(b) {
            *o += ai * bj;
        }
    }
    divide_by_degree(out);
}

/// The antiderivative that vanishes at 0 of `scale` times a polynomial's square, into `out`:
/// each cross product formed once and doubled, half the products of
/// [`antiderivative_of_product`] on a series of the step's length.
fn antiderivative_of_square(a: &[f64], scale: f64, out: &mut Vec<f64>) {
    out.clear();
    if a.is_empty() {
        return;
    }
    out.resize(2 * a.len(), 0.0);
    for (i, ai) in a.iter().enumerate() {
        let ai = scale * ai;
        out[2 * i + 1] += ai * a[i];
        let twice = 2.0 * ai;
        for (o, aj) in out[2 * i + 2..=i + a.len()].iter_mut().zip(&a[i + 1..]) {
            *o += twice * aj;
        }
    }
    divide_by_degree(out);
}

#[cfg(test)]
mod tests {
    use super::super::{evaluate, motion, TEST_MODES, TEST_STEPS};
    use super::*;

    /// (e^z − 1)/z against the series of [`exp_moments`] (∫₀¹ e^{zσ} dσ, every term bounded
    /// for |z| ≤ 2) where the two forms meet, at the damped roots' sums the ledger takes it
    /// for: within 4 ulps of the value's size.
    #[test]
    fn the_exponential_s_difference_quotient_matches_its_series() {
        for &(re, im) in &[
            (0.0, 0.0),
            (-1e-12, 0.0),
            (-3e-4, 0.0),
            (-0.7, 0.0),
            (-1.9, 0.3),
            (-1e-3, 1.5),
            (-0.2, -1.9),
            (0.0, 1e-9),
        ] {
            let z = C64::new(re, im);
            let closed = exp_m1_over(z);
            let series = exp_moments(z, 1.0, 1)[0];
            assert!(
                (closed - series).norm() <= 4.0 * f64::EPSILON * series.norm(),
                "z {z}: {closed} against {series}"
            );
        }
    }

    /// The force's work ∫ g ẋ dt and the damping's c ∫ ẋ² dt in closed form, against the
    /// composite four-point Gauss–Legendre rule on the motion itself (pieces of a tenth of a
    /// period and of the decay time, where the rule errs by ~10⁻¹⁴): series and particular
    /// forms, under- and over-damped, undamped and a free mass, over a whole step and a part;
    /// critical damping has none.
    /// Within 10⁻¹¹ of ∫ |g ẋ| dt and of c ∫ ẋ² dt (the worst measured, 1.2·10⁻¹³, over-damped):
    /// what the ledger's balance reads of an exactly integrated run.
    #[test]
    fn power_integrals_in_closed_form_match_quadrature() {
        let g = [1.0, -2.0, 0.5, 3.0, -1.0];
        let nodes = [
            (0.069_431_844_202_973_71, 0.173_927_422_568_726_93),
            (0.330_009_478_207_571_9, 0.326_072_577_431_273_1),
            (0.669_990_521_792_428_1, 0.326_072_577_431_273_1),
            (0.930_568_155_797_026_3, 0.173_927_422_568_726_93),
        ];
        let mut energy = ModeEnergy::default();
        for &(w2, c) in TEST_MODES.iter().chain(&[(4.0e6, 1.0e4)]) {
            for &h in &TEST_STEPS {
                let m = motion(w2, c, h, &g, 0.3, -1.7);
                for &sigma in &[0.37, 1.0] {
                    // One set of buffers refilled for every case, as a run refills them.
                    let Some((work, dissipated)) =
                        energy.refill(&m, &g, (w2, c), h).then(|| energy.at(sigma))
                    else {
                        // Critically damped: the one form left to the quadrature.
                        let split = (0.25 * c * c - w2).abs().sqrt() * h;
                        assert!(split < SPLIT_REACH, "ω² {w2}, c {c}, h {h}: no closed form");
                        continue;
                    };
                    let fast = (w2.sqrt() + c) * h * sigma;
                    let n = (10.0 * fast).ceil().max(64.0) as usize;
                    let (mut w, mut d, mut size) = (0.0, 0.0, 0.0);
                    for i in 0..n {
                        for &(x, weight) in &nodes {
                            let at = sigma * (i as f64 + x) / n as f64;
                            let v = evaluate(&m, w2, c, h, at).1;
                            let dt = weight * h * sigma / n as f64;
                            w += dt * horner(&g, at) * v;
                            size += dt * (horner(&g, at) * v).abs();
                            d += dt * c * v * v;
                        }
                    }
                    let case = format!("ω² {w2}, c {c}, h {h}, σ {sigma}");
                    assert!(
                        (work - w).abs() <= 1e-11 * size,
                        "{case}: work {work:e} against {w:e}"
                    );
                    assert!(
                        (dissipated - d).abs() <= 1e-11 * d + 1e-300,
                        "{case}: dissipated {dissipated:e} against {d:e}"
                    );
                }
            }
        }
    }
}

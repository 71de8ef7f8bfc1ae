//! Exact integration of uncoupled linear oscillators, q̈_k + c_k q̇_k + k_k q_k = g_k(t): a
//! structure that says it is one ([`Structure::linear_modal`]) with a force that does not
//! depend on the state. Over each step the force is fitted by a polynomial in t at
//! Chebyshev–Lobatto points, and each oscillator's response to that polynomial is taken in
//! closed form; where the force is a polynomial over the step (a moving point force between
//! two nodes of the mesh its modes live on, which the problem's kinks make step ends), the
//! step is exact to round-off and as long as the driver allows.
//!
//! Per oscillator, with σ = τ/h ∈ [0, 1] the step's own time and g(σ) = Σ g_j σ^j:
//! - where ωh and ch are small, the Taylor series of the solution about the step's start,
//!   whose coefficients follow from the equation term by term (every term bounded: no
//!   cancellation), in sub-steps of ωh, ch ≤ [`SERIES_REACH`];
//! - elsewhere, a polynomial particular solution (its coefficients from the top degree down,
//!   each division by ω²h² ≥ [`PARTICULAR_REACH`]² keeping them bounded, and by ch ≤ 1 or
//!   ω²h² ≥ [`SERIES_REACH`]² the damping's term too) plus the free response
//!   e^{−ch τ/2}(e₀ C(τ) + b S(τ)), C and S the cosine and sine (or their hyperbolic forms
//!   over-damped), which holds every damping alike.
//!
//! The error estimate is what the two highest Chebyshev coefficients of the force would move:
//! for a force that is a polynomial of the degree the problem names, nothing.
//!
//! `energy.rs`: each oscillator's work and damping over a step in closed form, for the ledger;
//! `forms.rs`: weighted sums of the oscillators over a step in closed form, for the watches.

use super::second_order::{LinearModal, Structure};
use super::{Attempt, Ctx, Dynamics, FormRow, PowerIntegrals, SolveError, StepForms, Stepper};
use energy::{sum_at, ModeEnergy};

mod energy;
mod forms;
pub(crate) use forms::Carry;

/// How far (ωh or ch) a Taylor series is summed in one piece.
const SERIES_REACH: f64 = 4.0;
/// From this ωh on, where ch ≤ 1, a mode takes the particular polynomial: the coefficient two
/// degrees up enters each by (j + 2)(j + 1)/ω²h² ≤ 7.5 at the degree 6 a quartic element's
/// force is fitted by, the damping's by ch (j + 1)/ω²h² ≤ 1.5. Read within the step it is one
/// phasor product and a short polynomial, where the series sums up to forty terms.
const PARTICULAR_REACH: f64 = 2.0;
/// Terms of a series past which what is left is below round-off (4^k/k! < 1e-17 from here).
const SERIES_TERMS: usize = 48;

/// 1 / ((k + 2)(k + 1)), the series' recurrence's divisors: a division in the recurrence's
/// chain of dependent terms costs several multiplications.
const SERIES_DIVISORS: [f64; SERIES_TERMS - 2] = {
    let mut d = [0.0; SERIES_TERMS - 2];
    let mut k = 0;
    while k < SERIES_TERMS - 2 {
        d[k] = 1.0 / ((k + 2) * (k + 1)) as f64;
        k += 1;
    }
    d
};

/// One oscillator's motion over an accepted step, in the step's own time σ ∈ [0, 1].
#[derive(Clone, Debug)]
enum Motion {
    /// x(σ) on consecutive pieces of the step, each its Taylor coefficients in the piece's own
    /// time (x = Σ s_k ς^k, ς ∈ [0, 1] across the piece).
    Series(Vec<Vec<f64>>),
    /// x = p(σ) + the free response from (e₀, e₁), e₁ the rate in t.
    Particular { p: Vec<f64>, e0: f64, e1: f64 },
    /// At rest under no force: a mode the loads do not reach (a level beam's axial modes
    /// under vertical loads), which every reading then skips.
    Rest,
}

/// A step's motion: every oscillator's, and the force's polynomial in σ.
#[derive(Clone, Debug, Default)]
struct StepMotion {
    t0: f64,
    h: f64,
    /// Per oscillator, the force's coefficients in σ.
    force: Vec<Vec<f64>>,
    motions: Vec<Motion>,
}

pub(crate) struct ExactModal {
    /// Degree of the polynomial the force is fitted by, and its Chebyshev–Lobatto points in
    /// the step's own time.
    degree: usize,
    nodes: Vec<f64>,
    /// Row i: the i-th Chebyshev coefficient's weights on the samples at `nodes`, formed once:
    /// every mode fits its force by it at every step.
    chebyshev: Vec<Vec<f64>>,
    /// Row j: the weights that turn the samples into the fitted polynomial's coefficient of
    /// σ^j (each column the interpolant through one unit sample, in monomials).
    monomial: Vec<Vec<f64>>,
    linear: Option<LinearModal>,
    trial: StepMotion,
    accepted: StepMotion,
    y_new: Vec<f64>,
    /// The accepted step's motion at the last time asked, (t, x, ẋ): an observer reads the
    /// state and its rate at one time in turn, and each costs every mode's exponential and
    /// sinusoid.
    evaluated: std::cell::RefCell<Option<(f64, Vec<f64>, Vec<f64>)>>,
    /// The under-damped free responses' phasors at the last time asked within the accepted
    /// step: the ledger samples a long step at equal spacing, and each next phasor is then one
    /// complex product instead of an exponential, a sine and a cosine per mode.
    phasors: std::cell::RefCell<Option<Phasors>>,
    /// The accepted step's work and dissipation per mode as functions of time, formed at the
    /// first time asked (`Some(false)`: a mode too near critical damping to have them); the
    /// buffers stay from step to step.
    energy: std::cell::RefCell<(Option<bool>, Vec<ModeEnergy>)>,
    /// The last σ the energies were summed to within the accepted step, and their sums.
    energy_at: std::cell::RefCell<Option<(f64, PowerIntegrals)>>,
}

/// e^{(−c/2 + i ω_d) τ} per mode at the step's own time τ of `t` (`None`: the mode's motion
/// is no damped sinusoid), and the turns e^{(−c/2 + i ω_d) dt} that carry them on by the last
/// [`TURNS`] spacings met: the ledger's Gauss–Lobatto points come at two spacings in turn.
/// Carried on, `t` is where they stand: the last anchor plus whole spacings.
struct Phasors {
    t: f64,
    at: Vec<Option<(f64, f64)>>,
    turns: Vec<(f64, Vec<Option<(f64, f64)>>)>,
}

/// Spacings whose turns the phasors keep.
const TURNS: usize = 2;

impl ExactModal {
    pub fn new(n: usize) -> Self {
        ExactModal {
            degree: 6,
            nodes: Vec::new(),
            chebyshev: Vec::new(),
            monomial: Vec::new(),
            linear: None,
            trial: StepMotion::default(),
            accepted: StepMotion::default(),
            y_new: vec![0.0; n],
            evaluated: std::cell::RefCell::new(None),
            phasors: std::cell::RefCell::new(None),
            energy: std::cell::RefCell::new((None, Vec::new())),
            energy_at: std::cell::RefCell::new(None),
        }
    }
}

fn structural(p: &dyn Dynamics) -> Result<&dyn Structure, SolveError> {
    p.second_order().ok_or(SolveError::NeedsSecondOrder)
}

impl Stepper for ExactModal {
    fn error_order(&self) -> u32 {
        self.degree as u32 + 1
    }

    fn start(
        &mut self,
        p: &dyn Dynamics,
        t0: f64,
        y0: &[f64],
        _ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        let s = structural(p)?;
        let linear = s.linear_modal().ok_or(SolveError::NotLinearModal)?;
        // A force of degree d within its pieces is fitted exactly with two degrees to spare,
        // which the error estimate reads. A run restarts at every breakpoint (each axle's
        // entry and exit): the points and weights are formed once per degree.
        if self.chebyshev.is_empty() || self.degree != linear.degree + 2 {
            self.fit_to_degree(linear.degree + 2);
        }
        self.linear = Some(linear);
        self.y_new.copy_from_slice(y0);
        self.accepted = StepMotion {
            t0,
            h: 0.0,
            ..Default::default()
        };
        self.evaluated.replace(None);
        self.phasors.replace(None);
        self.energy.borrow_mut().0 = None;
        self.energy_at.replace(None);
        Ok(())
    }

    fn attempt(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<Attempt, SolveError> {
        let s = structural(p)?;
        if let Some(g) = s.force_at_rest_over(t, h) {
            ctx.stats.rhs_evals += 1;
            return self.attempt_under(g, vec![0.0; y.len()], t, y, h, ctx);
        }
        let linear = self.linear.as_ref().ok_or(SolveError::NotLinearModal)?;
        let n = linear.stiffness.len();
        let d = self.degree;
        // The force at the Chebyshev–Lobatto points of the step, the state held at rest: what
        // remains of f is g(t).
        let zeros = vec![0.0; n];
        let mut samples = vec![vec![0.0; d + 1]; n];
        let mut f = vec![0.0; n];
        for (j, &sj) in self.nodes.iter().enumerate() {
            s.force(t + sj * h, &zeros, &zeros, &mut f);
            ctx.stats.rhs_evals += 1;
            for k in 0..n {
                samples[k][j] = f[k];
            }
        }
        let mut error = vec![0.0; 2 * n];
        let weigh = |row: &[f64], k: usize| -> f64 {
            row.iter().zip(&samples[k]).map(|(w, v)| w * v).sum()
        };
        let mut force = Vec::with_capacity(n);
        for k in 0..n {
            let dropped =
                weigh(&self.chebyshev[d], k).abs() + weigh(&self.chebyshev[d - 1], k).abs();
            let (w2, w) = (linear.stiffness[k], linear.stiffness[k].max(0.0).sqrt());
            // What the two highest coefficients move: at most their size times the static
            // (1/ω²) or the impulsive (h²/2) response, and a rate of h or 1/ω.
            error[k] = dropped * (0.5 * h * h).min(if w2 > 0.0 { 1.0 / w2 } else { f64::INFINITY });
            error[n + k] = dropped * h.min(if w > 0.0 { 1.0 / w } else { f64::INFINITY });
            force.push(self.monomial.iter().map(|row| weigh(row, k)).collect());
        }
        self.attempt_under(force, error, t, y, h, ctx)
    }

    fn y_new(&self) -> &[f64] {
        &self.y_new
    }

    fn accept(&mut self, t_new: f64) {
        let mut m = std::mem::take(&mut self.trial);
        m.h = t_new - m.t0;
        self.accepted = m;
        // No time is NaN: the buffers stay for the next step's evaluations.
        if let Some(e) = self.evaluated.borrow_mut().as_mut() {
            e.0 = f64::NAN;
        }
        self.phasors.replace(None);
        self.energy.borrow_mut().0 = None;
        self.energy_at.replace(None);
    }

    fn interpolate(&self, t: f64, out: &mut [f64]) {
        let half = self.y_new.len() / 2;
        let (x, v) = out.split_at_mut(half);
        self.at_into(t, x, &mut v[..half]);
    }

    fn interpolate_rate(&self, t: f64, out: &mut [f64]) {
        let Some(linear) = &self.linear else { return };
        // The rate's second half holds x until it is turned into the acceleration.
        let half = self.y_new.len() / 2;
        let (v, a) = out.split_at_mut(half);
        let a = &mut a[..half];
        self.at_into(t, a, v);
        let m = &self.accepted;
        let sigma = if m.h > 0.0 { (t - m.t0) / m.h } else { 0.0 };
        for (k, (ak, vk)) in a.iter_mut().zip(v.iter()).enumerate() {
            let g = m.force.get(k).map_or(0.0, |f| horner(f, sigma));
            *ak = g - linear.damping[k] * vk - linear.stiffness[k] * *ak;
        }
    }

    fn power_integrals(&self, ta: f64, tb: f64) -> Option<PowerIntegrals> {
        let linear = self.linear.as_ref()?;
        let m = &self.accepted;
        if !(m.h > 0.0) || m.motions.len() != linear.stiffness.len() {
            return None;
        }
        let mut energy = self.energy.borrow_mut();
        let (formed, modes) = &mut *energy;
        if formed.is_none() {
            modes.resize_with(m.motions.len(), ModeEnergy::default);
            let mut all = true;
            for (k, ((motion, g), mode)) in m
                .motions
                .iter()
                .zip(&m.force)
                .zip(modes.iter_mut())
                .enumerate()
            {
                let oscillator = (linear.stiffness[k], linear.damping[k]);
                all = all && mode.refill(motion, g, oscillator, m.h);
            }
            *formed = Some(all);
        }
        if *formed != Some(true) {
            return None;
        }
        let sigma = |t: f64| ((t - m.t0) / m.h).clamp(0.0, 1.0);
        let (sa, sb) = (sigma(ta), sigma(tb));
        // The ledger asks for consecutive pieces: where one starts the last ended.
        let mut last = self.energy_at.borrow_mut();
        let to_start = match *last {
            Some((s, total)) if s == sa => total,
            _ if sa > 0.0 => sum_at(modes, sa),
            _ => PowerIntegrals::default(),
        };
        let to_end = sum_at(modes, sb);
        *last = Some((sb, to_end));
        Some(PowerIntegrals {
            work: to_end.work - to_start.work,
            dissipated: to_end.dissipated - to_start.dissipated,
        })
    }

    fn forms(&self, rows: &[FormRow]) -> Option<StepForms> {
        forms::forms(&self.accepted, self.linear.as_ref()?, rows)
    }

    fn max_growth(&self) -> f64 {
        // The step is exact where the force is a polynomial: it may grow to what the problem
        // allows at once.
        1e6
    }
}

impl ExactModal {
    /// The step from (t, y) over h under the force `g` (per oscillator, its coefficients in
    /// σ), whose fit may err by what moves the state by `error`.
    fn attempt_under(
        &mut self,
        force: Vec<Vec<f64>>,
        error: Vec<f64>,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<Attempt, SolveError> {
        let linear = self.linear.as_ref().ok_or(SolveError::NotLinearModal)?;
        let n = linear.stiffness.len();
        if force.len() != n {
            return Err(SolveError::NotLinearModal);
        }
        let mut motions = Vec::with_capacity(n);
        for (k, g) in force.iter().enumerate() {
            let (w2, c) = (linear.stiffness[k], linear.damping[k]);
            let m = motion(w2, c, h, g, y[k], y[n + k]);
            let (x1, v1) = evaluate(&m, w2, c, h, 1.0);
            self.y_new[k] = x1;
            self.y_new[n + k] = v1;
            motions.push(m);
        }
        if self.y_new.iter().any(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite { t: t + h });
        }
        self.trial = StepMotion {
            t0: t,
            h,
            force,
            motions,
        };
        let err = ctx.norm(&error, y, &self.y_new);
        Ok(Attempt::Done { err })
    }

    /// The Chebyshev–Lobatto points of a fit of `degree` and the weights that turn samples at
    /// them into Chebyshev coefficients.
    fn fit_to_degree(&mut self, degree: usize) {
        self.degree = degree;
        let d = degree as f64;
        self.nodes = (0..=degree)
            .map(|j| 0.5 * (1.0 - (std::f64::consts::PI * j as f64 / d).cos()))
            .collect();
        let unit =
            |j: usize| -> Vec<f64> { (0..=degree).map(|i| f64::from(u8::from(i == j))).collect() };
        let columns: Vec<Vec<f64>> = (0..=degree)
            .map(|j| chebyshev_coefficients(&unit(j)))
            .collect();
        self.chebyshev = (0..=degree)
            .map(|i| columns.iter().map(|c| c[i]).collect())
            .collect();
        let in_sigma: Vec<Vec<f64>> = columns.iter().map(|c| monomial_in_sigma(c)).collect();
        self.monomial = (0..=degree)
            .map(|j| in_sigma.iter().map(|c| c[j]).collect())
            .collect();
    }

    /// Displacements and rates of every oscillator at t within the accepted step.
    #[cfg(test)]
    fn at(&self, t: f64) -> (Vec<f64>, Vec<f64>) {
        let half = self.y_new.len() / 2;
        let (mut x, mut v) = (vec![0.0; half], vec![0.0; half]);
        self.at_into(t, &mut x, &mut v);
        (x, v)
    }

    /// Displacements `x` and rates `v` of every oscillator at t within the accepted step.
    fn at_into(&self, t: f64, x: &mut [f64], v: &mut [f64]) {
        let m = &self.accepted;
        let n = m.motions.len();
        if n == 0 || !(m.h > 0.0) {
            let half = self.y_new.len() / 2;
            x.copy_from_slice(&self.y_new[..half]);
            v.copy_from_slice(&self.y_new[half..]);
            return;
        }
        let Some(linear) = &self.linear else {
            x.fill(0.0);
            v.fill(0.0);
            return;
        };
        if let Some((_, xe, ve)) = self.evaluated.borrow().as_ref().filter(|e| e.0 == t) {
            x.copy_from_slice(xe);
            v.copy_from_slice(ve);
            return;
        }
        let sigma = ((t - m.t0) / m.h).clamp(0.0, 1.0);
        let phasors = self.phasors_at(t, sigma * m.h);
        for k in 0..n {
            let (w2, c) = (linear.stiffness[k], linear.damping[k]);
            (x[k], v[k]) = match (&m.motions[k], phasors.at[k]) {
                (Motion::Particular { p, e0, e1 }, Some(z)) => {
                    let (x_p, v_p) = polynomial_at(p, m.h, sigma);
                    let (x_f, v_f) = free_from_phasor(w2, c, *e0, *e1, z);
                    (x_p + x_f, v_p + v_f)
                }
                (motion, _) => evaluate(motion, w2, c, m.h, sigma),
            };
        }
        self.phasors.replace(Some(phasors));
        let mut evaluated = self.evaluated.borrow_mut();
        match evaluated.as_mut() {
            Some((te, xe, ve)) => {
                *te = t;
                xe.copy_from_slice(x);
                ve.copy_from_slice(v);
            }
            None => *evaluated = Some((t, x.to_vec(), v.to_vec())),
        }
    }

    /// The phasors at t (τ = t − the step's start): carried on from the last time asked, by a
    /// spacing met before or by the turn of a new one; formed afresh at a time before it.
    fn phasors_at(&self, t: f64, tau: f64) -> Phasors {
        let Some(linear) = &self.linear else {
            return Phasors {
                t,
                at: Vec::new(),
                turns: Vec::new(),
            };
        };
        let lambda = |k: usize| -> Option<(f64, f64)> {
            let half = 0.5 * linear.damping[k];
            let kappa = half * half - linear.stiffness[k];
            let damped = matches!(self.accepted.motions[k], Motion::Particular { .. });
            (damped && kappa < 0.0).then(|| (-half, (-kappa).sqrt()))
        };
        let exp = |(a, b): (f64, f64), s: f64| {
            let (sin, cos) = (b * s).sin_cos();
            let decay = (a * s).exp();
            (decay * cos, decay * sin)
        };
        let n = self.accepted.motions.len();
        let last = self.phasors.borrow_mut().take();
        // The phasors carried on stand at their own time, p.t + dt, which drifts from the
        // sample times by their rounding: carried only while that is within a few ulps of t.
        let next = |p: &Phasors| {
            p.turns
                .iter()
                .position(|(dt, _)| (p.t + dt - t).abs() <= 8.0 * f64::EPSILON * t.abs().max(1.0))
        };
        let last = match last {
            Some(mut p) => match next(&p) {
                Some(i) => {
                    let (dt, turn) = &p.turns[i];
                    for (z, r) in p.at.iter_mut().zip(turn) {
                        if let (Some(z), Some(r)) = (z.as_mut(), r) {
                            *z = (z.0 * r.0 - z.1 * r.1, z.0 * r.1 + z.1 * r.0);
                        }
                    }
                    p.t += dt;
                    return p;
                }
                None => Some(p),
            },
            None => None,
        };
        match last {
            // Later in the step by a new spacing: its turn, kept for the next, carries the
            // phasors on too (one exponential and sinusoid per mode instead of two).
            Some(mut p) if t > p.t => {
                let dt = t - p.t;
                if p.turns.len() == TURNS {
                    p.turns.remove(0);
                }
                let turn: Vec<Option<(f64, f64)>> =
                    (0..n).map(|k| lambda(k).map(|l| exp(l, dt))).collect();
                let at =
                    p.at.iter()
                        .zip(&turn)
                        .map(|(z, r)| {
                            z.zip(*r)
                                .map(|(z, r)| (z.0 * r.0 - z.1 * r.1, z.0 * r.1 + z.1 * r.0))
                        })
                        .collect();
                p.turns.push((dt, turn));
                Phasors {
                    t,
                    at,
                    turns: p.turns,
                }
            }
            last => Phasors {
                t,
                at: (0..n).map(|k| lambda(k).map(|l| exp(l, tau))).collect(),
                turns: last.map_or_else(Vec::new, |p| p.turns),
            },
        }
    }
}

/// The Chebyshev coefficients (on [0, 1]) of the polynomial through values at the
/// Chebyshev–Lobatto points σ_j = (1 − cos(πj/d))/2.
fn chebyshev_coefficients(values: &[f64]) -> Vec<f64> {
    let d = values.len() - 1;
    (0..=d)
        .map(|i| {
            let mut sum = 0.0;
            for (j, v) in values.iter().enumerate() {
                let w = if j == 0 || j == d { 0.5 } else { 1.0 };
                // x_j = 2σ_j − 1 = −cos(πj/d); T_i(x_j) = cos(i·acos(x_j)) = (−1)^i cos(πij/d).
                let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
                sum += w * v * sign * (std::f64::consts::PI * (i * j) as f64 / d as f64).cos();
            }
            let w = if i == 0 || i == d { 0.5 } else { 1.0 };
            2.0 * w * sum / d as f64
        })
        .collect()
}

/// Σ c_i T_i(2σ − 1) as coefficients of σ^j.
fn monomial_in_sigma(cheb: &[f64]) -> Vec<f64> {
    let d = cheb.len() - 1;
    // T_i(x) as monomials in x, by T_{i+1} = 2x T_i − T_{i−1}.
    let mut t_prev = vec![0.0; d + 1];
    let mut t_cur = vec![0.0; d + 1];
    t_prev[0] = 1.0;
    let mut in_x = vec![0.0; d + 1];
    in_x[0] += cheb[0];
    if d >= 1 {
        t_cur[1] = 1.0;
        in_x[1] += cheb[1];
    }
    for c in cheb.iter().skip(2) {
        let mut next = vec![0.0; d + 1];
        for j in 0..d {
            next[j + 1] += 2.0 * t_cur[j];
        }
        for j in 0..=d {
            next[j] -= t_prev[j];
        }
        for j in 0..=d {
            in_x[j] += c * next[j];
        }
        t_prev = std::mem::replace(&mut t_cur, next);
    }
    // x = 2σ − 1: expand each x^j.
    let mut out = vec![0.0; d + 1];
    let mut power = vec![0.0; d + 1];
    power[0] = 1.0;
    for (j, &a) in in_x.iter().enumerate() {
        if j > 0 {
            let mut next = vec![0.0; d + 1];
            for i in 0..d {
                next[i + 1] += 2.0 * power[i];
                next[i] -= power[i];
            }
            next[d] -= power[d];
            power = next;
        }
        for i in 0..=d {
            out[i] += a * power[i];
        }
    }
    out
}

fn horner(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ci| acc * x + ci)
}

/// The coefficients of p(σ + shift) from those of p(σ).
fn shifted(c: &[f64], shift: f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(c.len());
    shifted_into(c, shift, &mut out);
    out
}

/// [`shifted`] into `out`.
fn shifted_into(c: &[f64], shift: f64, out: &mut Vec<f64>) {
    out.clear();
    out.extend_from_slice(c);
    let n = out.len();
    for i in 0..n {
        for j in (i..n - 1).rev() {
            out[j] += shift * out[j + 1];
        }
    }
}

/// The motion of x'' + c x' + ω² x = g(σ) over [0, h] (' in t, σ = t/h), from (x0, v0).
fn motion(w2: f64, c: f64, h: f64, g: &[f64], x0: f64, v0: f64) -> Motion {
    if x0 == 0.0 && v0 == 0.0 && g.iter().all(|&gj| gj == 0.0) {
        return Motion::Rest;
    }
    let wh = w2.max(0.0).sqrt() * h;
    let ch = c.abs() * h;
    if wh > SERIES_REACH || (wh > PARTICULAR_REACH && ch <= 1.0) {
        let p = particular(w2, c, h, g);
        let (p0, p1) = (p[0], p.get(1).copied().unwrap_or(0.0) / h);
        return Motion::Particular {
            e0: x0 - p0,
            e1: v0 - p1,
            p,
        };
    }
    let pieces = (wh.max(ch) / SERIES_REACH).ceil().max(1.0) as usize;
    let part = 1.0 / pieces as f64;
    let hp = h * part;
    let mut out = Vec::with_capacity(pieces);
    let (mut x, mut v) = (x0, v0);
    for i in 0..pieces {
        // The force in the piece's own time ς ∈ [0, 1]: σ = (i + ς)/pieces.
        let mut gi = shifted(g, i as f64 * part);
        let mut scale = 1.0;
        for coefficient in gi.iter_mut() {
            *coefficient *= scale;
            scale *= part;
        }
        let s = series(w2, c, hp, &gi, x, v);
        let (x1, v1) = series_at(&s, hp, 1.0);
        (x, v) = (x1, v1);
        out.push(s);
    }
    Motion::Series(out)
}

/// Taylor coefficients in ς = τ/hp of the solution from (x0, v0) under g(ς).
fn series(w2: f64, c: f64, hp: f64, g: &[f64], x0: f64, v0: f64) -> Vec<f64> {
    let mut s = vec![0.0; SERIES_TERMS];
    s[0] = x0;
    s[1] = v0 * hp;
    let (w2h2, ch) = (w2 * hp * hp, c * hp);
    // Past the force's terms and degree 8 each term is at most (|ch| + w2h2/9)/10 ≤ 0.58 of the
    // larger of the two before it (a piece reaches ωh, |c|h ≤ 4): once two in a row are below
    // the cut below, so is every later one, and the sum stops there.
    let reach = SERIES_REACH * SERIES_REACH;
    let free_from = if w2h2.abs() <= reach && ch * ch <= reach {
        g.len().max(8)
    } else {
        SERIES_TERMS
    };
    let mut largest = s[0].abs().max(s[1].abs());
    for k in 0..SERIES_TERMS - 2 {
        let gk = g.get(k).copied().unwrap_or(0.0) * hp * hp;
        s[k + 2] = (gk - ch * (k + 1) as f64 * s[k + 1] - w2h2 * s[k]) * SERIES_DIVISORS[k];
        largest = largest.max(s[k + 2].abs());
        if k >= free_from && s[k + 2].abs().max(s[k + 1].abs()) <= 1e-18 * largest {
            break;
        }
    }
    // The terms past the last above round-off of the largest add nothing at ς ≤ 1 (nor to the
    // rate, k ≤ SERIES_TERMS times them); every evaluation within the step sums fewer.
    let kept = s
        .iter()
        .rposition(|v| v.abs() > 1e-18 * largest)
        .map_or(1, |k| k + 1);
    s.truncate(kept);
    s
}

/// x and its rate in t at ς of a series over a piece of length hp.
fn series_at(s: &[f64], hp: f64, sigma: f64) -> (f64, f64) {
    let (x, slope) = value_and_slope(s, sigma);
    (x, slope / hp)
}

/// A polynomial's value and derivative at x, by one Horner pass for both.
fn value_and_slope(c: &[f64], x: f64) -> (f64, f64) {
    let (mut p, mut dp) = (0.0, 0.0);
    for &ci in c.iter().rev() {
        dp = dp * x + p;
        p = p * x + ci;
    }
    (p, dp)
}

/// The polynomial solution in σ of x''/h² + c x'/h + ω² x = g(σ), from the top degree down.
fn particular(w2: f64, c: f64, h: f64, g: &[f64]) -> Vec<f64> {
    let d = g.len() - 1;
    let mut a = vec![0.0; d + 1];
    for j in (0..=d).rev() {
        let mut rhs = g[j];
        if j < d {
            rhs -= c / h * (j + 1) as f64 * a[j + 1];
        }
        if j + 1 < d {
            rhs -= ((j + 2) * (j + 1)) as f64 / (h * h) * a[j + 2];
        }
        a[j] = rhs / w2;
    }
    a
}

/// x and its rate in t at σ of a motion over a step of length h.
fn evaluate(m: &Motion, w2: f64, c: f64, h: f64, sigma: f64) -> (f64, f64) {
    match m {
        Motion::Series(pieces) => {
            let count = pieces.len();
            let hp = h / count as f64;
            let at = sigma * count as f64;
            // σ ≥ 0: the cast's truncation is the floor.
            let i = (at as usize).min(count - 1);
            series_at(&pieces[i], hp, at - i as f64)
        }
        Motion::Particular { p, e0, e1 } => {
            let (x_p, v_p) = polynomial_at(p, h, sigma);
            let (x_f, v_f) = free(w2, c, *e0, *e1, sigma * h);
            (x_p + x_f, v_p + v_f)
        }
        Motion::Rest => (0.0, 0.0),
    }
}

/// A polynomial in σ and its rate in t at σ, over a step of length h.
fn polynomial_at(p: &[f64], h: f64, sigma: f64) -> (f64, f64) {
    let (x, slope) = value_and_slope(p, sigma);
    (x, slope / h)
}

/// [`free`] under-damped, from its phasor (e^{−cτ/2} cos ω_d τ, e^{−cτ/2} sin ω_d τ).
fn free_from_phasor(w2: f64, c: f64, e0: f64, e1: f64, (ec, sin): (f64, f64)) -> (f64, f64) {
    let half = 0.5 * c;
    let kappa = half * half - w2;
    let b = e1 + half * e0;
    let es = sin / (-kappa).sqrt();
    let x = e0 * ec + b * es;
    (x, -half * x + e0 * kappa * es + b * ec)
}

/// The free motion of x'' + c x' + ω² x = 0 from (e0, e1) after τ: e^{−cτ/2}(e0 C + b S),
/// b = e1 + c e0/2, with C' = κ S and S' = C, κ = c²/4 − ω² (cosines under-damped,
/// hyperbolic over-damped, and their limits between).
fn free(w2: f64, c: f64, e0: f64, e1: f64, tau: f64) -> (f64, f64) {
    let half = 0.5 * c;
    let kappa = half * half - w2;
    let b = e1 + half * e0;
    let r = kappa.abs().sqrt();
    // e^{−cτ/2} C and e^{−cτ/2} S, formed so that neither overflows over-damped.
    let (ec, es) = if r * tau < 1e-4 {
        let decay = (-half * tau).exp();
        let k2 = kappa * tau * tau;
        (
            decay * (1.0 + 0.5 * k2 + k2 * k2 / 24.0),
            decay * tau * (1.0 + k2 / 6.0 + k2 * k2 / 120.0),
        )
    } else if kappa < 0.0 {
        let decay = (-half * tau).exp();
        let (sin, cos) = (r * tau).sin_cos();
        (decay * cos, decay * sin / r)
    } else {
        let up = ((r - half) * tau).exp();
        let down = (-(r + half) * tau).exp();
        (0.5 * (up + down), 0.5 * (up - down) / r)
    };
    let x = e0 * ec + b * es;
    let v = -half * x + e0 * kappa * es + b * ec;
    (x, v)
}

/// (ω², c) of oscillators of every kind the closed forms hold: under-damped (lightly and
/// heavily), critically and over-damped, undamped, and a free mass; and the steps they are
/// taken over.
#[cfg(test)]
const TEST_MODES: [(f64, f64); 6] = [
    (1.0, 0.0),
    (100.0, 0.4),
    (1.0e4, 200.0),
    (1.0e4, 500.0),
    (0.0, 0.0),
    (4.0e6, 10.0),
];
#[cfg(test)]
const TEST_STEPS: [f64; 5] = [1e-3, 0.01, 0.1, 1.0, 3.0];

#[cfg(test)]
mod tests {
    use super::*;

    /// x'' + c x' + ω² x = g for a polynomial g, against the equation itself: the residual of
    /// the motion, by finite differences of its own closed form, and its start.
    fn check_motion(w2: f64, c: f64, h: f64, g: &[f64]) {
        let (x0, v0) = (0.3, -1.7);
        let m = motion(w2, c, h, g, x0, v0);
        let (xs, vs) = evaluate(&m, w2, c, h, 0.0);
        assert!((xs - x0).abs() < 1e-12 && (vs - v0).abs() < 1e-10 * (1.0 + v0.abs()));
        for &sigma in &[0.1, 0.37, 0.5, 0.83, 0.99] {
            // Short against the step and the period, so that the difference is the derivative.
            let dt = (1e-5 * h).min(1e-4 / w2.sqrt().max(1.0));
            let ds = dt / h;
            let (x, v) = evaluate(&m, w2, c, h, sigma);
            let (_, vp) = evaluate(&m, w2, c, h, sigma + ds);
            let (_, vm) = evaluate(&m, w2, c, h, sigma - ds);
            let a = (vp - vm) / (2.0 * dt);
            let residual = a + c * v + w2 * x - horner(g, sigma);
            let size = horner(g, sigma).abs() + w2 * x.abs() + c * v.abs() + 1.0;
            assert!(
                residual.abs() < 1e-5 * size,
                "ω² {w2}, c {c}, h {h}, σ {sigma}: residual {residual:e} of {size:e}"
            );
        }
    }

    /// A step sampled at equal spacing, or at two spacings in turn as the ledger samples it,
    /// carries the free responses' phasors on by products: the same displacements and rates as
    /// formed afresh (a thousand samples each; under-, over-damped and series modes side by
    /// side), within 10⁻¹¹ of each mode's largest: the sample times themselves are known to an ulp of t, which moves a
    /// phase by ω ulp(t) ≈ 10⁻¹³ here, either way.
    #[test]
    fn phasors_carried_on_give_the_motion_formed_afresh() {
        let modes = [(1.0e6, 20.0), (4.0e4, 1.0), (1.0e4, 500.0), (1.0, 0.1)];
        let (t0, h) = (2.0, 0.05);
        let g = [1.0, -2.0, 0.5, 3.0];
        let mut stepper = ExactModal::new(2 * modes.len());
        stepper.linear = Some(LinearModal {
            stiffness: modes.iter().map(|m| m.0).collect(),
            damping: modes.iter().map(|m| m.1).collect(),
            degree: 3,
        });
        stepper.accepted = StepMotion {
            t0,
            h,
            force: vec![g.to_vec(); modes.len()],
            motions: modes
                .iter()
                .map(|&(w2, c)| motion(w2, c, h, &g, 0.3, -1.7))
                .collect(),
        };
        // Equal spacing, and the ledger's: Gauss–Lobatto points of equal pieces, two spacings
        // in turn.
        let lobatto = [0.172_673_164_646_011_43, 0.5, 0.827_326_835_353_988_6, 1.0];
        let times: Vec<f64> = (0..=1000)
            .map(|i| t0 + h * i as f64 / 1000.0)
            .chain((0..250).flat_map(|i| lobatto.map(|x| t0 + h * (i as f64 + x) / 250.0)))
            .collect();
        let carried: Vec<(Vec<f64>, Vec<f64>)> = times.iter().map(|&t| stepper.at(t)).collect();
        assert!(stepper
            .phasors
            .borrow()
            .as_ref()
            .is_some_and(|p| !p.turns.is_empty()));
        for (k, &(w2, c)) in modes.iter().enumerate() {
            let afresh: Vec<(f64, f64)> = times
                .iter()
                .map(|&t| evaluate(&stepper.accepted.motions[k], w2, c, h, (t - t0) / h))
                .collect();
            let largest = |f: fn(&(f64, f64)) -> f64| afresh.iter().map(f).fold(0.0, f64::max);
            let (xs, vs) = (largest(|e| e.0.abs()), largest(|e| e.1.abs()));
            for ((x, v), (xe, ve)) in carried.iter().map(|(x, v)| (x[k], v[k])).zip(&afresh) {
                assert!((x - xe).abs() <= 1e-11 * xs, "mode {k}: x {x} against {xe}");
                assert!((v - ve).abs() <= 1e-11 * vs, "mode {k}: v {v} against {ve}");
            }
        }
    }

    /// Series and particular forms, under-, critically and over-damped, and a free mass.
    #[test]
    fn motions_satisfy_their_equation() {
        let g = [1.0, -2.0, 0.5, 3.0, -1.0];
        for &(w2, c) in &TEST_MODES {
            for &h in &TEST_STEPS {
                check_motion(w2, c, h, &g);
            }
        }
    }

    /// The polynomial through Chebyshev–Lobatto samples of a polynomial is that polynomial.
    #[test]
    fn a_polynomial_is_fitted_exactly() {
        let p = [0.5, -1.0, 2.0, 0.25, -3.0];
        let d = 6;
        let values: Vec<f64> = (0..=d)
            .map(|j| {
                horner(
                    &p,
                    0.5 * (1.0 - (std::f64::consts::PI * j as f64 / d as f64).cos()),
                )
            })
            .collect();
        let cheb = chebyshev_coefficients(&values);
        assert!(cheb[5].abs() < 1e-13 && cheb[6].abs() < 1e-13, "{cheb:?}");
        let back = monomial_in_sigma(&cheb);
        for (a, b) in back.iter().zip(p.iter().chain([0.0, 0.0].iter())) {
            assert!((a - b).abs() < 1e-12, "{back:?}");
        }
    }
}

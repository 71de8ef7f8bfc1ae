//! Structural systems M q'' = f(t, q), with f = F_ext(t) − F_int(q) and K = −∂f/∂q, and the
//! two ways to integrate them: as a first-order system y = (q, v) through [`FirstOrder`] (any
//! integrator of this module), or directly by generalized-α (Chung & Hulbert 1993) with the
//! spectral radius at infinity ρ∞ as its setting (ρ∞ = 1: the trapezoidal rule, energy-neutral
//! for linear systems; smaller values damp the unresolved high modes).

use std::borrow::Cow;
use std::ops::Range;
use std::time::Instant;

use super::{EventHit, EventSpec, Observer, Options, Outcome, Problem, SolveError, Stats};
use crate::linalg::{self, Assembly, Combination, LowRank, Sparse, SparseLu, Woodbury};

pub trait SecondOrderProblem {
    fn dim(&self) -> usize;
    /// M(t, q): constant for a bare beam, state-dependent once a body rides on it.
    fn mass(&self, t: f64, q: &[f64]) -> Cow<'_, Sparse>;
    /// A constant mass is factorised into the iteration matrix once per step size.
    fn mass_is_constant(&self) -> bool {
        true
    }
    /// M(t, q) = B + Σ_k w_k g_k g_kᵀ with B constant and a few sparse rows g_k, where the
    /// mass has that form (a body riding on a structure): B, and the (w_k, g_k) at (t, q).
    /// Generalized-α then factorises its iteration matrix from B alone, once per step size,
    /// and adds the rest exactly at every step by the Woodbury identity.
    fn mass_split(&self, _t: f64, _q: &[f64]) -> Option<(&Sparse, LowRank)> {
        None
    }
    /// out = M(t, q) a, without assembling M where the problem can avoid it.
    fn mass_mul(&self, t: f64, q: &[f64], a: &[f64], out: &mut [f64]) {
        linalg::mul(&self.mass(t, q), a, out);
    }
    /// f(t, q, v) = F_ext(t) − F_int(q) − (forces quadratic in the velocities).
    fn force(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]);
    /// K(q) = −∂f/∂q, the tangent stiffness (the part that matters for Newton's convergence).
    fn stiffness(&self, t: f64, q: &[f64]) -> Sparse;
    /// The longest step allowed from (t, q, v); see [`Problem::max_step`].
    fn max_step(&self, _t: f64, _q: &[f64], _v: &[f64]) -> f64 {
        f64::INFINITY
    }
    /// Blocks of unknowns of one kind (beam displacements, the contact coordinate): each is
    /// measured against its own largest value in the error norm.
    fn norm_groups(&self) -> Vec<Range<usize>> {
        vec![0..self.dim()]
    }
    fn breakpoints(&self) -> Vec<f64> {
        Vec::new()
    }
    fn enter_segment(&self, _start: f64, _end: f64) {}
    fn events(&self) -> &[EventSpec] {
        &[]
    }
    /// g(t, q, v); the run is watched for g passing from ≥ 0 to < 0.
    fn event(&self, _index: usize, _t: f64, _q: &[f64], _v: &[f64]) -> f64 {
        1.0
    }
}

/// y = (q, v): q' = v, M(q) v' = f(t, q, v). Mass diag(I, M), Jacobian [[0, I], [−K, 0]].
pub struct FirstOrder<'a> {
    pub inner: &'a dyn SecondOrderProblem,
}

impl<'a> FirstOrder<'a> {
    pub fn new(inner: &'a dyn SecondOrderProblem) -> Self {
        FirstOrder { inner }
    }
}

impl Problem for FirstOrder<'_> {
    fn dim(&self) -> usize {
        2 * self.inner.dim()
    }
    fn rhs(&self, t: f64, y: &[f64], f: &mut [f64]) {
        let n = self.inner.dim();
        f[..n].copy_from_slice(&y[n..]);
        self.inner.force(t, &y[..n], &y[n..], &mut f[n..]);
    }
    fn mass(&self, t: f64, y: &[f64]) -> Option<Sparse> {
        let n = self.inner.dim();
        let mut a = Assembly::new(2 * n);
        (0..n).for_each(|i| a.add(i, i, 1.0));
        a.add_sparse(&self.inner.mass(t, &y[..n]), 1.0, n, n);
        Some(a.build())
    }
    fn mass_is_constant(&self) -> bool {
        self.inner.mass_is_constant()
    }
    fn jacobian(&self, t: f64, y: &[f64]) -> Option<Sparse> {
        let n = self.inner.dim();
        let mut a = Assembly::new(2 * n);
        (0..n).for_each(|i| a.add(i, n + i, 1.0));
        a.add_sparse(&self.inner.stiffness(t, &y[..n]), -1.0, n, 0);
        Some(a.build())
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.inner.breakpoints()
    }
    fn enter_segment(&self, start: f64, end: f64) {
        self.inner.enter_segment(start, end)
    }
    fn events(&self) -> &[EventSpec] {
        self.inner.events()
    }
    fn event(&self, index: usize, t: f64, y: &[f64]) -> f64 {
        let n = self.inner.dim();
        self.inner.event(index, t, &y[..n], &y[n..])
    }
    fn max_step(&self, t: f64, y: &[f64]) -> f64 {
        let n = self.inner.dim();
        self.inner.max_step(t, &y[..n], &y[n..])
    }
    /// The structure's groups, once for the displacements and once for the velocities.
    fn norm_groups(&self) -> Option<Vec<Range<usize>>> {
        let n = self.inner.dim();
        let q = self.inner.norm_groups();
        let v = q.iter().map(|g| g.start + n..g.end + n);
        Some(q.iter().cloned().chain(v).collect())
    }
}

/// Chung–Hulbert parameters for a given ρ∞ ∈ [0, 1].
#[derive(Clone, Copy, Debug)]
pub struct GenAlpha {
    pub alpha_m: f64,
    pub alpha_f: f64,
    pub beta: f64,
    pub gamma: f64,
}

impl GenAlpha {
    pub fn new(rho_inf: f64) -> Self {
        let alpha_m = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
        let alpha_f = rho_inf / (rho_inf + 1.0);
        let gamma = 0.5 - alpha_m + alpha_f;
        GenAlpha {
            alpha_m,
            alpha_f,
            beta: 0.25 * (1.0 - alpha_m + alpha_f).powi(2),
            gamma,
        }
    }
}

const MAX_NEWTON: usize = 10;
const NEWTON_KAPPA: f64 = 0.01;

struct State {
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    /// f(t, q, v) at this state, on the side of the current segment.
    f: Vec<f64>,
}

struct Ga<'a> {
    p: &'a dyn SecondOrderProblem,
    c: GenAlpha,
    rtol: f64,
    atol: f64,
    groups: Vec<Range<usize>>,
    stats: Stats,
    /// Factorised (1 − α_m) M + (1 − α_f) β h² K and the h it was built for; with a split
    /// mass, M is its constant part B.
    iteration: Option<(f64, SparseLu)>,
    /// With a split mass: its low-rank part at the step's start, added by Woodbury.
    woodbury: Option<Woodbury>,
    /// The tangent stiffness the iteration matrix is built from, kept until Newton stalls.
    k: Option<Sparse>,
    /// (1 − α_m) M + c K on their joint pattern, for the current K (and M, if it is constant).
    combination: Option<Combination>,
    k_fresh: bool,
}

impl Ga<'_> {
    /// Per group, max |e_i| / (atol + rtol max_j |q_j|): relative to the largest displacement
    /// of the group, not to each component, so that the tiny, unresolvable motion of the
    /// mesh-scale modes a sudden load excites does not dictate the step.
    fn norm(&self, e: &[f64], q: &[f64]) -> f64 {
        self.groups
            .iter()
            .map(|g| {
                let size = q[g.clone()].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                let sc = self.atol + self.rtol * size;
                e[g.clone()].iter().fold(0.0_f64, |m, v| m.max(v.abs())) / sc
            })
            .fold(0.0, |m, x| if x.is_nan() { f64::NAN } else { m.max(x) })
    }

    fn acceleration(&mut self, s: &mut State) -> Result<(), SolveError> {
        self.stats.rhs_evals += 1;
        self.p.force(s.t, &s.q, &s.v, &mut s.f);
        s.a.copy_from_slice(&s.f);
        self.stats.factorizations += 1;
        SparseLu::factor(&self.p.mass(s.t, &s.q), None)
            .ok_or(SolveError::SingularMatrix { t: s.t })?
            .solve_in_place(&mut s.a);
        Ok(())
    }

    fn factor(&mut self, t: f64, q: &[f64], h: f64) -> Result<(), SolveError> {
        let split = self.p.mass_split(t, q);
        self.factor_base(t, q, h, split.as_ref().map(|(b, _)| *b))?;
        self.woodbury = match split {
            Some((_, terms)) => {
                let (_, lu) = self.iteration.as_ref().expect("factorised above");
                let scaled = terms
                    .into_iter()
                    .map(|(w, g)| ((1.0 - self.c.alpha_m) * w, g))
                    .collect();
                Some(Woodbury::new(lu, scaled).ok_or(SolveError::SingularMatrix { t })?)
            }
            None => None,
        };
        Ok(())
    }

    /// x ← S⁻¹ x for the iteration matrix S.
    fn solve(&self, x: &mut [f64]) {
        let (_, lu) = self.iteration.as_ref().expect("factorised");
        match &self.woodbury {
            Some(w) => w.solve_in_place(lu, x),
            None => lu.solve_in_place(x),
        }
    }

    /// The factorised iteration matrix, or with a split mass its part from the constant B.
    fn factor_base(
        &mut self,
        t: f64,
        q: &[f64],
        h: f64,
        split: Option<&Sparse>,
    ) -> Result<(), SolveError> {
        let constant = self.p.mass_is_constant() || split.is_some();
        let fresh_k_due = self.k.is_none();
        if !fresh_k_due && matches!(self.iteration, Some((hh, _)) if hh == h) {
            return Ok(());
        }
        if fresh_k_due {
            self.k = Some(self.p.stiffness(t, q));
            self.stats.jacobians += 1;
            self.k_fresh = true;
            let k = self.k.as_ref().expect("built above");
            if !self.combination.as_mut().is_some_and(|c| c.update_b(k)) {
                self.combination = None;
            }
        }
        if self.combination.is_none() || !constant {
            let mut m = match split {
                Some(b) => b.clone(),
                None => self.p.mass(t, q).into_owned(),
            };
            m.val_mut()
                .iter_mut()
                .for_each(|v| *v *= 1.0 - self.c.alpha_m);
            let same = self.combination.as_mut().is_some_and(|c| c.update_a(&m));
            if !same {
                let k = self.k.as_ref().expect("built above");
                self.combination = Some(Combination::new(&m, k));
            }
        }
        let c = (1.0 - self.c.alpha_f) * self.c.beta * h * h;
        let s = self.combination.as_mut().expect("built above").at(c);
        self.stats.factorizations += 1;
        let previous = self.iteration.take().map(|(_, lu)| lu);
        self.iteration = Some((
            h,
            SparseLu::factor(s, previous).ok_or(SolveError::SingularMatrix { t })?,
        ));
        Ok(())
    }

    /// One step of size h; `None` when Newton does not converge.
    fn step(&mut self, s: &State, h: f64) -> Result<Option<(State, f64)>, SolveError> {
        let n = s.q.len();
        let c = self.c;
        let t1 = s.t + h;
        self.factor(s.t, &s.q, h)?;
        let mut a1 = s.a.clone();
        let mut q1 = vec![0.0; n];
        let mut v1 = vec![0.0; n];
        let mut f1 = vec![0.0; n];
        let mut r = vec![0.0; n];
        let mut ma = vec![0.0; n];
        let mut ma0 = vec![0.0; n];
        self.p.mass_mul(s.t, &s.q, &s.a, &mut ma0);
        let advance = |a1: &[f64], q1: &mut [f64], v1: &mut [f64]| {
            for i in 0..n {
                q1[i] = s.q[i] + h * s.v[i] + h * h * ((0.5 - c.beta) * s.a[i] + c.beta * a1[i]);
                v1[i] = s.v[i] + h * ((1.0 - c.gamma) * s.a[i] + c.gamma * a1[i]);
            }
        };
        let mut prev: Option<f64> = None;
        let mut converged = false;
        for _ in 0..MAX_NEWTON {
            self.stats.newton_iterations += 1;
            advance(&a1, &mut q1, &mut v1);
            self.stats.rhs_evals += 1;
            self.p.force(t1, &q1, &v1, &mut f1);
            self.p.mass_mul(t1, &q1, &a1, &mut ma);
            for i in 0..n {
                r[i] = -((1.0 - c.alpha_m) * ma[i] + c.alpha_m * ma0[i]
                    - (1.0 - c.alpha_f) * f1[i]
                    - c.alpha_f * s.f[i]);
            }
            self.solve(&mut r);
            for i in 0..n {
                a1[i] += r[i];
            }
            let dq: Vec<f64> = r.iter().map(|d| c.beta * h * h * d).collect();
            let norm = self.norm(&dq, &q1);
            if !norm.is_finite() {
                break;
            }
            if let Some(prev) = prev {
                if norm / prev >= 0.9 {
                    break;
                }
            }
            if norm <= NEWTON_KAPPA {
                converged = true;
                break;
            }
            prev = Some(norm);
        }
        if !converged {
            return Ok(None);
        }
        advance(&a1, &mut q1, &mut v1);
        self.stats.rhs_evals += 1;
        self.p.force(t1, &q1, &v1, &mut f1);
        // Local error of the displacement (Zienkiewicz & Xie 1991): h² (β − 1/6)(a_{n+1} − a_n),
        // filtered through the iteration matrix as Hairer & Wanner filter stiff estimates: a mode
        // with ωh ≫ 1 is divided by about β(ωh)², which brings its estimate down to its own
        // (tiny) amplitude, while resolved modes pass unchanged.
        let raw: Vec<f64> = (0..n)
            .map(|i| (1.0 - c.alpha_m) * h * h * (c.beta - 1.0 / 6.0) * (a1[i] - s.a[i]))
            .collect();
        let mut e = vec![0.0; n];
        self.p.mass_mul(t1, &q1, &raw, &mut e);
        self.solve(&mut e);
        let err = self.norm(&e, &q1);
        Ok(Some((
            State {
                t: t1,
                q: q1,
                v: v1,
                a: a1,
                f: f1,
            },
            err,
        )))
    }
}

/// Cubic Hermite on (q, v) and on (v, a) between two states.
fn interpolate(s0: &State, s1: &State, t: f64, out: &mut [f64]) {
    let n = s0.q.len();
    let h = s1.t - s0.t;
    let th = (t - s0.t) / h;
    let h00 = (1.0 + 2.0 * th) * (1.0 - th).powi(2);
    let h10 = th * (1.0 - th).powi(2);
    let h01 = th * th * (3.0 - 2.0 * th);
    let h11 = th * th * (th - 1.0);
    for i in 0..n {
        out[i] = h00 * s0.q[i] + h * h10 * s0.v[i] + h01 * s1.q[i] + h * h11 * s1.v[i];
        out[n + i] = h00 * s0.v[i] + h * h10 * s0.a[i] + h01 * s1.v[i] + h * h11 * s1.a[i];
    }
}

/// Generalized-α from (q0, v0) at t0 to t_end; the observer sees y = (q, v). A terminal event
/// of the problem ends the run where it is located.
#[allow(clippy::too_many_arguments)]
pub fn solve_genalpha(
    p: &dyn SecondOrderProblem,
    rho_inf: f64,
    t0: f64,
    q0: &[f64],
    v0: &[f64],
    t_end: f64,
    outputs: &[f64],
    opts: &Options,
    observer: &mut dyn Observer,
) -> Result<Outcome, SolveError> {
    let clock = Instant::now();
    let n = p.dim();
    let mut ga = Ga {
        p,
        c: GenAlpha::new(rho_inf),
        rtol: opts.rtol,
        atol: opts.atol,
        groups: p.norm_groups(),
        stats: Stats::default(),
        iteration: None,
        k: None,
        combination: None,
        k_fresh: false,
        woodbury: None,
    };
    let specs = p.events();
    let breaks = super::breakpoints_within(p.breakpoints(), t0, t_end);
    let segment_end = |t: f64| breaks.iter().copied().find(|&b| b > t).unwrap_or(t_end);
    p.enter_segment(t0, segment_end(t0));
    let mut s = State {
        t: t0,
        q: q0.to_vec(),
        v: v0.to_vec(),
        a: vec![0.0; n],
        f: vec![0.0; n],
    };
    ga.acceleration(&mut s)?;
    let mut y = vec![0.0; 2 * n];
    let mut next_out = outputs.partition_point(|&o| o < t0);
    let emit = |st: &State, y: &mut [f64]| {
        y[..n].copy_from_slice(&st.q);
        y[n..].copy_from_slice(&st.v);
    };
    while next_out < outputs.len() && outputs[next_out] <= t0 {
        emit(&s, &mut y);
        observer.output(t0, &y);
        next_out += 1;
    }
    let mut events = Vec::new();
    let finish = |t: f64, y: Vec<f64>, mut stats: Stats, stopped_by, events| {
        stats.wall_s = clock.elapsed().as_secs_f64();
        Ok(Outcome {
            t,
            y,
            stats,
            stopped_by,
            events,
        })
    };
    let mut g: Vec<f64> = (0..specs.len())
        .map(|i| p.event(i, t0, &s.q, &s.v))
        .collect();
    if let Some(i) = (0..specs.len()).find(|&i| specs[i].terminal && g[i] < 0.0) {
        emit(&s, &mut y);
        let hit = EventHit {
            index: i,
            name: specs[i].name,
            t: t0,
        };
        return finish(t0, y, ga.stats, Some(hit), events);
    }
    let h_min = 1e-14 * t_end.abs().max(1.0);
    let mut h = opts.fixed_step.unwrap_or_else(|| {
        // Start from the step that keeps the first displacement increment h²|a|/2 on tolerance.
        let amax =
            s.a.iter()
                .zip(&s.q)
                .map(|(a, q)| a.abs() / (ga.atol + ga.rtol * q.abs()))
                .fold(0.0, f64::max);
        if amax > 0.0 {
            (2.0 / amax).sqrt().min(1e-2 * (t_end - t0))
        } else {
            1e-3 * (t_end - t0)
        }
    });
    let mut just_rejected = false;
    while s.t < t_end {
        if ga.stats.steps >= opts.max_steps {
            return Err(SolveError::TooManySteps {
                t: s.t,
                steps: ga.stats.steps,
            });
        }
        if opts.fixed_step.is_none() {
            h = h.min(p.max_step(s.t, &s.q, &s.v));
        }
        let target = segment_end(s.t + h_min);
        let last = s.t + h >= target - h_min;
        let h_try = if last { target - s.t } else { h };
        let Some((mut s1, err)) = ga.step(&s, h_try)? else {
            if !ga.k_fresh {
                // A fresh tangent; the factorisation keeps its symbolic analysis.
                ga.k = None;
                continue;
            }
            if opts.fixed_step.is_some() {
                return Err(SolveError::NewtonFailed { t: s.t });
            }
            ga.stats.rejected += 1;
            h = h_try * 0.25;
            if h < h_min {
                return Err(SolveError::NewtonFailed { t: s.t });
            }
            continue;
        };
        if opts.fixed_step.is_none() && !(err <= 1.0) {
            ga.stats.rejected += 1;
            just_rejected = true;
            h = h_try
                * if err.is_finite() {
                    (0.9 * err.powf(-1.0 / 3.0)).clamp(0.2, 1.0)
                } else {
                    0.2
                };
            if h < h_min {
                return Err(SolveError::StepSizeUnderflow { t: s.t, h });
            }
            continue;
        }
        if s1.q.iter().chain(&s1.v).any(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite { t: s1.t });
        }
        if last {
            s1.t = target;
        }
        ga.stats.steps += 1;
        ga.k_fresh = false;

        // Earliest terminal sign change in this step, located on the Hermite interpolant.
        let g_new: Vec<f64> = (0..specs.len())
            .map(|i| p.event(i, s1.t, &s1.q, &s1.v))
            .collect();
        let first = super::crossings(specs, &g, &g_new, s.t, s1.t, &mut events, |i, tt| {
            interpolate(&s, &s1, tt, &mut y);
            p.event(i, tt, &y[..n], &y[n..])
        });
        let t_stop = first.map_or(s1.t, |(_, te)| te);
        while next_out < outputs.len() && outputs[next_out] <= t_stop {
            interpolate(&s, &s1, outputs[next_out], &mut y);
            observer.output(outputs[next_out], &y);
            next_out += 1;
        }
        if let Some((i, te)) = first {
            interpolate(&s, &s1, te, &mut y);
            observer.step(te, &y);
            let hit = EventHit {
                index: i,
                name: specs[i].name,
                t: te,
            };
            return finish(te, y, ga.stats, Some(hit), events);
        }
        g = g_new;
        emit(&s1, &mut y);
        observer.step(s1.t, &y);
        if last && target < t_end {
            // The load jumps here: restart with the acceleration of the new segment.
            p.enter_segment(target, segment_end(target));
            ga.acceleration(&mut s1)?;
        }
        s = s1;
        if opts.fixed_step.is_none() {
            let grow = if just_rejected { 1.0 } else { 2.0 };
            let h_new = h_try * (0.9 * err.max(1e-10).powf(-1.0 / 3.0)).clamp(0.2, grow);
            // Keep h (and the factorised iteration matrix) unless it should grow by half.
            h = if (1.0..=1.5).contains(&(h_new / h_try)) {
                h_try
            } else {
                h_new
            };
            just_rejected = false;
        }
    }
    emit(&s, &mut y);
    finish(s.t, y, ga.stats, None, events)
}

//! Generalized-α (Chung & Hulbert 1993) as a stepper of the one driver, for problems that are
//! structural ([`Dynamics::second_order`]): it steps M q'' = f(t, q, v) directly, with the
//! spectral radius at infinity ρ∞ as its setting (ρ∞ = 1: the trapezoidal rule,
//! energy-neutral for linear systems; smaller values damp the unresolved high modes). The
//! driver sees y = (q, v) like every other method's.
//!
//! It is written in Arnold and Brüls' form (2007): the equation of motion holds at the step's
//! end, M(q₁) q''₁ = f(t₁, q₁, v₁), and the Newmark updates advance with a pseudo-acceleration
//! a, (1 − α_m) a₁ + α_m a₀ = (1 − α_f) q''₁ + α_f q''₀. For a constant mass this is Chung and
//! Hulbert's method step for step. Their own form balances (1 − α_m) M a₁ + α_m M a₀ against
//! the forces; its a belongs to the time t + (α_m − α_f) h, so where the mass varies (a disk
//! or an axle crossing the beam) it leaves (α_f − α_m) h Ṁ q'' in every step and the method
//! falls to first order for ρ∞ < 1 (measured on D44 with 0.5 % damping: the midspan peak
//! settled by ×2.3 per tenfold cut of rtol instead of ×4.6).

use super::second_order::Structure;
use super::{Attempt, Ctx, Dynamics, SolveError, StepEnds, Stepper};
use crate::linalg::{Assembly, Combination, Sparse, SparseLu, Woodbury};

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

/// q, v, the pseudo-acceleration a and the acceleration q'' at one time, q'' on the side of
/// the current segment.
#[derive(Default)]
struct State {
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    acc: Vec<f64>,
}

impl State {
    fn zeros(n: usize) -> Self {
        State {
            q: vec![0.0; n],
            v: vec![0.0; n],
            a: vec![0.0; n],
            acc: vec![0.0; n],
        }
    }
}

/// The vectors one step works in, kept from step to step: the pseudo-acceleration's carried
/// part, f(t₁, q₁, v₁), M q''₁, the residual (then the error), and the displacement
/// correction (then the raw error).
#[derive(Default)]
struct Work {
    carried: Vec<f64>,
    f: Vec<f64>,
    ma: Vec<f64>,
    r: Vec<f64>,
    dq: Vec<f64>,
}

impl Work {
    fn zeros(n: usize) -> Self {
        Work {
            carried: vec![0.0; n],
            f: vec![0.0; n],
            ma: vec![0.0; n],
            r: vec![0.0; n],
            dq: vec![0.0; n],
        }
    }
}

pub(crate) struct GenAlphaStepper {
    c: GenAlpha,
    /// The structure's norm groups: the error is a displacement error, measured per group
    /// against the group's largest displacement.
    groups: Vec<std::ops::Range<usize>>,
    /// The structure's norm weights (see `Structure::norm_weights`).
    weights: Option<Vec<f64>>,
    /// The structure's norm rows (see `Structure::norm_rows`).
    rows: Option<super::NormRows>,
    /// Factorised (1 − α_m) M + (1 − α_f) β h² K and the h it was built for; with a split
    /// mass, M is its constant part B.
    iteration: Option<(f64, SparseLu)>,
    /// With a split mass: its low-rank part at the step's start, added by Woodbury.
    woodbury: Option<Woodbury>,
    /// The tangent stiffness the iteration matrix is built from, kept until Newton stalls.
    k: Option<Sparse>,
    /// K, or K + γ/(β h) C for a damped structure: the operand the combination scales by
    /// (1 − α_f) β h².
    operand: Option<Sparse>,
    /// (1 − α_m) M + c K on their joint pattern, for the current K (and M, if it is constant).
    combination: Option<Combination>,
    k_fresh: bool,
    /// The step start and the candidate of the last attempt.
    now: State,
    next: State,
    work: Work,
    /// (q, v) of the candidate, and the dense output of the last accepted step: y = (q, v)
    /// with y' = (v, a), so its cubic Hermite is the one every one-step method here uses.
    y_new: Vec<f64>,
    /// y' = (v, a) of the accepted candidate.
    yp_new: Vec<f64>,
    ends: StepEnds,
    t_try: f64,
}

fn structural(p: &dyn Dynamics) -> Result<&dyn Structure, SolveError> {
    p.second_order().ok_or(SolveError::NeedsSecondOrder)
}

impl GenAlphaStepper {
    /// A stepper for a first-order view of dimension `n` = 2 × the structure's.
    pub fn new(rho_inf: f64, n: usize) -> Self {
        let nq = n / 2;
        GenAlphaStepper {
            c: GenAlpha::new(rho_inf),
            groups: Vec::new(),
            weights: None,
            rows: None,
            iteration: None,
            woodbury: None,
            k: None,
            operand: None,
            combination: None,
            k_fresh: false,
            now: State::zeros(nq),
            next: State::zeros(nq),
            work: Work::zeros(nq),
            y_new: vec![0.0; n],
            yp_new: vec![0.0; n],
            ends: StepEnds::new(n),
            t_try: 0.0,
        }
    }

    fn acceleration(
        p: &dyn Structure,
        t: f64,
        s: &mut State,
        ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        ctx.stats.rhs_evals += 1;
        p.force(t, &s.q, &s.v, &mut s.acc);
        ctx.stats.factorizations += 1;
        SparseLu::factor(&p.mass(t, &s.q), None)
            .ok_or(SolveError::SingularMatrix { t })?
            .solve_in_place(&mut s.acc);
        // The pseudo-acceleration starts as the acceleration: its O(h) offset from the shifted
        // time decays at the rate ρ∞ sets, and q, v keep second order (the test on a mass
        // varying in time measures it).
        s.a.copy_from_slice(&s.acc);
        Ok(())
    }

    /// The norm over the unknowns, which Newton's corrections are measured by.
    fn norm(&self, ctx: &Ctx, e: &[f64], q: &[f64]) -> f64 {
        super::grouped_norm(
            &self.groups,
            self.weights.as_deref(),
            ctx.atol,
            ctx.rtol,
            e,
            q,
            q,
        )
    }

    /// The step's error: over the unknowns and the structure's rows.
    fn error_norm(&self, ctx: &Ctx, e: &[f64], q: &[f64]) -> f64 {
        let unknowns = self.norm(ctx, e, q);
        match &self.rows {
            Some(rows) if !unknowns.is_nan() => {
                unknowns.max(rows.norm(ctx.atol, ctx.rtol, e, q, q))
            }
            _ => unknowns,
        }
    }

    fn factor(
        &mut self,
        p: &dyn Structure,
        t: f64,
        q: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        let split = p.mass_split(t, q);
        self.factor_base(p, t, q, h, split.as_ref().map(|(b, _)| *b), ctx)?;
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
        p: &dyn Structure,
        t: f64,
        q: &[f64],
        h: f64,
        split: Option<&Sparse>,
        ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        let constant = p.mass_is_constant() || split.is_some();
        let fresh_k_due = self.k.is_none();
        if !fresh_k_due && matches!(self.iteration, Some((hh, _)) if hh == h) {
            return Ok(());
        }
        if fresh_k_due {
            self.k = Some(p.stiffness(t, q));
            ctx.stats.jacobians += 1;
            self.k_fresh = true;
        }
        // Damping enters as (1 − α_f) γ h C beside (1 − α_f) β h² K: folded into the stiffness
        // operand as K + γ/(β h) C, which changes with h.
        let damping = p.damping();
        if fresh_k_due || damping.is_some() {
            let k = self.k.as_ref().expect("built above");
            let operand = match &damping {
                None => k.clone(),
                Some(c) => {
                    let mut a = Assembly::new(k.nrows());
                    a.add_sparse(k, 1.0, 0, 0);
                    a.add_sparse(c, self.c.gamma / (self.c.beta * h), 0, 0);
                    a.build()
                }
            };
            if !self
                .combination
                .as_mut()
                .is_some_and(|c| c.update_b(&operand))
            {
                self.combination = None;
            }
            self.operand = Some(operand);
        }
        if self.combination.is_none() || !constant {
            let mut m = match split {
                Some(b) => b.clone(),
                None => p.mass(t, q).into_owned(),
            };
            m.val_mut()
                .iter_mut()
                .for_each(|v| *v *= 1.0 - self.c.alpha_m);
            let same = self.combination.as_mut().is_some_and(|c| c.update_a(&m));
            if !same {
                let operand = self.operand.as_ref().expect("built above");
                self.combination = Some(Combination::new(&m, operand));
            }
        }
        let c = (1.0 - self.c.alpha_f) * self.c.beta * h * h;
        let s = self.combination.as_mut().expect("built above").at(c);
        ctx.stats.factorizations += 1;
        let previous = self.iteration.take().map(|(_, lu)| lu);
        self.iteration = Some((
            h,
            SparseLu::factor(s, previous).ok_or(SolveError::SingularMatrix { t })?,
        ));
        Ok(())
    }

    /// One step of size h from `now` into `next`; the error estimate, or `None` when Newton
    /// does not converge.
    fn step(
        &mut self,
        p: &dyn Structure,
        t: f64,
        h: f64,
        full: bool,
        ctx: &mut Ctx,
    ) -> Result<Option<f64>, SolveError> {
        let q0 = std::mem::take(&mut self.now.q);
        let factored = self.factor(p, t, &q0, h, ctx);
        self.now.q = q0;
        factored?;
        // The start, the candidate and the work vectors are used while a full Newton
        // refactorises: taken out of `self` meanwhile.
        let start = std::mem::take(&mut self.now);
        let mut next = std::mem::take(&mut self.next);
        let mut work = std::mem::take(&mut self.work);
        let out = self.step_from(p, &start, &mut next, &mut work, t, h, full, ctx);
        self.now = start;
        self.next = next;
        self.work = work;
        out
    }

    /// [`Self::step`] from the state `s` at t into `next`, with the iteration matrix
    /// factorised.
    #[allow(clippy::too_many_arguments)]
    fn step_from(
        &mut self,
        p: &dyn Structure,
        s: &State,
        next: &mut State,
        work: &mut Work,
        t: f64,
        h: f64,
        full: bool,
        ctx: &mut Ctx,
    ) -> Result<Option<f64>, SolveError> {
        let n = s.q.len();
        let c = self.c;
        let t1 = t + h;
        // a₁ = (1 − α_f)/(1 − α_m) q''₁ + (α_f q''₀ − α_m a₀)/(1 − α_m).
        let ratio = (1.0 - c.alpha_f) / (1.0 - c.alpha_m);
        for i in 0..n {
            work.carried[i] = (c.alpha_f * s.acc[i] - c.alpha_m * s.a[i]) / (1.0 - c.alpha_m);
        }
        next.acc.copy_from_slice(&s.acc);
        let carried = &work.carried;
        let advance = |next: &mut State| {
            for i in 0..n {
                let a1 = ratio * next.acc[i] + carried[i];
                next.a[i] = a1;
                next.q[i] = s.q[i] + h * s.v[i] + h * h * ((0.5 - c.beta) * s.a[i] + c.beta * a1);
                next.v[i] = s.v[i] + h * ((1.0 - c.gamma) * s.a[i] + c.gamma * a1);
            }
        };
        let (f1, r, ma, dq) = (&mut work.f, &mut work.r, &mut work.ma, &mut work.dq);
        let mut prev: Option<f64> = None;
        let mut converged = false;
        for _ in 0..MAX_NEWTON {
            ctx.stats.newton_iterations += 1;
            advance(next);
            ctx.stats.rhs_evals += 1;
            p.force(t1, &next.q, &next.v, f1);
            p.mass_mul(t1, &next.q, &next.acc, ma);
            // The residual's derivative in q''₁ is M + (1 − α_f)/(1 − α_m)(β h² K + γ h C),
            // the iteration matrix over (1 − α_m): scaled so that one factorisation serves.
            for i in 0..n {
                r[i] = -(1.0 - c.alpha_m) * (ma[i] - f1[i]);
            }
            if full {
                self.k = None;
                self.factor(p, t1, &next.q, h, ctx)?;
            }
            self.solve(r);
            for i in 0..n {
                next.acc[i] += r[i];
                dq[i] = ratio * c.beta * h * h * r[i];
            }
            let norm = self.norm(ctx, dq, &next.q);
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
        advance(next);
        // Local error of the displacement (Zienkiewicz & Xie 1991): h² (β − 1/6)(a_{n+1} − a_n),
        // filtered through the iteration matrix as Hairer & Wanner filter stiff estimates: a mode
        // with ωh ≫ 1 is divided by about β(ωh)², which brings its estimate down to its own
        // (tiny) amplitude, while resolved modes pass unchanged.
        let (raw, e) = (&mut work.dq, &mut work.r);
        for i in 0..n {
            raw[i] = (1.0 - c.alpha_m) * h * h * (c.beta - 1.0 / 6.0) * (next.a[i] - s.a[i]);
        }
        p.mass_mul(t1, &next.q, raw, e);
        self.solve(e);
        Ok(Some(self.error_norm(ctx, e, &next.q)))
    }
}

impl Stepper for GenAlphaStepper {
    fn error_order(&self) -> u32 {
        2
    }

    /// (Re)start from (t0, y0): the acceleration of the segment that begins here. The tangent
    /// and the factorisation are kept: a load that jumps does not change them.
    fn start(
        &mut self,
        p: &dyn Dynamics,
        t0: f64,
        y0: &[f64],
        ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        let s = structural(p)?;
        self.groups = s.norm_groups();
        self.weights = s.norm_weights();
        self.rows = s.norm_rows().map(|rows| super::NormRows {
            rows,
            blocks: vec![(0, 1.0)],
        });
        let n = self.now.q.len();
        self.now.q.copy_from_slice(&y0[..n]);
        self.now.v.copy_from_slice(&y0[n..]);
        Self::acceleration(s, t0, &mut self.now, ctx)?;
        self.y_new.copy_from_slice(y0);
        Ok(())
    }

    /// The step that keeps the first displacement increment h²|a|/2 on tolerance.
    fn initial_step(
        &mut self,
        _p: &dyn Dynamics,
        t0: f64,
        _y0: &[f64],
        t_end: f64,
        ctx: &mut Ctx,
    ) -> Result<f64, SolveError> {
        let s = &self.now;
        let amax = s
            .acc
            .iter()
            .zip(&s.q)
            .map(|(a, q)| a.abs() / (ctx.atol + ctx.rtol * q.abs()))
            .fold(0.0, f64::max);
        Ok(if amax > 0.0 {
            (2.0 / amax).sqrt().min(1e-2 * (t_end - t0))
        } else {
            1e-3 * (t_end - t0)
        })
    }

    fn attempt(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        _y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<Attempt, SolveError> {
        let s = structural(p)?;
        let mut full = false;
        let err = loop {
            match self.step(s, t, h, full, ctx)? {
                Some(err) => break err,
                // A fresh tangent first; the factorisation keeps its symbolic analysis.
                None if !self.k_fresh => self.k = None,
                // Then a tangent at every iterate: a stiff constraint that turns with the
                // state (a shear stiffness G Av far above E A, rotating with φ) can leave
                // the tangent of the step's start no use past its first iteration.
                None if !full => full = true,
                None => return Ok(Attempt::NewtonFailed),
            }
        };
        let n = self.now.q.len();
        self.y_new[..n].copy_from_slice(&self.next.q);
        self.y_new[n..].copy_from_slice(&self.next.v);
        self.t_try = t;
        Ok(Attempt::Done { err })
    }

    fn y_new(&self) -> &[f64] {
        &self.y_new
    }

    fn accept(&mut self, t_new: f64) {
        // The dense output runs from the step start as it stands now (after a restart at a
        // breakpoint, with the new segment's acceleration) to the accepted candidate.
        let n = self.now.q.len();
        let (y, yp) = (&mut self.ends.y, &mut self.ends.yp);
        y[..n].copy_from_slice(&self.now.q);
        y[n..].copy_from_slice(&self.now.v);
        yp[..n].copy_from_slice(&self.now.v);
        yp[n..].copy_from_slice(&self.now.acc);
        std::mem::swap(&mut self.now, &mut self.next);
        self.yp_new[..n].copy_from_slice(&self.now.v);
        self.yp_new[n..].copy_from_slice(&self.now.acc);
        // The step's length as the two times give it, which the dense output spans.
        self.ends
            .accept(self.t_try, t_new - self.t_try, &self.y_new, &self.yp_new);
        self.k_fresh = false;
    }

    fn interpolate(&self, t: f64, out: &mut [f64]) {
        self.ends.interpolate(t, out);
    }

    fn interpolate_rate(&self, t: f64, out: &mut [f64]) {
        self.ends.interpolate_rate(t, out);
    }

    fn max_growth(&self) -> f64 {
        2.0
    }

    /// Keep h (and the factorised iteration matrix) unless it should grow by half.
    fn keep_step(&self, h_old: f64, h_new: f64) -> f64 {
        if (1.0..=1.5).contains(&(h_new / h_old)) {
            h_old
        } else {
            h_new
        }
    }
}

//! Time integration of M(t, y) y' = f(t, y), knowing nothing of disks or beams.
//!
//! A [`Problem`] supplies its size, right-hand side, mass matrix (identity unless it says
//! otherwise), Jacobian (finite differences unless it has one) and event functions; a
//! structural one also says so ([`Dynamics::second_order`]). A [`Stepper`] knows how to attempt
//! one step, accept it and interpolate inside it: `dopri5.rs`, `trbdf2.rs`, `esdirk.rs` (their
//! implicit stages in `stage_solver.rs`) and `genalpha.rs`. One driver, [`solve`] in
//! `driver.rs`, steps them all over [t0, t_end]: step-size control on rtol/atol (or a fixed
//! step, for measuring orders of convergence), breakpoints, dense output at the requested
//! times, and events located on the dense output to [`EVENT_TIME_TOL`]. `test_models.rs`
//! holds the small problems every method is checked on.

mod dopri5;
mod driver;
mod esdirk;
mod exact_modal;
mod genalpha;
pub mod second_order;
mod stage_solver;
#[cfg(test)]
mod test_models;
mod trbdf2;

pub use driver::{same_breakpoint, solve};

use std::fmt;

use serde::Serialize;

use crate::linalg::{self, Sparse, SparseLu};

/// Events are located to this width of their bracket in time (s).
pub const EVENT_TIME_TOL: f64 = 1e-10;

/// The step-size controller's safety factor: the next step is this fraction of the one its
/// error estimate asks for.
pub(crate) const SAFETY: f64 = 0.9;

/// An event g(t, y) of a problem: the run is watched for g passing from ≥ 0 to < 0, and a hit
/// carries the reason the problem gave it, of the problem's own type.
#[derive(Clone, Copy, Debug)]
pub struct EventSpec<E> {
    pub reason: E,
    pub terminal: bool,
}

/// M(t, y) y' = f(t, y): what a stepper needs to take a step.
pub trait Dynamics {
    fn dim(&self) -> usize;
    fn rhs(&self, t: f64, y: &[f64], f: &mut [f64]);
    /// M(t, y) of M y' = f; `None` is the identity.
    fn mass(&self, _t: f64, _y: &[f64]) -> Option<Sparse> {
        None
    }
    /// A constant mass matrix is factorised once per run.
    fn mass_is_constant(&self) -> bool {
        false
    }
    /// ∂f/∂y in closed form, where the problem has one; otherwise finite differences are used
    /// (dense: meant for small problems only).
    fn jacobian(&self, _t: f64, _y: &[f64]) -> Option<Sparse> {
        None
    }
    /// Blocks of unknowns of one kind, each measured in the error norm against its own largest
    /// value; `None` measures every unknown against itself.
    fn norm_groups(&self) -> Option<Vec<std::ops::Range<usize>>> {
        None
    }
    /// What each unknown stands for in the error norm, as a factor: an unknown that is not
    /// itself a displacement (a modal amplitude, in units of √kg·m) is measured by the largest
    /// displacement a unit of it makes, so that atol means the same on every model. `None`:
    /// every unknown is measured as it is.
    fn norm_weights(&self) -> Option<Vec<f64>> {
        None
    }
    /// Linear measures of the unknowns the error norm weighs beside the unknowns themselves
    /// (see [`NormRows`]); `None` where there are none.
    fn norm_rows(&self) -> Option<NormRows> {
        None
    }
    /// The structure M q'' = f(t, q, v) this is the first-order view y = (q, v) of, where
    /// there is one: generalized-α steps that directly.
    fn second_order(&self) -> Option<&dyn second_order::Structure> {
        None
    }
}

/// Dynamics over time: what the driver watches besides the steps.
pub trait Problem: Dynamics {
    /// Why an event fires, as the problem names it (a stop reason, say).
    type Event: Copy + fmt::Debug;
    /// Times where f jumps (loads switched on or off): steps end there and restart.
    fn breakpoints(&self) -> Vec<f64> {
        Vec::new()
    }
    /// Times where f has a kink: steps of `exact-modal`, which fits f by polynomials, end
    /// there; the other methods step over them under their error control.
    fn kinks(&self) -> Vec<f64> {
        Vec::new()
    }
    /// Told before the steps of each stretch between breakpoints, so that a jump is seen on
    /// the right side of it by every stage.
    fn enter_segment(&self, _start: f64, _end: f64) {}
    fn events(&self) -> &[EventSpec<Self::Event>] {
        &[]
    }
    fn event(&self, _index: usize, _t: f64, _y: &[f64]) -> f64 {
        1.0
    }
    /// The longest step the problem allows from (t, y): features of the problem that its
    /// unknowns do not feel strongly enough for the error estimate to see them (a crest under a
    /// rolling disk shows in the contact force, not in the motion) must not be stepped over.
    fn max_step(&self, _t: f64, _y: &[f64]) -> f64 {
        f64::INFINITY
    }
    /// The longest stretch of a step over which the events' functions, looked at at its ends,
    /// cannot fall below zero and rise again unseen: one that may (a wheel's contact force
    /// dipping over a crest quicker than the motion the steps follow) is looked at this often
    /// inside each step.
    fn event_pace(&self, _t: f64, _y: &[f64]) -> f64 {
        f64::INFINITY
    }
    /// The run has reached (t, y) for good: the step to it is accepted (or an event stopped
    /// it there). A problem whose law depends on the way the solution came (which of two
    /// crests a disk rests on) takes that in here, never from a trial or a look inside a
    /// step, so that every evaluation within one step sees the same law.
    fn accepted(&self, _t: f64, _y: &[f64]) {}
}

/// The reason of a problem that has no events.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoEvent {}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Method {
    #[serde(rename = "dopri5")]
    Dopri5,
    #[serde(rename = "trbdf2")]
    TrBdf2,
    /// Generalized-α, for structural (second-order) problems only.
    #[serde(rename = "genalpha")]
    GenAlpha,
    /// ESDIRK4(3)6L[2]SA: fourth order, L-stable, for tight tolerances.
    #[serde(rename = "esdirk4")]
    Esdirk4,
    /// Uncoupled linear oscillators (a modal beam under moving forces) in closed form.
    #[serde(rename = "exact-modal")]
    ExactModal,
}

impl Method {
    pub const ALL: [Method; 4] = [
        Method::Dopri5,
        Method::TrBdf2,
        Method::GenAlpha,
        Method::Esdirk4,
    ];
    /// The methods that integrate any first-order problem.
    pub const FIRST_ORDER: [Method; 3] = [Method::Dopri5, Method::TrBdf2, Method::Esdirk4];
    /// Every method a scene or the command line may name: the time-stepping ones, and
    /// `exact-modal` for the structures it applies to.
    pub const NAMED: [Method; 5] = [
        Method::Dopri5,
        Method::TrBdf2,
        Method::GenAlpha,
        Method::Esdirk4,
        Method::ExactModal,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Method::Dopri5 => "dopri5",
            Method::TrBdf2 => "trbdf2",
            Method::GenAlpha => "genalpha",
            Method::Esdirk4 => "esdirk4",
            Method::ExactModal => "exact-modal",
        }
    }

    pub fn from_name(name: &str) -> Option<Method> {
        Method::NAMED.into_iter().find(|m| m.name() == name)
    }

    /// Classical order of the propagated solution.
    pub fn order(self) -> u32 {
        match self {
            Method::Dopri5 => 5,
            Method::Esdirk4 => 4,
            Method::TrBdf2 | Method::GenAlpha => 2,
            // Exact where the force is a polynomial between kinks; its fit is of degree 6 and
            // more.
            Method::ExactModal => 7,
        }
    }
}

/// Smallest relative tolerance an integrator is asked for: a hundred times the round-off of a
/// double, below which no step can show its error.
pub const MIN_RTOL: f64 = 1e-14;

/// Why a relative tolerance cannot be used, if it cannot: it must be a fraction (below 1,
/// where an error as large as the solution would pass) and no finer than [`MIN_RTOL`].
pub fn rtol_problem(rtol: f64) -> Option<String> {
    if !(rtol < 1.0) {
        Some(format!("= {rtol} would accept an error as large as the solution; a relative tolerance must be below 1"))
    } else if rtol < MIN_RTOL {
        Some(format!(
            "= {rtol:e} is finer than double precision can check; use at least {MIN_RTOL:e}"
        ))
    } else {
        None
    }
}

#[derive(Clone, Debug)]
pub struct Options {
    pub method: Method,
    pub rtol: f64,
    pub atol: f64,
    /// Take steps of exactly this size, with no error control.
    pub fixed_step: Option<f64>,
    pub max_steps: usize,
    /// Spend all of `max_steps` before giving up, rather than give up early when the pace of
    /// the steps so far projects far past it: for a setting chosen to finish whose first steps
    /// may be by far its densest (a point past a work–precision grid; on the zip-line the
    /// first 2000 steps project 16–27 times the steps a run takes).
    pub whole_budget: bool,
    /// Generalized-α's spectral radius at infinity.
    pub rho_inf: f64,
    /// The circular frequency ω at which a first-order view's velocities are measured: a
    /// velocity's error against ω · atol, the speed of a vibration of amplitude atol at ω, so
    /// that atol in metres means the same for both halves of the state. `None`: against atol.
    pub velocity_rate: Option<f64>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            method: Method::Dopri5,
            rtol: 1e-6,
            atol: 1e-9,
            fixed_step: None,
            max_steps: 10_000_000,
            whole_budget: false,
            rho_inf: 1.0,
            velocity_rate: None,
        }
    }
}

/// What a run did; every run reports it.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Stats {
    pub steps: usize,
    pub rejected: usize,
    pub rhs_evals: usize,
    pub jacobians: usize,
    pub factorizations: usize,
    pub newton_iterations: usize,
    pub wall_s: f64,
}

impl Stats {
    /// Add another solve's counts (and wall time) to these: a run of several phases.
    pub fn add(&mut self, more: &Stats) {
        self.steps += more.steps;
        self.rejected += more.rejected;
        self.rhs_evals += more.rhs_evals;
        self.jacobians += more.jacobians;
        self.factorizations += more.factorizations;
        self.newton_iterations += more.newton_iterations;
        self.wall_s += more.wall_s;
    }
}

#[derive(Clone, Debug)]
pub struct EventHit<E> {
    pub reason: E,
    pub t: f64,
}

#[derive(Clone, Debug)]
pub struct Outcome<E> {
    pub t: f64,
    pub y: Vec<f64>,
    pub stats: Stats,
    /// The terminal event that ended the run early, if any.
    pub stopped_by: Option<EventHit<E>>,
    /// Non-terminal events met on the way.
    pub events: Vec<EventHit<E>>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum SolveError {
    /// The step fell below `floor`, the finest a run can take: 10⁻¹⁴ of its latest time
    /// (or of 1 s), where t + h no longer differs from t by enough digits to step on.
    StepSizeUnderflow {
        t: f64,
        h: f64,
        floor: f64,
    },
    /// A step of h to a breakpoint was rejected, and the step asked instead is shorter by less
    /// than `floor`, the finest the run resolves: both end on the breakpoint.
    BelowResolution {
        t: f64,
        h: f64,
        floor: f64,
    },
    NewtonFailed {
        t: f64,
    },
    NonFinite {
        t: f64,
    },
    /// The step budget is spent, or `projected` steps would pass it at the recent pace.
    TooManySteps {
        t: f64,
        steps: usize,
        projected: usize,
        budget: usize,
    },
    SingularMatrix {
        t: f64,
    },
    NeedsSecondOrder,
    NotLinearModal,
}

impl fmt::Display for SolveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolveError::StepSizeUnderflow { t, h, floor } if *floor > 1e-14 => {
                write!(f, "the step size fell to {h:.3e} s at t = {t:.6} s, below the finest step a run {:.3e} s long can take ({floor:.3e} s, 1e-14 of it): shorten the run (its duration, or a crossing a near-zero speed makes endless), or the solution is not smooth enough to follow there", floor / 1e-14)
            }
            SolveError::StepSizeUnderflow { t, h, .. } => {
                write!(f, "the step size fell to {h:.3e} s at t = {t:.6} s: the solution is not smooth enough to follow there")
            }
            SolveError::BelowResolution { t, h, floor } => {
                write!(f, "at t = {t:.6} s the step of {h:.3e} s to the next breakpoint (a load entering, leaving or passing a node) was rejected, and the shorter one its error asks for ends closer to that breakpoint than the finest time a run {:.3e} s long resolves ({floor:.3e} s, 1e-14 of it): shorten the run (its duration, or a crossing a near-zero speed makes endless)", floor / 1e-14)
            }
            SolveError::NewtonFailed { t } => {
                write!(f, "Newton iterations did not converge at t = {t:.6} s even with a fresh Jacobian and smaller steps")
            }
            SolveError::NonFinite { t } => write!(f, "the state became non-finite at t = {t:.6} s"),
            SolveError::TooManySteps {
                t,
                steps,
                projected,
                budget,
            } => {
                if projected > budget {
                    write!(f, "gave up after {steps} steps at t = {t:.6} s: at its recent pace the run would need about {:.1e} steps, past the budget of {budget}; loosen rtol, shorten the run, or look for a time scale the scene makes tiny (a near-zero mass or density, a huge stiffness)", *projected as f64)
                } else {
                    write!(
                        f,
                        "gave up after {steps} steps at t = {t:.6} s; loosen rtol or shorten the run"
                    )
                }
            }
            SolveError::NeedsSecondOrder => {
                write!(
                    f,
                    "generalized-α integrates second-order (structural) problems only"
                )
            }
            SolveError::NotLinearModal => write!(
                f,
                "exact-modal integrates uncoupled linear oscillators under a force of time alone: a modal beam under moving forces, point loads or its weight, without a disk or moving masses"
            ),
            SolveError::SingularMatrix { t } => {
                write!(
                    f,
                    "the mass (or iteration) matrix is singular at t = {t:.6} s"
                )
            }
        }
    }
}

impl std::error::Error for SolveError {}

/// The dense output of an accepted step, for t within it.
pub trait Dense {
    /// y(t).
    fn at(&self, t: f64) -> Vec<f64>;
    /// y'(t): at the step's ends the method's y'; inside, the problem's y' at the interpolated
    /// state where the stepper's interpolant is a cubic ([`Stepper::rate_from_the_problem`]),
    /// else the interpolant's own derivative. `None` where the view of the state has none.
    fn rate(&self, _t: f64) -> Option<Vec<f64>> {
        None
    }
    /// Over [ta, tb] within the step, in closed form where the stepper holds the motion as
    /// one ([`Stepper::power_integrals`]).
    fn power_integrals(&self, _ta: f64, _tb: f64) -> Option<PowerIntegrals> {
        None
    }
    /// The weighted sums `rows` of the oscillators over the step, in closed form where the
    /// stepper holds its motion as one ([`Stepper::forms`]).
    fn forms(&self, _rows: &[FormRow]) -> Option<StepForms> {
        None
    }
}

/// A weighted sum of a linear modal problem's oscillators: of their displacements, or of
/// their accelerations.
pub struct FormRow<'a> {
    pub weights: &'a [f64],
    pub accelerations: bool,
}

/// Weighted sums of the oscillators over one exactly integrated step, each a polynomial in
/// σ = (t − t0)/h and the under-damped oscillators' free motions Re Σ_k B_k e^{λ_k (t − t0)}.
pub struct StepForms {
    t0: f64,
    h: f64,
    lambda: Vec<nalgebra::Complex<f64>>,
    /// How many sums.
    count: usize,
    /// The sums' polynomials, coefficient by coefficient: degree j of sum r at j · count + r.
    polys: Vec<f64>,
    /// Each sum's amplitude of free motion k at k · count + r.
    free: Vec<nalgebra::Complex<f64>>,
    /// The phasors e^{λ_k τ} at the last time read, and the factor that carries them on by
    /// the spacing met last.
    carry: std::cell::RefCell<exact_modal::Carry>,
}

/// What a linear modal problem's forces and damping did over an interval: Σ_k ∫ g_k ẋ_k dt,
/// the work of the force that does not depend on the state, and Σ_k c_k ∫ ẋ_k² dt, the energy
/// the damping took.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PowerIntegrals {
    pub work: f64,
    pub dissipated: f64,
}

/// A dense output given as a function of t alone.
impl<F: Fn(f64) -> Vec<f64>> Dense for F {
    fn at(&self, t: f64) -> Vec<f64> {
        self(t)
    }
}

/// Receives the solution at output times and after every accepted step.
pub trait Observer {
    fn output(&mut self, t: f64, y: &[f64]);
    fn step(&mut self, _t: f64, _y: &[f64]) {}
    /// The accepted step from t0 to t1 as its dense output: for what integrates over time
    /// and the extremes between output times, which the output grid would alias or miss.
    fn span(&mut self, _t0: f64, _t1: f64, _dense: &dyn Dense) {}
}

/// Step outcome of one attempt by a stepper.
pub(crate) enum Attempt {
    /// Accepted or not by the driver from `err` (weighted RMS norm, 1 = on tolerance).
    Done { err: f64 },
    /// The nonlinear solve failed even with a fresh Jacobian: retry with a smaller step.
    NewtonFailed,
}

pub(crate) trait Stepper {
    /// Exponent base for step-size control: the order of the error estimate.
    fn error_order(&self) -> u32;
    fn start(
        &mut self,
        p: &dyn Dynamics,
        t0: f64,
        y0: &[f64],
        ctx: &mut Ctx,
    ) -> Result<(), SolveError>;
    /// Attempt a step of size h from (t, y); leaves the candidate in `y_new`.
    fn attempt(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        h: f64,
        ctx: &mut Ctx,
    ) -> Result<Attempt, SolveError>;
    fn y_new(&self) -> &[f64];
    /// Commit the last attempt as the new step start; the step ends at `t_new` (the attempt's
    /// t + h, or the breakpoint it was cut to end on exactly).
    fn accept(&mut self, t_new: f64);
    /// Dense output inside the last accepted step [t_old, t_old + h].
    fn interpolate(&self, t: f64, out: &mut [f64]);
    /// The dense output's derivative in t.
    fn interpolate_rate(&self, t: f64, out: &mut [f64]);
    /// Whether y' inside a step is better read from the problem at the interpolated state than
    /// from the interpolant's derivative: where the interpolant is the cubic through the ends
    /// and the method's y' there is the problem's. The cubic's y is within O(h⁴) and its
    /// derivative only O(h³), so the accelerations of a fourth-order method's long steps read
    /// from the derivative miss by (ωh)³: the railcar's bogies' root mean square under ESDIRK4
    /// came out 1.3·10⁻² low.
    fn rate_from_the_problem(&self) -> bool {
        false
    }
    /// Implicit methods keep a factorised iteration matrix valid while h stays put.
    fn keep_step(&self, _h_old: f64, h_new: f64) -> f64 {
        h_new
    }
    /// The force's work and the damping's energy over [ta, tb] within the accepted step, where
    /// the stepper holds its motion in closed form (`exact-modal`); `None` elsewhere.
    fn power_integrals(&self, _ta: f64, _tb: f64) -> Option<PowerIntegrals> {
        None
    }
    /// The weighted sums `rows` of the oscillators over the accepted step in closed form
    /// (`exact-modal`); `None` elsewhere.
    fn forms(&self, _rows: &[FormRow]) -> Option<StepForms> {
        None
    }
    /// The most an accepted step may grow the next one by.
    fn max_growth(&self) -> f64 {
        5.0
    }
    /// The first step from (t0, y0), after [`Stepper::start`].
    fn initial_step(
        &mut self,
        p: &dyn Dynamics,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        ctx: &mut Ctx,
    ) -> Result<f64, SolveError> {
        driver::initial_step(p, t0, y0, t_end, self.error_order(), ctx)
    }
}

/// The larger of two error measures, NaN if either is: a NaN error must reject the step.
fn worst(m: f64, x: f64) -> f64 {
    if x.is_nan() {
        f64::NAN
    } else {
        m.max(x)
    }
}

/// Per group, max |e_i| / (atol + rtol max_j max(|a_j|, |b_j|)), every value first scaled by
/// its unknown's weight where the problem gives weights (see [`Dynamics::norm_weights`]).
pub(crate) fn grouped_norm(
    groups: &[std::ops::Range<usize>],
    weights: Option<&[f64]>,
    atol: f64,
    rtol: f64,
    e: &[f64],
    a: &[f64],
    b: &[f64],
) -> f64 {
    // Plain maxima over slices, NaN tracked on the side: every Newton iteration of an implicit
    // step measures its correction here, and a fold with a NaN test per entry does not vectorise.
    let mut nan = false;
    let mut largest = 0.0_f64;
    for g in groups {
        let (e, a, b) = (&e[g.clone()], &a[g.clone()], &b[g.clone()]);
        let (size, error) = match weights {
            Some(w) => group_maxima(w[g.clone()].iter().copied(), e, a, b, &mut nan),
            None => group_maxima(std::iter::repeat(1.0), e, a, b, &mut nan),
        };
        let ratio = error / (atol + rtol * size);
        nan |= ratio.is_nan();
        largest = largest.max(ratio);
    }
    if nan {
        f64::NAN
    } else {
        largest
    }
}

/// One group's largest weighted max(|a|, |b|) and weighted |e|, with `nan` set where an e is
/// NaN. Unweighted, the weights are ones, which the product by them leaves exact.
fn group_maxima(
    weights: impl Iterator<Item = f64>,
    e: &[f64],
    a: &[f64],
    b: &[f64],
    nan: &mut bool,
) -> (f64, f64) {
    let (mut size, mut error) = (0.0_f64, 0.0_f64);
    for (((w, &e), &a), &b) in weights.zip(e).zip(a).zip(b) {
        size = size.max(w * a.abs().max(b.abs()));
        error = error.max(w * e.abs());
        *nan |= e.is_nan();
    }
    (size, error)
}

/// The rows of a [`NormRows`], formed once per run and shared by every driver start (a flight
/// restarts the driver).
pub type ModeRows = std::sync::Arc<[Vec<f64>]>;

/// Rows r_k over the first unknowns of a block, which the error norm measures beside the
/// unknowns: max_k |r_k · e| against atol + rtol max_k max(|r_k · a|, |r_k · b|), once per block
/// in `blocks` (the displacements, and the velocities after them in a first-order view), each
/// block's values first scaled by its weight as the unknowns are by theirs.
/// A mesh's modes below the acceleration cutoff are such rows: an error in the nodal
/// displacements within atol can still be ω_k²/ω₁² times that in the accelerations the run
/// reports. The step's error is measured with them, Newton's corrections on the unknowns alone:
/// measured with the rows too, Newton took half as long again over the tests of moving forces
/// on a mesh, both within the accuracy.
#[derive(Clone, Debug)]
pub struct NormRows {
    pub rows: ModeRows,
    /// Each block's first unknown and its weight.
    pub blocks: Vec<(usize, f64)>,
}

impl NormRows {
    pub(crate) fn norm(&self, atol: f64, rtol: f64, e: &[f64], a: &[f64], b: &[f64]) -> f64 {
        let mut largest = 0.0_f64;
        for &(o, w) in &self.blocks {
            let (mut error, mut size) = (0.0_f64, 0.0_f64);
            for r in self.rows.iter() {
                let dot = |x: &[f64]| -> f64 { r.iter().zip(&x[o..]).map(|(r, x)| r * x).sum() };
                error = worst(error, w * dot(e).abs());
                size = size.max(w * dot(a).abs()).max(w * dot(b).abs());
            }
            largest = worst(largest, error / (atol + rtol * size));
        }
        largest
    }
}

/// Shared per-run context: tolerances, statistics and the weighted error norm.
pub(crate) struct Ctx {
    pub rtol: f64,
    pub atol: f64,
    pub stats: Stats,
    /// Factorised mass matrix of a problem whose mass is constant.
    mass_lu: Option<SparseLu>,
    /// Factorised constant part of a mass that splits (a body riding on a structure).
    split_lu: Option<SparseLu>,
    groups: Option<Vec<std::ops::Range<usize>>>,
    weights: Option<Vec<f64>>,
    rows: Option<NormRows>,
}

impl Ctx {
    /// max_i |e_i| / (atol + rtol max(|a_i|, |b_i|)): every component within its tolerance, as
    /// Matlab's solvers (and so the thesis) measure it. A problem with norm groups is measured
    /// per group against the group's largest value instead, so that components that are tiny
    /// only because they are near a node of the motion do not dictate the step.
    pub fn norm(&self, e: &[f64], a: &[f64], b: &[f64]) -> f64 {
        let unknowns = self.unknowns_norm(e, a, b);
        match &self.rows {
            Some(rows) if !unknowns.is_nan() => {
                unknowns.max(rows.norm(self.atol, self.rtol, e, a, b))
            }
            _ => unknowns,
        }
    }

    /// The norm over the unknowns alone, without the problem's rows: Newton's corrections are
    /// measured by it (see [`NormRows`]).
    pub fn unknowns_norm(&self, e: &[f64], a: &[f64], b: &[f64]) -> f64 {
        let weights = self.weights.as_deref();
        match &self.groups {
            None => {
                let w = |i: usize| weights.map_or(1.0, |w| w[i]);
                (0..e.len())
                    .map(|i| {
                        (w(i) * e[i] / (self.atol + self.rtol * w(i) * a[i].abs().max(b[i].abs())))
                            .abs()
                    })
                    .fold(0.0, worst)
            }
            Some(groups) => grouped_norm(groups, weights, self.atol, self.rtol, e, a, b),
        }
    }

    pub fn rhs(&mut self, p: &dyn Dynamics, t: f64, y: &[f64], f: &mut [f64]) {
        self.stats.rhs_evals += 1;
        p.rhs(t, y, f);
    }

    /// y' = M⁻¹ f.
    pub fn derivative(
        &mut self,
        p: &dyn Dynamics,
        t: f64,
        y: &[f64],
        yp: &mut [f64],
    ) -> Result<(), SolveError> {
        self.rhs(p, t, y, yp);
        if p.mass_is_constant() {
            if self.mass_lu.is_none() {
                if let Some(m) = p.mass(t, y) {
                    self.stats.factorizations += 1;
                    self.mass_lu =
                        Some(SparseLu::factor(&m, None).ok_or(SolveError::SingularMatrix { t })?);
                }
            }
            if let Some(lu) = &self.mass_lu {
                lu.solve_in_place(yp);
            }
        } else if let Some(m) = p.mass(t, y) {
            self.stats.factorizations += 1;
            SparseLu::factor(&m, None)
                .ok_or(SolveError::SingularMatrix { t })?
                .solve_in_place(yp);
        }
        Ok(())
    }

    /// y' = M⁻¹ f where the outputs read it inside a step (`None` where M is singular). A
    /// mass that splits into a constant part and a few rows (a body riding on a structure) is
    /// solved from the constant part, factorised once, with the rows added by Woodbury, rather
    /// than factorising the whole at every sample of the extremes' watch.
    pub fn rate(&mut self, p: &dyn Dynamics, t: f64, y: &[f64]) -> Option<Vec<f64>> {
        let mut yp = vec![0.0; y.len()];
        let split = p.second_order().filter(|_| !p.mass_is_constant());
        let Some((s, (base, rows))) =
            split.and_then(|s| s.mass_split(t, &y[..s.dim()]).map(|m| (s, m)))
        else {
            return self.derivative(p, t, y, &mut yp).ok().map(|()| yp);
        };
        if self.split_lu.is_none() {
            self.stats.factorizations += 1;
            self.split_lu = Some(SparseLu::factor(base, None)?);
        }
        self.rhs(p, t, y, &mut yp);
        let lu = self.split_lu.as_ref()?;
        linalg::Woodbury::new(lu, rows)?.solve_in_place(lu, &mut yp[s.dim()..]);
        Some(yp)
    }

    /// ∂f/∂y: the problem's own, or forward differences scaled to each component.
    pub fn jacobian(&mut self, p: &dyn Dynamics, t: f64, y: &[f64], f0: &[f64]) -> Sparse {
        self.stats.jacobians += 1;
        if let Some(j) = p.jacobian(t, y) {
            return j;
        }
        let n = y.len();
        let mut j = nalgebra::DMatrix::zeros(n, n);
        let mut yh = y.to_vec();
        let mut fh = vec![0.0; n];
        for c in 0..n {
            let delta = f64::EPSILON.sqrt()
                * y[c]
                    .abs()
                    .max(self.atol / self.rtol.max(f64::EPSILON))
                    .max(1e-8);
            yh[c] = y[c] + delta;
            self.rhs(p, t, &yh, &mut fh);
            for r in 0..n {
                j[(r, c)] = (fh[r] - f0[r]) / delta;
            }
            yh[c] = y[c];
        }
        linalg::from_dense(&j)
    }
}

/// The two ends (y, y') of the last accepted step of a one-step method: the next step starts
/// from the newer one, and dense output inside the step is the cubic Hermite through both
/// (third order).
pub(crate) struct StepEnds {
    /// y and y' = M⁻¹ f at the end of the last accepted step.
    pub y: Vec<f64>,
    pub yp: Vec<f64>,
    prev_y: Vec<f64>,
    prev_yp: Vec<f64>,
    t0: f64,
    h: f64,
}

impl StepEnds {
    pub fn new(n: usize) -> Self {
        StepEnds {
            y: vec![0.0; n],
            yp: vec![0.0; n],
            prev_y: vec![0.0; n],
            prev_yp: vec![0.0; n],
            t0: 0.0,
            h: 0.0,
        }
    }

    /// Start from (t0, y0), with its derivative from the problem.
    pub fn start(
        &mut self,
        p: &dyn Dynamics,
        t0: f64,
        y0: &[f64],
        ctx: &mut Ctx,
    ) -> Result<(), SolveError> {
        self.y.copy_from_slice(y0);
        ctx.derivative(p, t0, y0, &mut self.yp)
    }

    /// The step [t, t + h] that ends at (y, y') is accepted.
    pub fn accept(&mut self, t: f64, h: f64, y: &[f64], yp: &[f64]) {
        self.t0 = t;
        self.h = h;
        std::mem::swap(&mut self.prev_y, &mut self.y);
        std::mem::swap(&mut self.prev_yp, &mut self.yp);
        self.y.copy_from_slice(y);
        self.yp.copy_from_slice(yp);
    }

    /// y'(t) inside the last accepted step: the cubic's derivative.
    pub fn interpolate_rate(&self, t: f64, out: &mut [f64]) {
        let h = self.h;
        let th = (t - self.t0) / h;
        let d00 = 6.0 * th * (th - 1.0) / h;
        let d10 = (3.0 * th - 1.0) * (th - 1.0);
        let d11 = th * (3.0 * th - 2.0);
        for (i, o) in out.iter_mut().enumerate() {
            *o = d00 * (self.prev_y[i] - self.y[i]) + d10 * self.prev_yp[i] + d11 * self.yp[i];
        }
    }

    /// y(t) inside the last accepted step.
    pub fn interpolate(&self, t: f64, out: &mut [f64]) {
        let h = self.h;
        let th = (t - self.t0) / h;
        let h00 = (1.0 + 2.0 * th) * (1.0 - th).powi(2);
        let h10 = th * (1.0 - th).powi(2);
        let h01 = th * th * (3.0 - 2.0 * th);
        let h11 = th * th * (th - 1.0);
        for (i, o) in out.iter_mut().enumerate() {
            *o = h00 * self.prev_y[i]
                + h * h10 * self.prev_yp[i]
                + h01 * self.y[i]
                + h * h11 * self.yp[i];
        }
    }
}

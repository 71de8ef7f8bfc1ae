//! A disk rolling without slip on a rigid curve, in two formulations that must agree:
//! [`thesis`], the 6-unknown mass-matrix system of thesis Table 1, and [`minimal`], one degree of
//! freedom s with the centre on the offset curve. Both report the same [`DiskObservation`] and
//! watch the same physical events ([`crate::disk`]).

pub mod flight;
pub mod minimal;
pub mod thesis;

use crate::curve::{Curve, CurvePoint};
use crate::disk::{ContactLoss, Disk, DiskObservation, StopReason, FIT_MARGIN};
use crate::ode::{EventSpec, Problem};

/// A rolling model the run can drive: an ODE problem that also knows its initial state and
/// what its state means.
pub trait RollingModel: Problem<Event = StopReason> {
    fn initial_state(&self) -> Vec<f64>;
    /// The state of the disk rolling at contact parameter `s` with centre speed `v` along the
    /// tangent and rotation `phi` relative to the tangent frame (a landing's restart).
    fn state_at(&self, s: f64, v: f64, phi: f64) -> Vec<f64>;
    fn observe(&self, t: f64, y: &[f64]) -> DiskObservation;
    fn formulation(&self) -> &'static str;
}

/// The rolling setting shared by both formulations.
#[derive(Clone, Debug)]
pub struct Rolling {
    pub curve: Curve,
    pub disk: Disk,
    pub gravity: f64,
    pub s0: f64,
    pub omega0: f64,
    pub mu: Option<f64>,
    pub contact_loss: ContactLoss,
    specs: Vec<EventSpec<StopReason>>,
    reasons: Vec<StopReason>,
}

impl Rolling {
    pub fn new(
        curve: Curve,
        disk: Disk,
        gravity: f64,
        s0: f64,
        omega0: f64,
        mu: Option<f64>,
    ) -> Self {
        let mut reasons = vec![StopReason::ContactLost, StopReason::NoFit];
        if mu.is_some() {
            reasons.push(StopReason::Slip);
        }
        if curve.domain().is_some() {
            reasons.push(StopReason::LeftTrack);
        }
        let specs = reasons
            .iter()
            .map(|&reason| EventSpec {
                reason,
                terminal: true,
            })
            .collect();
        Rolling {
            curve,
            disk,
            gravity,
            s0,
            omega0,
            mu,
            contact_loss: ContactLoss::Fly { restitution: 0.0 },
            specs,
            reasons,
        }
    }

    pub fn event_specs(&self) -> &[EventSpec<StopReason>] {
        &self.specs
    }

    /// g ≥ 0 while the disk rolls; the event fires where g turns negative.
    pub fn event_value(&self, index: usize, obs: &DiskObservation) -> f64 {
        match self.reasons[index] {
            StopReason::ContactLost => obs.rn,
            StopReason::Slip => self.mu.unwrap_or(f64::INFINITY) * obs.rn - obs.rt.abs(),
            StopReason::NoFit => {
                let p = self.curve.at(obs.s);
                1.0 - self.disk.radius * p.curvature() - FIT_MARGIN
            }
            StopReason::LeftTrack => {
                let (lo, hi) = self
                    .curve
                    .domain()
                    .unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
                (obs.s - lo).min(hi - obs.s)
            }
        }
    }

    /// Centre of the disk touching the curve at p: r + a e_n.
    pub fn centre(&self, p: &CurvePoint) -> [f64; 2] {
        let n = p.normal();
        [
            p.r[0] + self.disk.radius * n[0],
            p.r[1] + self.disk.radius * n[1],
        ]
    }

    /// Initial centre speed along the tangent, from the no-slip condition v + aΩ = 0.
    pub fn v0(&self) -> f64 {
        -self.disk.radius * self.omega0
    }

    /// Contact forces from Newton's law for the centre in the tangent frame (thesis (3.6), with
    /// erratum 2): R_t = m v̇ + m g e_tY, R_n = m v ψ' ṡ + m g e_tX.
    pub fn reactions(&self, p: &CurvePoint, v: f64, vdot: f64, sdot: f64) -> (f64, f64) {
        let m = self.disk.mass;
        let t = p.tangent();
        let rt = m * vdot + m * self.gravity * t[1];
        let rn = m * v * p.psi_prime() * sdot + m * self.gravity * t[0];
        (rt, rn)
    }

    pub fn energies(&self, v: f64, omega: f64, centre_y: f64) -> (f64, f64) {
        let kinetic = 0.5 * self.disk.mass * v * v + 0.5 * self.disk.inertia() * omega * omega;
        (kinetic, self.disk.mass * self.gravity * centre_y)
    }

    /// Scan every point the disk could reach with its initial energy and fail where the disk
    /// does not fit the curve (1 − aκ ≤ 0). Returns the parameter of the first such point.
    /// Between samples, each local maximum of the curvature is refined by golden-section
    /// search, so a peak such as the parabola's vertex is checked exactly.
    pub fn first_unfit_point(&self) -> Option<f64> {
        let a = self.disk.radius;
        let kappa = |s: f64| self.curve.at(s).curvature();
        let fits_at = |k: f64| 1.0 - a * k > 0.0;
        let fits = |s: f64| fits_at(kappa(s));
        if !fits(self.s0) {
            return Some(self.s0);
        }
        let start = self.curve.at(self.s0);
        let g = self.gravity;
        let reach_height = if g > 0.0 {
            self.centre(&start)[1]
                + 0.5 * self.disk.rolling_mass() / self.disk.mass * self.v0().powi(2) / g
        } else {
            f64::INFINITY
        };
        let (lo, hi) = self
            .curve
            .domain()
            .unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
        const SAMPLES: usize = 200_000;
        for dir in [-1.0, 1.0] {
            // One evaluation of the curve a sample: an expression curve costs microseconds a
            // point, and a closed one is scanned for all the samples.
            let (mut p, mut k) = (start, start.curvature());
            let mut trail = [(self.s0, k); 2];
            let mut s = self.s0;
            for _ in 0..SAMPLES {
                // Steps a fraction of the smaller of the disk radius and the local radius of
                // curvature, so that no bend is stepped over.
                let ds = 0.02 * a.min(1.0 / k.abs().max(1e-12)) / p.speed();
                s = (s + dir * ds).clamp(lo, hi);
                p = self.curve.at(s);
                k = p.curvature();
                if !fits_at(k) {
                    return Some(s);
                }
                // A rise within round-off is no peak: on a circle round-off alone makes one at
                // every other sample.
                let rise = trail[1].1 - trail[0].1;
                if rise > 1e-12 * trail[1].1.abs() && trail[1].1 >= k {
                    let peak = golden_max(&kappa, trail[0].0.min(s), trail[0].0.max(s));
                    if !fits(peak) {
                        return Some(peak);
                    }
                }
                trail = [trail[1], (s, k)];
                if s <= lo || s >= hi || self.centre(&p)[1] > reach_height {
                    break;
                }
            }
        }
        None
    }
}

/// Maximiser of a unimodal f on [a, b] by golden-section search.
fn golden_max(f: &dyn Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let r = (5f64.sqrt() - 1.0) / 2.0;
    let mut c = b - r * (b - a);
    let mut d = a + r * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    while b - a > 1e-12 * (1.0 + a.abs().max(b.abs())) {
        if fc > fd {
            b = d;
            (d, fd) = (c, fc);
            c = b - r * (b - a);
            fc = f(c);
        } else {
            a = c;
            (c, fc) = (d, fd);
            d = a + r * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}

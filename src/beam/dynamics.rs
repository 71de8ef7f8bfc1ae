//! The loaded beam as a structural problem M q'' = F_ext(t) − F_int(q) for the integrators;
//! on a modal beam the unknowns are the modal amplitudes, η̈ = Φᵀ F_ext(t) − Ω² η.
//! Loads switch on and off at their `from`/`until` times: those are breakpoints, and within
//! each stretch between them the set of active loads is fixed (the integrator names the
//! stretch), so no stage ever sees a load on the wrong side of its jump.

use std::borrow::Cow;
use std::cell::{Cell, RefCell};

use super::damping::Rayleigh;
use super::load::PointLoad;
use super::modal::ModalBasis;
use super::train::Train;
use super::Beam;
use crate::linalg::{Assembly, Sparse};
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::NoEvent;

pub struct LoadedBeam<'a> {
    pub beam: &'a Beam,
    pub loads: &'a [PointLoad],
    /// The modes whose amplitudes are the unknowns, on a modal beam.
    pub modal: Option<&'a ModalBasis>,
    /// C = α M + β K₀ in the model's unknowns (diagonal on a modal beam), and α, β.
    damping: Option<(Sparse, Rayleigh)>,
    /// A train of axle loads crossing the beam.
    pub train: Option<&'a Train>,
    /// Midpoint of the current stretch between breakpoints; NaN outside a run.
    segment: Cell<f64>,
    /// Internal forces, kept so that each force evaluation does not allocate.
    scratch: RefCell<Vec<f64>>,
    /// C v, in the model's unknowns, kept for the same reason.
    damped: RefCell<Vec<f64>>,
}

impl<'a> LoadedBeam<'a> {
    pub fn new(
        beam: &'a Beam,
        loads: &'a [PointLoad],
        modal: Option<&'a ModalBasis>,
        damping: Option<Rayleigh>,
        train: Option<&'a Train>,
    ) -> Self {
        let damping = damping.map(|r| {
            let c = match modal {
                Some(m) => {
                    let mut a = Assembly::new(m.dim());
                    for (k, w) in m.omega.iter().enumerate() {
                        a.add(k, k, r.alpha + r.beta * w * w);
                    }
                    a.build()
                }
                None => {
                    let mut a = Assembly::new(beam.dim());
                    a.add_sparse(beam.mass(), r.alpha, 0, 0);
                    a.add_sparse(&beam.initial_stiffness(), r.beta, 0, 0);
                    a.build()
                }
            };
            (c, r)
        });
        LoadedBeam {
            beam,
            loads,
            modal,
            damping,
            train,
            segment: Cell::new(f64::NAN),
            scratch: RefCell::new(vec![0.0; beam.dim()]),
            damped: RefCell::new(vec![0.0; modal.map_or(beam.dim(), |m| m.dim())]),
        }
    }

    /// `then` of the damping force C v at the model's velocities v; `None` undamped.
    fn with_damping_force<R>(&self, v: &[f64], then: impl FnOnce(&[f64]) -> R) -> Option<R> {
        let (c, _) = self.damping.as_ref()?;
        let mut cv = self.damped.borrow_mut();
        crate::linalg::mul(c, v, &mut cv);
        Some(then(&cv))
    }

    /// The loads acting at time t (within the current stretch, if one is set).
    pub fn active(&self, t: f64) -> impl Iterator<Item = &PointLoad> {
        let when = if self.segment.get().is_nan() {
            t
        } else {
            self.segment.get()
        };
        self.loads.iter().filter(move |l| l.active(when))
    }

    /// F_ext at time t, on the mesh's unknowns: the point loads acting, and the beam's own
    /// weight where the scene puts it on.
    pub fn external(&self, t: f64, f: &mut [f64]) {
        f.fill(0.0);
        for l in self.active(t) {
            self.beam.add_point_load(l.x, l.force, l.mz, f);
        }
        self.beam.add_weight(f);
        for (x, p) in self.axles(t) {
            self.beam.add_point_load(x, [0.0, -p], 0.0, f);
        }
    }

    /// The train's axles on the beam at t, with their forces. Where an end is free an axle
    /// that enters or leaves there is a jump of the load: which axles are on is then decided
    /// within the current stretch between breakpoints (an axle enters or leaves only at one).
    /// Where the ends hold w an axle comes on and goes off at nothing, so it is decided at t.
    pub fn axles(&self, t: f64) -> Vec<(f64, f64)> {
        let Some(train) = self.train else {
            return Vec::new();
        };
        let length = self.beam.length;
        let when = if self.segment.get().is_nan() || self.train_breakpoints().is_empty() {
            t
        } else {
            self.segment.get()
        };
        (0..train.axles.len())
            .filter(|&a| (0.0..=length).contains(&train.position(a, when)))
            .map(|a| (train.position(a, t).clamp(0.0, length), train.loads[a]))
            .collect()
    }

    /// When an axle enters or leaves at an end that does not hold w.
    fn train_breakpoints(&self) -> Vec<f64> {
        let Some(train) = self.train else {
            return Vec::new();
        };
        let length = self.beam.length;
        train
            .axles
            .iter()
            .flat_map(|d| {
                [
                    (!self.beam.holds_w_at(false)).then_some(d / train.speed),
                    (!self.beam.holds_w_at(true)).then_some((d + length) / train.speed),
                ]
            })
            .flatten()
            .collect()
    }

    /// The power of the train's axle forces on the beam moving at the mesh's velocities v.
    pub fn train_power(&self, t: f64, v: &[f64]) -> f64 {
        self.axles(t)
            .into_iter()
            .map(|(x, p)| -p * self.beam.displacement_at(v, x).w)
            .sum()
    }

    /// The Rayleigh damping acting, if any.
    pub fn rayleigh(&self) -> Option<Rayleigh> {
        self.damping.as_ref().map(|(_, r)| *r)
    }

    /// The power the damping takes at the model's velocities v: vᵀ C v.
    pub fn dissipation(&self, v: &[f64]) -> f64 {
        self.with_damping_force(v, |cv| v.iter().zip(cv).map(|(a, b)| a * b).sum())
            .unwrap_or(0.0)
    }

    /// The beam's own weight as the model's unknowns feel it, dotted with their displacements:
    /// the work the weight has done since the undeformed state is this less its start value.
    pub fn weight_dot(&self, q: &[f64]) -> f64 {
        let Some(w) = self.beam.weight() else {
            return 0.0;
        };
        let q = self.to_mesh(q);
        w.iter().zip(q.iter()).map(|(a, b)| a * b).sum()
    }

    /// The mass in the model's unknowns: the mesh's, or the identity of mass-normalised modes.
    pub fn model_mass(&self) -> &Sparse {
        self.modal.map_or(self.beam.mass(), |m| m.mass())
    }

    /// The beam's kinetic and strain energy at the model's (q, v): ½ vᵀM v and the strain
    /// energy of the beam (½ qᵀK₀q on the linear models; on a modal beam ½|η̇|² and ½ηᵀΩ²η).
    pub fn energies(&self, q: &[f64], v: &[f64]) -> (f64, f64) {
        match self.modal {
            Some(m) => (
                0.5 * v.iter().map(|x| x * x).sum::<f64>(),
                0.5 * q
                    .iter()
                    .zip(&m.omega)
                    .map(|(x, w)| (w * x).powi(2))
                    .sum::<f64>(),
            ),
            None => {
                let mut mv = self.scratch.borrow_mut();
                crate::linalg::mul(self.beam.mass(), v, &mut mv);
                let kinetic = 0.5 * v.iter().zip(mv.iter()).map(|(a, b)| a * b).sum::<f64>();
                (kinetic, self.beam.strain_energy(q))
            }
        }
    }

    /// The mesh's displacements (or velocities) from the model's unknowns.
    pub fn to_mesh<'y>(&self, z: &'y [f64]) -> Cow<'y, [f64]> {
        match self.modal {
            None => Cow::Borrowed(z),
            Some(m) => {
                let mut q = vec![0.0; self.beam.dim()];
                m.expand(z, &mut q);
                Cow::Owned(q)
            }
        }
    }

    /// The model's unknowns from the mesh's displacements (or velocities).
    pub fn from_mesh(&self, q: &[f64]) -> Vec<f64> {
        match self.modal {
            None => q.to_vec(),
            Some(m) => {
                let mut eta = vec![0.0; m.dim()];
                m.amplitudes_of(q, &mut eta);
                eta
            }
        }
    }
}

impl Structure for LoadedBeam<'_> {
    fn dim(&self) -> usize {
        self.modal.map_or(self.beam.dim(), |m| m.dim())
    }
    fn mass(&self, _t: f64, _q: &[f64]) -> Cow<'_, Sparse> {
        Cow::Borrowed(self.model_mass())
    }
    fn force(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        let mut scratch = self.scratch.borrow_mut();
        match self.modal {
            None => {
                self.external(t, f);
                self.beam.internal_force(q, &mut scratch);
                f.iter_mut().zip(scratch.iter()).for_each(|(a, b)| *a -= b);
            }
            Some(m) => {
                if let Some(w) = self.beam.weight() {
                    m.project(w, f);
                } else {
                    f.fill(0.0);
                }
                // A point load or axle reaches only its element's unknowns: projected there.
                let mut add = |i: usize, v: f64| m.add_row(i, v, f);
                for l in self.active(t) {
                    self.beam.point_load_terms(l.x, l.force, l.mz, &mut add);
                }
                for (x, p) in self.axles(t) {
                    self.beam.point_load_terms(x, [0.0, -p], 0.0, &mut add);
                }
                for (k, fk) in f.iter_mut().enumerate() {
                    *fk -= m.omega[k] * m.omega[k] * q[k];
                }
            }
        }
        self.with_damping_force(v, |cv| {
            f.iter_mut().zip(cv).for_each(|(a, b)| *a -= b);
        });
    }
    fn damping(&self) -> Option<Cow<'_, Sparse>> {
        self.damping.as_ref().map(|(c, _)| Cow::Borrowed(c))
    }
    fn norm_weights(&self) -> Option<Vec<f64>> {
        self.modal.map(|m| m.displacement_per_amplitude())
    }
    fn stiffness(&self, _t: f64, q: &[f64]) -> Sparse {
        match self.modal {
            None => self.beam.tangent(q),
            Some(m) => m.stiffness().clone(),
        }
    }
}

impl SecondOrderProblem for LoadedBeam<'_> {
    type Event = NoEvent;
    fn breakpoints(&self) -> Vec<f64> {
        let train = self.train_breakpoints();
        self.loads
            .iter()
            .flat_map(|l| [l.from, l.until])
            .chain(train)
            .filter(|t| t.is_finite())
            .collect()
    }
    fn enter_segment(&self, start: f64, end: f64) {
        self.segment.set(0.5 * (start + end));
    }
}

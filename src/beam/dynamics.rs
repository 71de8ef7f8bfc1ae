//! The loaded beam as a structural problem M q'' = F_ext(t) − F_int(q) for the integrators;
//! on a modal beam the unknowns are the modal amplitudes, η̈ = Φᵀ F_ext(t) − Ω² η.
//! Loads switch on and off at their `from`/`until` times: those are breakpoints, and within
//! each stretch between them the set of active loads is fixed (the integrator names the
//! stretch), so no stage ever sees a load on the wrong side of its jump.

use std::borrow::Cow;
use std::cell::{Cell, OnceCell, RefCell};
use std::rc::Rc;

use super::damping::Rayleigh;
use super::load::PointLoad;
use super::modal::ModalBasis;
use super::train::{RidingAxle, Train, TrainModel};
use super::{Beam, PastFreeEnd, RowAlong};
use crate::linalg::{Assembly, LowRank, Sparse};
use crate::ode::second_order::{LinearModal, SecondOrderProblem, Structure};
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
    /// Per mode, its shape along each element in the directions along and across the axis,
    /// in powers of ξ: what a moving force reads of it (formed where a step first asks).
    modes_along: OnceCell<Vec<RowAlong>>,
    /// When an axle enters or leaves the beam.
    train_breakpoints: Vec<f64>,
    /// Internal forces, kept so that each force evaluation does not allocate.
    scratch: RefCell<Vec<f64>>,
    /// C v, in the model's unknowns, kept for the same reason.
    damped: RefCell<Vec<f64>>,
    /// The moving masses riding at the last t asked for: a force evaluation, the mass, its
    /// update and the ledger all ask at one t, and each axle's patch basis was most of a
    /// moving-mass run's cost.
    riding_at: RefCell<Option<(f64, Rc<[RidingAxle]>)>>,
    /// What rides under moving forces, formed once: the modal beam's force is sampled at
    /// every step.
    no_riders: Rc<[RidingAxle]>,
    /// The longest step anything may take on this beam: a share of its lowest mode's period
    /// ([`STEPS_PER_PERIOD`]), once [`LoadedBeam::resolving`] has set it.
    longest_step: f64,
    /// Whether the integration is exact (`stepped_exactly`).
    exact: bool,
    /// Whether the steps may stride past `longest_step`: set where the integration is exact
    /// and no load is left to come ([`LoadedBeam::stride_freely`]).
    striding: Cell<bool>,
    /// The lowest mode's circular frequency, and the highest whose accelerations are reported
    /// (the cutoff's): where a modal beam's errors are weighed (see `norm_weights`).
    lowest: f64,
    reported: f64,
    /// On a mesh, the modes below the cutoff as rows of the error norm (see `norm_rows`).
    reported_modes: Option<crate::ode::ModeRows>,
}

/// The fewest steps a period of the beam's lowest mode is cut into. Where the response has
/// fallen below atol the error estimate no longer limits the step, and a step over several
/// periods would leave the dense output (a cubic between the step's ends) nothing of the
/// vibration it reports, and the trapezoidal rule's damping of it nothing to act on; at
/// sixteen steps a period the cubic is within 6·10⁻⁵ of a sine's amplitude ((ωh)⁴/384).
pub const STEPS_PER_PERIOD: f64 = 16.0;

/// How many of those shares an exact step may span while a train is on the beam: a train slow
/// enough to take longer over an element is still watched at the cutoff's pace, within the
/// watch's bound on the pairs of samples one step holds, on bridges whose lowest mode is above
/// 0.3 Hz.
const EXACT_STRIDE: f64 = 32.0;

/// Steps a moving mass (or a vehicle's wheel with a mass) takes at least to cross an element
/// of the mesh. It bears the deck's acceleration under it, which every mode of the mesh
/// carries; the implicit steps hold a mode faster than themselves at its response to the load
/// as it stands, to the order of their stages, and the load turns at each element it crosses.
/// A 510 kg wheel under β damping, four steps an element, read its largest contact force
/// 2.8 % high; sixteen, within 10⁻⁶.
pub const STEPS_OVER_AN_ELEMENT_UNDER_A_MASS: f64 = 16.0;

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
            modes_along: OnceCell::new(),
            train_breakpoints: train_breakpoints(beam, train),
            scratch: RefCell::new(vec![0.0; beam.dim()]),
            damped: RefCell::new(vec![0.0; modal.map_or(beam.dim(), |m| m.dim())]),
            riding_at: RefCell::new(None),
            no_riders: Rc::from([]),
            longest_step: f64::INFINITY,
            exact: false,
            striding: Cell::new(false),
            lowest: 0.0,
            reported: 0.0,
            reported_modes: None,
        }
    }

    /// The beam whose steps resolve its lowest mode, of circular frequency `omega1`.
    pub fn resolving(mut self, omega1: f64) -> Self {
        if omega1 > 0.0 && omega1.is_finite() {
            self.longest_step = std::f64::consts::TAU / omega1 / STEPS_PER_PERIOD;
            self.lowest = omega1;
        }
        self
    }

    /// The longest step a time-stepped integration of this beam takes ([`Self::resolving`]);
    /// infinite where no lowest mode was set.
    pub fn longest_step(&self) -> f64 {
        self.longest_step
    }

    /// The beam integrated exactly (`exact-modal`): its dense output holds every vibration
    /// however long the step, so while a train is on the beam its passage over an element
    /// bounds the step, and [`EXACT_STRIDE`] shares of the lowest period. With no load on it
    /// one share still does, until the free vibration has settled: the watch checks at every
    /// step whether it has.
    pub fn stepped_exactly(mut self, exact: bool) -> Self {
        self.exact = exact;
        self
    }

    /// Let the steps from here on be as long as the integrator allows: where it integrates the
    /// modes exactly, with no load left to come and nothing left to watch, a share of the
    /// lowest period resolves nothing the run reports.
    pub fn stride_freely(&self) {
        self.striding.set(true);
    }

    /// The beam whose accelerations are reported up to the circular frequency `cutoff`.
    pub fn reporting_accelerations_below(mut self, cutoff: f64) -> Self {
        self.reported = cutoff;
        self
    }

    /// The mesh whose accelerations are reported in the modes `shapes` (mass-normalised, one
    /// column each) of circular frequencies `omega`: each weighs in the error norm as the
    /// displacement of the lowest mode that makes the acceleration it makes, as a modal beam's
    /// amplitudes do (`norm_weights`). Weighed by the nodal displacements alone, a 10 t force
    /// crossing a 30 m steel deck at 3 m/s read the quarter point's largest acceleration 2.166
    /// m/s² against 2.150 converged (with the modes weighed, 2.151): an error of atol in the
    /// fourth mode's displacement is (ω₄/ω₁)² atol in the acceleration's units.
    pub fn weighing_reported_modes(
        mut self,
        shapes: &nalgebra::DMatrix<f64>,
        omega: &[f64],
    ) -> Self {
        if self.modal.is_some() || !(self.lowest > 0.0) {
            return self;
        }
        let rows: Vec<Vec<f64>> = (0..shapes.ncols())
            .zip(omega)
            .filter(|(_, w)| **w > self.lowest)
            .map(|(k, w)| {
                let shape: Vec<f64> = shapes.column(k).iter().copied().collect();
                let largest = shape.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                let weight = (w / self.lowest).powi(2) * largest;
                let mut row = vec![0.0; shape.len()];
                crate::linalg::mul(self.beam.mass(), &shape, &mut row);
                row.iter_mut().for_each(|r| *r *= weight);
                row
            })
            .collect();
        self.reported_modes = (!rows.is_empty()).then(|| rows.into());
        self
    }

    /// `then` of the damping force C v at the model's velocities v; `None` undamped.
    fn with_damping_force<R>(&self, v: &[f64], then: impl FnOnce(&[f64]) -> R) -> Option<R> {
        let (c, _) = self.damping.as_ref()?;
        let mut cv = self.damped.borrow_mut();
        // The exact modal integration samples the force with the state at rest.
        if v.iter().all(|&x| x == 0.0) {
            cv.fill(0.0);
        } else {
            crate::linalg::mul(c, v, &mut cv);
        }
        Some(then(&cv))
    }

    /// The stretch between breakpoints the run is in, by its midpoint (NaN outside a run):
    /// which of the train's axles are on at its ends.
    pub fn stretch(&self) -> f64 {
        self.segment.get()
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
        self.external_terms(t, |i, v| f[i] += v);
    }

    /// The terms (unknown, value) of the loads on the mesh at t, as [`Self::external`] adds
    /// them, handed to `add` one by one: a reader of a few rows against the loads (a probe's
    /// static correction) then touches the few unknowns under each load, not the whole mesh.
    pub fn external_terms(&self, t: f64, mut add: impl FnMut(usize, f64)) {
        self.standing_terms(t, &mut add);
        for (x, p) in self.axles(t) {
            self.beam.point_load_terms(x, [0.0, -p], 0.0, &mut add);
        }
        for r in self.riding(t).iter() {
            r.spread(self.beam.to_local([0.0, -r.load]), [0.0; 2], &mut add);
        }
    }

    /// Add the riding axles' inertia from the motion of the beam under them, −m (2 v ṙ' +
    /// v² r''), at the mesh's (q, v) as `q_at` and `v_at` read them, through `add`: the part
    /// of their force on the beam that is not their weight (which is F_ext) and not their
    /// mass times the beam's acceleration (which is the mass matrix's).
    fn add_axle_inertia(
        &self,
        t: f64,
        q_at: impl Fn(usize) -> f64,
        v_at: impl Fn(usize) -> f64,
        mut add: impl FnMut(usize, f64),
    ) {
        let Some(speed) = self.moving_masses() else {
            return;
        };
        for r in self.riding(t).iter() {
            let c = r.convective(speed, &q_at, &v_at);
            r.spread([0.0; 2], c, &mut add);
        }
    }

    /// The loads that do not move, handed term by term to `add` as [`Self::external_terms`]
    /// does: the point loads acting at t and the beam's weight.
    pub fn standing_terms(&self, t: f64, mut add: impl FnMut(usize, f64)) {
        for l in self.active(t) {
            self.beam.point_load_terms(l.x, l.force, l.mz, &mut add);
        }
        if let Some(weight) = self.beam.weight() {
            weight.iter().enumerate().for_each(|(i, &v)| add(i, v));
        }
    }

    /// The standing loads' force on the modes at t into `f`: the weight's projection and
    /// each point load's, projected at its element's unknowns.
    fn standing_on_modes(&self, m: &ModalBasis, t: f64, f: &mut [f64]) {
        match self.beam.weight() {
            Some(w) => m.project(w, f),
            None => f.fill(0.0),
        }
        let mut add = |i: usize, v: f64| m.add_row(i, v, f);
        for l in self.active(t) {
            self.beam.point_load_terms(l.x, l.force, l.mz, &mut add);
        }
    }

    /// The train's moving forces on the beam over [t0, t1], a stretch between two of its
    /// breakpoints: each one's place at t0 and at t1, and its force.
    pub fn axle_paths(&self, t0: f64, t1: f64) -> Vec<(f64, f64, f64)> {
        let length = self.beam.length;
        let when = if self.segment.get().is_nan() {
            0.5 * (t0 + t1)
        } else {
            self.segment.get()
        };
        let Some(train) = self.moving_forces() else {
            return Vec::new();
        };
        let place = |a: usize, t: f64| train.position(a, t).clamp(0.0, length);
        train
            .on(length, when)
            .map(|a| (place(a, t0), place(a, t1), train.loads[a]))
            .collect()
    }

    /// The train's moving forces on the beam at t, with their forces (none for moving masses).
    /// An axle enters and leaves only at a breakpoint, so which axles are on is decided within
    /// the current stretch between breakpoints: where an end is free, an axle entering there
    /// is a jump of the load that no stage may see on the wrong side.
    pub fn axles(&self, t: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
        let length = self.beam.length;
        let when = if self.segment.get().is_nan() {
            t
        } else {
            self.segment.get()
        };
        let train = self.moving_forces();
        let on = train.map_or(0..0, |train| train.on(length, when));
        on.filter_map(move |a| {
            train.map(|train| (train.position(a, t).clamp(0.0, length), train.loads[a]))
        })
    }

    /// The train, where its axles are moving forces.
    fn moving_forces(&self) -> Option<&'a Train> {
        self.train.filter(|tr| tr.model == TrainModel::MovingForce)
    }

    /// The train's axles riding on the beam at t as moving masses (none for moving forces):
    /// each while its patch overlaps the beam, so that it comes on and goes off smoothly.
    pub fn riding(&self, t: f64) -> Rc<[RidingAxle]> {
        if self.moving_masses().is_none() {
            return self.no_riders.clone();
        }
        if let Some((at, axles)) = &*self.riding_at.borrow() {
            if *at == t {
                return axles.clone();
            }
        }
        let axles: Rc<[RidingAxle]> = self.riding_now(t).into();
        *self.riding_at.borrow_mut() = Some((t, axles.clone()));
        axles
    }

    fn riding_now(&self, t: f64) -> Vec<RidingAxle> {
        let Some(train) = self.train.filter(|tr| tr.model == TrainModel::MovingMass) else {
            return Vec::new();
        };
        let (b, length) = (train.patch, self.beam.length);
        (0..train.axles.len())
            .filter_map(|a| {
                let x = train.position(a, t);
                (x > -b && x < length + b).then(|| RidingAxle {
                    x,
                    mass: train.masses[a],
                    load: train.loads[a],
                    basis: self.beam.patch_basis_at(x, b, PastFreeEnd::Slab),
                })
            })
            .collect()
    }

    /// The train's speed, and whether its axles are moving masses.
    fn moving_masses(&self) -> Option<f64> {
        self.train
            .filter(|tr| tr.model == TrainModel::MovingMass)
            .map(|tr| tr.speed)
    }

    /// The inertia the riding axles add to the mass at t, in the model's unknowns: m g gᵀ for
    /// each axle and each direction of the beam frame (on a modal beam the rows are Φᵀ g).
    pub fn axle_inertia(&self, t: f64) -> LowRank {
        let mut out = LowRank::new();
        for r in self.riding(t).iter() {
            for row in r.rows() {
                let row = match self.modal {
                    None => row,
                    Some(m) => {
                        let mut dense = vec![0.0; m.dim()];
                        row.iter().for_each(|&(i, g)| m.add_row(i, g, &mut dense));
                        dense.into_iter().enumerate().collect()
                    }
                };
                out.push((r.mass, row));
            }
        }
        out
    }

    /// Unknown i of the mesh from the model's unknowns y: y_i itself, or on a modal beam
    /// Σ_k Φ_ik y_k, without expanding the whole mesh.
    fn on_mesh_at(&self, i: usize, y: &[f64]) -> f64 {
        match self.modal {
            None => y[i],
            Some(m) => m.value_at(i, y),
        }
    }

    /// The force a riding axle exerts on the beam (beam frame), m (g − d²r/dt²), and the
    /// velocity ṙ of the point it rides on, at the model's displacements q, velocities v and
    /// accelerations a.
    fn riding_force(
        &self,
        r: &RidingAxle,
        speed: f64,
        q: &[f64],
        v: &[f64],
        a: &[f64],
    ) -> ([f64; 2], [f64; 2]) {
        let acc = self.riding_acceleration(r, speed, q, v, a);
        let [gx, gy] = r.rows();
        let force = r.spread(self.beam.to_local([0.0, -r.load]), acc, |_, _| ());
        (force, [self.row_dot(&gx, v), self.row_dot(&gy, v)])
    }

    /// d²r/dt² (beam frame) of the point a riding axle rides on, at the model's (q, v, a).
    fn riding_acceleration(
        &self,
        r: &RidingAxle,
        speed: f64,
        q: &[f64],
        v: &[f64],
        a: &[f64],
    ) -> [f64; 2] {
        let [gx, gy] = r.rows();
        let c = r.convective(speed, |i| self.on_mesh_at(i, q), |i| self.on_mesh_at(i, v));
        [c[0] + self.row_dot(&gx, a), c[1] + self.row_dot(&gy, a)]
    }

    /// A row over the mesh's unknowns against the model's unknowns y.
    fn row_dot(&self, g: &[(usize, f64)], y: &[f64]) -> f64 {
        g.iter().map(|&(i, c)| c * self.on_mesh_at(i, y)).sum()
    }

    /// The riding masses' inertia, −m d²r/dt² at the model's (q, v, a), added to f on the
    /// mesh's unknowns as the equations spread it: with [`Self::external`] each moving mass's
    /// force in full, which the modes a modal beam leaves out answer statically.
    pub fn add_riding_inertia(&self, t: f64, q: &[f64], v: &[f64], a: &[f64], f: &mut [f64]) {
        let Some(speed) = self.moving_masses() else {
            return;
        };
        for r in self.riding(t).iter() {
            let acc = self.riding_acceleration(r, speed, q, v, a);
            r.spread([0.0; 2], acc, |i, x| f[i] += x);
        }
    }

    /// The train's axles as point forces on the beam (global) at the model's (q, v, a): a
    /// moving mass's force taken at its centre, which is exact for the support reactions once
    /// its patch is clear of the supports.
    pub fn axle_forces(&self, t: f64, q: &[f64], v: &[f64], a: &[f64]) -> Vec<(f64, [f64; 2])> {
        let mut out: Vec<(f64, [f64; 2])> = self.axles(t).map(|(x, p)| (x, [0.0, -p])).collect();
        if let Some(speed) = self.moving_masses() {
            for r in self.riding(t).iter() {
                let (force, _) = self.riding_force(r, speed, q, v, a);
                out.push((r.x.clamp(0.0, self.beam.length), self.beam.to_global(force)));
            }
        }
        out
    }

    /// The power of the train's axles on the beam at the model's (q, v) and, for moving
    /// masses, whose force holds the beam's acceleration, a: read at the axles' own unknowns,
    /// so a modal beam is not expanded over the mesh at every step.
    pub fn train_power(&self, t: f64, q: &[f64], v: &[f64], a: Option<&[f64]>) -> f64 {
        let mut forces = 0.0;
        for (x, p) in self.axles(t) {
            // An axle's force has no moment and, on a level beam, no axial part: the rates of
            // those unknowns are not needed.
            self.beam.point_load_terms(x, [0.0, -p], 0.0, |i, f| {
                if f != 0.0 {
                    forces += f * self.on_mesh_at(i, v);
                }
            });
        }
        let masses = match (self.moving_masses(), a) {
            (Some(speed), Some(a)) => self
                .riding(t)
                .iter()
                .map(|r| {
                    let (f, rd) = self.riding_force(r, speed, q, v, a);
                    f[0] * rd[0] + f[1] * rd[1]
                })
                .sum(),
            _ => 0.0,
        };
        forces + masses
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

/// When each axle enters and leaves the beam (a moving mass as its patch first and last
/// overlaps it), whatever the supports: an axle entering a beam at rest over a support that
/// holds w does nothing at first, so the error estimate sees nothing and would let a step grow
/// past it (or past a whole train); every step ends where an axle comes on or goes off.
fn train_breakpoints(beam: &Beam, train: Option<&Train>) -> Vec<f64> {
    let Some(train) = train else {
        return Vec::new();
    };
    let reach = match train.model {
        TrainModel::MovingForce => 0.0,
        TrainModel::MovingMass => train.patch,
    };
    let length = beam.length;
    train
        .axles
        .iter()
        .flat_map(|d| {
            [
                (d - reach) / train.speed,
                (d + length + reach) / train.speed,
            ]
        })
        .collect()
}

impl Structure for LoadedBeam<'_> {
    fn dim(&self) -> usize {
        self.modal.map_or(self.beam.dim(), |m| m.dim())
    }
    fn mass(&self, t: f64, _q: &[f64]) -> Cow<'_, Sparse> {
        let added = self.axle_inertia(t);
        if added.is_empty() {
            return Cow::Borrowed(self.model_mass());
        }
        let mut a = Assembly::new(self.dim());
        a.add_sparse(self.model_mass(), 1.0, 0, 0);
        for (w, g) in &added {
            for &(i, gi) in g {
                for &(j, gj) in g {
                    a.add(i, j, w * gi * gj);
                }
            }
        }
        Cow::Owned(a.build())
    }
    /// Moving masses make the mass change as they travel: the beam's plus the axles' m g gᵀ.
    fn mass_is_constant(&self) -> bool {
        self.moving_masses().is_none()
    }
    fn mass_split(&self, t: f64, _q: &[f64]) -> Option<(&Sparse, LowRank)> {
        self.moving_masses()
            .map(|_| (self.model_mass(), self.axle_inertia(t)))
    }
    fn mass_mul(&self, t: f64, _q: &[f64], a: &[f64], out: &mut [f64]) {
        crate::linalg::mul(self.model_mass(), a, out);
        for (w, g) in self.axle_inertia(t) {
            let ga = w * g.iter().map(|&(i, c)| c * a[i]).sum::<f64>();
            g.iter().for_each(|&(i, c)| out[i] += c * ga);
        }
    }
    fn force(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        let mut scratch = self.scratch.borrow_mut();
        match self.modal {
            None => {
                self.external(t, f);
                self.beam.internal_force(q, &mut scratch);
                f.iter_mut().zip(scratch.iter()).for_each(|(a, b)| *a -= b);
                self.add_axle_inertia(t, |i| q[i], |i| v[i], |i, x| f[i] += x);
            }
            Some(m) => {
                self.standing_on_modes(m, t, f);
                // A point load or axle reaches only its element's unknowns: projected there.
                let mut add = |i: usize, v: f64| m.add_row(i, v, f);
                for (x, p) in self.axles(t) {
                    self.beam.point_load_terms(x, [0.0, -p], 0.0, &mut add);
                }
                for r in self.riding(t).iter() {
                    r.spread(self.beam.to_local([0.0, -r.load]), [0.0; 2], &mut add);
                }
                self.add_axle_inertia(t, |i| m.value_at(i, q), |i| m.value_at(i, v), add);
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
    /// A mode's error counts as the displacement it makes, and where its accelerations are
    /// reported as the displacement of the lowest mode that would make the same acceleration:
    /// the same error in the third mode moves the deck's acceleration (ω₃/ω₁)² times as much
    /// as in the first, and a weight of the displacement alone let D44's largest acceleration
    /// come out 5 % low with every displacement within 10⁻⁴.
    fn norm_weights(&self) -> Option<Vec<f64>> {
        self.weights_by_acceleration_up_to(self.reported)
    }
    fn norm_rows(&self) -> Option<crate::ode::ModeRows> {
        self.reported_modes.clone()
    }
    /// A modal beam under moving forces, point loads and its weight: the modes' oscillators,
    /// damped by α + β ω², under a force that is, between the axles' crossings of the mesh's
    /// nodes, a polynomial of the elements' degree in t (the load's shape functions at a
    /// point that moves at constant speed).
    fn linear_modal(&self) -> Option<LinearModal> {
        let m = self.modal?;
        if self.moving_masses().is_some() {
            return None;
        }
        let rayleigh = self.rayleigh();
        Some(LinearModal {
            stiffness: m.omega.iter().map(|w| w * w).collect(),
            damping: m
                .omega
                .iter()
                .map(|w| rayleigh.map_or(0.0, |r| r.alpha + r.beta * w * w))
                .collect(),
            degree: self.beam.spec.order,
        })
    }
    fn stiffness(&self, _t: f64, q: &[f64]) -> Sparse {
        match self.modal {
            None => self.beam.tangent(q),
            Some(m) => m.stiffness().clone(),
        }
    }
    /// A modal beam under its weight, standing point loads and moving forces: the standing
    /// loads' projection, constant over a stretch, and each axle's, which between two node
    /// crossings reads each mode's shape along one element at a ξ linear in time.
    fn force_at_rest_over(&self, t: f64, h: f64) -> Option<Vec<Vec<f64>>> {
        let m = self.modal?;
        if self.moving_masses().is_some() || !(h > 0.0) {
            return None;
        }
        let mut constant = vec![0.0; m.dim()];
        self.standing_on_modes(m, t + 0.5 * h, &mut constant);
        let mut g: Vec<Vec<f64>> = constant
            .into_iter()
            .map(|c| self.beam.polynomial_along_from(c))
            .collect();
        let along = self.modes_along.get_or_init(|| {
            let mut unit = vec![0.0; m.dim()];
            let mut shape = vec![0.0; self.beam.dim()];
            (0..m.dim())
                .map(|k| {
                    unit.fill(0.0);
                    unit[k] = 1.0;
                    m.expand(&unit, &mut shape);
                    self.beam.row_along(&shape)
                })
                .collect()
        });
        self.beam
            .add_paths_along(along, &self.axle_paths(t, t + h), &mut g)?;
        Some(g)
    }
}

impl LoadedBeam<'_> {
    /// The modal error weights with every mode up to the circular frequency `reported` counted
    /// by the acceleration it makes (see `norm_weights`).
    fn weights_by_acceleration_up_to(&self, reported: f64) -> Option<Vec<f64>> {
        let m = self.modal?;
        let mut w = m.displacement_per_amplitude();
        if self.lowest > 0.0 {
            for (w, omega) in w.iter_mut().zip(&m.omega) {
                if crate::beam::modal::within_cutoff(*omega, reported) {
                    *w *= (omega / self.lowest).powi(2).max(1.0);
                }
            }
        }
        Some(w)
    }

    /// The modal error weights where a rider's contact force is reported: the force is the
    /// rider's mass times the beam's acceleration under it, in every mode the beam holds.
    pub fn contact_norm_weights(&self) -> Option<Vec<f64>> {
        self.weights_by_acceleration_up_to(f64::INFINITY)
    }

    /// The longest step at t: a share of the lowest mode's period (see [`STEPS_PER_PERIOD`]),
    /// and while an axle of the train is on the beam the time it takes to cross one element. An axle's load on the mesh changes smoothly within an element and
    /// with a kink at each node, so no step may carry it over a node unseen, and none can
    /// jump it across the span.
    pub fn load_step_bound(&self, t: f64) -> f64 {
        if self.striding.get() {
            return f64::INFINITY;
        }
        let Some(train) = self.train else {
            return self.longest_step;
        };
        let reach = match train.model {
            TrainModel::MovingForce => 0.0,
            TrainModel::MovingMass => train.patch,
        };
        let length = self.beam.length;
        let on = (0..train.axles.len()).any(|a| {
            let x = train.position(a, t);
            x >= -reach && x <= length + reach
        });
        let passage = match train.model {
            TrainModel::MovingMass if self.modal.is_none() => {
                self.beam.element_length() / (STEPS_OVER_AN_ELEMENT_UNDER_A_MASS * train.speed)
            }
            _ => self.beam.element_length() / train.speed,
        };
        if on && self.exact {
            passage.min(EXACT_STRIDE * self.longest_step)
        } else if on {
            self.longest_step.min(passage)
        } else {
            self.longest_step
        }
    }
    /// On a modal beam in the state (η, η̇), the longest piece of time over which the
    /// five-point Gauss–Lobatto rule integrates each mode's share of the powers to `tol` of
    /// the beam's energy: mode k moving at ω_k with a share s_k of the energy as kinetic
    /// energy errs by about 7.0·10⁻¹⁰ (ω_k h)⁸ · √s_k, and by no more than its share however
    /// long the piece, so that modes whose √s_k is below `tol` set no bound. `None` on a mesh,
    /// or at rest.
    pub fn quadrature_piece(&self, eta: &[f64], eta_dot: &[f64], tol: f64) -> Option<f64> {
        let modal = self.modal?;
        let energy: f64 = eta
            .iter()
            .zip(eta_dot)
            .zip(&modal.omega)
            .map(|((x, v), w)| 0.5 * (v * v + (w * x).powi(2)))
            .sum();
        if energy.is_nan() || energy <= 0.0 {
            return None;
        }
        eta_dot
            .iter()
            .zip(&modal.omega)
            .filter(|(v, w)| **v != 0.0 && **w > 0.0)
            .map(|(v, w)| ((0.5 * v * v / energy).sqrt(), w))
            .filter(|(share, _)| *share > tol)
            .map(|(share, w)| (tol / (LOBATTO_ERROR * share)).powf(0.125) / w)
            .min_by(f64::total_cmp)
    }

    /// The shortest piece [`Self::quadrature_piece`] can ask for at `tol`: the highest mode's,
    /// moving alone. `None` on a mesh.
    pub fn quadrature_floor(&self, tol: f64) -> Option<f64> {
        let highest = self.modal?.omega.last().copied()?;
        (highest > 0.0).then(|| (tol / LOBATTO_ERROR).powf(0.125) / highest)
    }

    /// While an axle of the train is on the beam, the time it takes to cross the shortest
    /// length the beam's response varies over along the span: an element (its shape functions)
    /// or, on a modal beam, the span over the modes kept (the highest one's half-wave). The
    /// axles' power on the beam changes at that pace. `None` with no axle on the beam.
    pub fn load_passage(&self, t: f64) -> Option<f64> {
        let train = self.train?;
        let length = self.beam.length;
        let on = !train.on(length, t).is_empty();
        (on && train.speed > 0.0).then(|| self.finest_length() / train.speed)
    }

    /// The shortest length the beam's response varies over along the span: an element (its
    /// shape functions) or, on a modal beam, the span over the modes kept.
    pub fn finest_length(&self) -> f64 {
        let length = self.beam.length;
        self.modal
            .map_or(f64::INFINITY, |m| length / m.dim().max(1) as f64)
            .min(self.beam.element_length())
    }
}

/// The five-point Gauss–Lobatto rule's error on ∫cos(ωt + φ) over a piece h, of h, per
/// (ωh)⁸: n(n−1)³((n−2)!)⁴ / ((2n−1)((2n−2)!)³) with n = 5.
const LOBATTO_ERROR: f64 = 7.03e-10;

impl SecondOrderProblem for LoadedBeam<'_> {
    type Event = NoEvent;
    fn max_step(&self, t: f64, _q: &[f64], _v: &[f64]) -> f64 {
        self.load_step_bound(t)
    }
    /// Each axle's crossing of each node of the mesh.
    fn kinks(&self) -> Vec<f64> {
        let Some(train) = self.train else {
            return Vec::new();
        };
        let h = self.beam.element_length();
        let nodes = self.beam.spec.elements + 1;
        train
            .axles
            .iter()
            .flat_map(|d| (0..nodes).map(move |j| (j as f64 * h + d) / train.speed))
            .collect()
    }
    fn breakpoints(&self) -> Vec<f64> {
        let train = self.train_breakpoints.iter().copied();
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

//! The disk on the beam: the two bodies moving together, coupled by one of four laws, each in
//! a file of its own behind the [`law`] trait (the rider's inertia and force as the beam's
//! unknowns z feel them, and its motion for the observation); `contact.rs` is the geometry of
//! the contact on the deformed axis. [`DiskOnBeam`] is the coupled structure for any law: it
//! assembles the rider's terms into the beam's equations, watches the events, and observes.
//!
//! - `consistent.rs` (the default): the disk stays on the moving beam. Unknowns z = (q, s),
//!   s the material point of contact; the disk's rotation θ is not an unknown. Centre
//!   c(q, s) = r(s) + a n(s). Rolling without slip, measured against the beam's own material
//!   velocity at s, is θ̇ = dψ/dt − |r'| ṡ / a: a velocity constraint B(z) ż − θ̇ = 0, not
//!   integrable once the axis stretches. Lagrange–d'Alembert with the multiplier λ gives
//!   C θ̈ = λ for θ, and for z, with T_z = ½ q̇ᵀ M q̇ + ½ m |ċ|², V = U(q) + m g c_Y:
//!   (M ⊕ 0 + m J_cᵀ J_c + C Bᵀ B) z̈ = F(q) − m J_cᵀ (J̇_c ż − g) − C Bᵀ (Ḃ ż),
//!   J_c = ∂c/∂z. The power of the constraint force is λ (B ż − θ̇) = 0, so the total energy
//!   T_z + ½ C θ̇² + V is conserved. Eliminating λ shows the beam feels exactly −F_contact at s
//!   through the shape functions: the terms of the normal's rotation cancel with the torque.
//! - `thesis.rs`: thesis Table 9 as published (errata 2–3 corrected), the disk rolling on the
//!   axis as if it were frozen; with a first-order integrator the run takes the published
//!   3n + 6 system of [`thesis_system`] instead.
//! - `moving_mass.rs`: a point mass at s = s0 + v0 t on the axis, following its displacement
//!   with its inertia; `moving_force.rs`: the constant weight m g at s = s0 + v0 t. Both are
//!   prescribed motions: the system is the beam alone, and the work the moving load does on
//!   it is the `work` of the energy budget.

mod consistent;
pub mod contact;
pub mod landing;
pub(crate) mod law;
mod moving_force;
mod moving_mass;
pub mod patch;
mod thesis;
pub mod thesis_system;
pub mod vehicles;

use std::borrow::Cow;
use std::cell::{OnceCell, RefCell};
use std::ops::Range;
use std::rc::Rc;

use contact::{dot, AxisPoint, Row};
use law::{AddedMass, Law, Rider};

use crate::beam::dynamics::LoadedBeam;
use crate::beam::{Beam, NodeBasis};
use crate::disk::Disk;
use crate::linalg::{self, Assembly, AssemblyPattern, LowRank, Sparse, SparseLu, Woodbury};
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::EventSpec;
use crate::rolling::{DiskObservation, StopReason, FIT_MARGIN};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coupling {
    Consistent,
    Thesis,
    MovingMass,
    MovingForce,
}

impl Coupling {
    pub const ALL: [Coupling; 4] = [
        Coupling::Consistent,
        Coupling::Thesis,
        Coupling::MovingMass,
        Coupling::MovingForce,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Coupling::Consistent => "consistent",
            Coupling::Thesis => "thesis",
            Coupling::MovingMass => "moving-mass",
            Coupling::MovingForce => "moving-force",
        }
    }

    pub fn from_name(name: &str) -> Option<Coupling> {
        Coupling::ALL.into_iter().find(|c| c.name() == name)
    }

    /// The disk's path is an unknown (not prescribed).
    pub fn rolls(self) -> bool {
        matches!(self, Coupling::Consistent | Coupling::Thesis)
    }
}

/// The disk as a beam scene names it.
#[derive(Clone, Debug)]
pub struct DiskOnBeamSpec {
    pub disk: Disk,
    /// Material point of first contact, along the undeformed axis.
    pub s0: f64,
    pub omega0: f64,
    pub coupling: Coupling,
    pub mu: Option<f64>,
    pub gravity: f64,
    /// Half-width of the contact patch over which the disk touches the axis.
    pub patch: f64,
    /// What happens where the normal force falls to zero.
    pub contact_loss: crate::rolling::ContactLoss,
}

impl DiskOnBeamSpec {
    /// Speed along the axis at t = 0 (Ω < 0 rolls towards +s).
    pub fn v0(&self) -> f64 {
        -self.disk.radius * self.omega0
    }
}

const EVENTS: [EventSpec<StopReason>; 5] = [
    EventSpec {
        reason: StopReason::LeftTrack,
        terminal: true,
    },
    EventSpec {
        reason: StopReason::LeftTrack,
        terminal: true,
    },
    EventSpec {
        reason: StopReason::ContactLost,
        terminal: true,
    },
    EventSpec {
        reason: StopReason::NoFit,
        terminal: true,
    },
    EventSpec {
        reason: StopReason::Slip,
        terminal: true,
    },
];

pub struct DiskOnBeam<'a> {
    pub loaded: &'a LoadedBeam<'a>,
    pub spec: DiskOnBeamSpec,
    /// The coupling law, and the disk as it sees it.
    law: Box<dyn Law>,
    rider: Rider,
    n: usize,
    /// The last observation and its acceleration, keyed by (t, s, ṡ): every event function
    /// of one state needs it, and so does the output row.
    cache: RefCell<Option<([f64; 3], DiskObservation, Option<Vec<f64>>)>>,
    /// `base_mass`, factorised once.
    lu: RefCell<Option<SparseLu>>,
    /// The beam's mass and a unit mass on the contact coordinate.
    base_mass: Sparse,
    /// The patch-averaged shape functions at the last contact point: a step evaluates the
    /// force and the mass at one s several times.
    basis: RefCell<Option<(f64, Vec<NodeBasis>)>>,
    /// The beam's tangent bordered by the contact coordinate, found at its first assembly.
    stiffness_pattern: OnceCell<AssemblyPattern>,
    /// The rider's inertia at the last state asked: Newton takes the mass product, and the
    /// next step its split, at the state its force was evaluated at.
    inertia: LastEvaluation<AddedMass>,
    /// The contact at the last state observed: an output row reads it for the disk, the
    /// reactions, the static correction and the energy.
    observed: LastEvaluation<AxisPoint>,
}

/// A value kept with the time and state (t, y) it was formed at, until another is asked.
pub(crate) struct LastEvaluation<T>(RefCell<Option<(f64, Vec<f64>, Rc<T>)>>);

impl<T> LastEvaluation<T> {
    pub(crate) fn new() -> Self {
        LastEvaluation(RefCell::new(None))
    }

    /// The value at (t, the parts of y in order), formed by `form` unless it is the one kept.
    pub(crate) fn at(&self, t: f64, y: &[&[f64]], form: impl FnOnce() -> T) -> Rc<T> {
        let mut kept = self.0.borrow_mut();
        let same = |k: &[f64]| {
            k.len() == y.iter().map(|p| p.len()).sum::<usize>()
                && y.iter().flat_map(|p| p.iter()).zip(k).all(|(a, b)| a == b)
        };
        if let Some((_, _, v)) = kept.as_ref().filter(|(kt, k, _)| *kt == t && same(k)) {
            return v.clone();
        }
        let v = Rc::new(form());
        *kept = Some((t, y.concat(), v.clone()));
        v
    }

    /// Forget the value kept: what it depends on beside (t, y) has changed.
    pub(crate) fn forget(&self) {
        self.0.borrow_mut().take();
    }
}

impl<'a> DiskOnBeam<'a> {
    pub fn new(loaded: &'a LoadedBeam<'a>, spec: DiskOnBeamSpec) -> Self {
        let gravity = loaded.beam.to_local([0.0, -spec.gravity]);
        let n = loaded.dim();
        let law: Box<dyn Law> = match spec.coupling {
            Coupling::Consistent => Box::new(consistent::Consistent),
            Coupling::Thesis => Box::new(thesis::Thesis),
            Coupling::MovingMass => Box::new(moving_mass::MovingMass),
            Coupling::MovingForce => Box::new(moving_force::MovingForce),
        };
        let nz = n + law.unknowns();
        let mut base = Assembly::new(nz);
        base.add_sparse(loaded.model_mass(), 1.0, 0, 0);
        if nz > n {
            base.add(n, n, 1.0);
        }
        DiskOnBeam {
            base_mass: base.build(),
            n,
            loaded,
            law,
            rider: Rider {
                disk: spec.disk,
                gravity,
                n: loaded.beam.dim(),
                omega0: spec.omega0,
            },
            spec,
            cache: RefCell::new(None),
            lu: RefCell::new(None),
            stiffness_pattern: OnceCell::new(),
            basis: RefCell::new(None),
            inertia: LastEvaluation::new(),
            observed: LastEvaluation::new(),
        }
    }

    /// A row over the mesh's unknowns and the contact coordinate (as the laws write it, s at
    /// the mesh's count) as a row over z: on a modal beam the mesh's part through Φᵀ.
    fn reduce(&self, row: Row) -> Row {
        let Some(modal) = self.loaded.modal else {
            return row;
        };
        let mesh = self.rider.n;
        let mut dense = vec![0.0; self.n];
        let mut out = Vec::with_capacity(self.n + 1);
        let mut on_s = 0.0;
        for (i, v) in row {
            if i < mesh {
                modal.add_row(i, v, &mut dense);
            } else {
                on_s += v;
            }
        }
        out.extend(dense.into_iter().enumerate().filter(|(_, v)| *v != 0.0));
        if on_s != 0.0 {
            out.push((self.n, on_s));
        }
        out
    }

    /// (q, s) on the mesh from z, as the laws read a state at the contact `at`: on a modal
    /// beam q = Φ η, formed only under the patch, where the laws read it.
    fn on_mesh<'y>(&self, at: &AxisPoint, z: &'y [f64]) -> Cow<'y, [f64]> {
        match self.loaded.modal {
            None => Cow::Borrowed(z),
            Some(modal) => {
                let mut out = vec![0.0; self.rider.n];
                let under = at
                    .nodes
                    .iter()
                    .flat_map(|nb| [nb.u, nb.w, nb.phi])
                    .flatten();
                modal.expand_at(under, &z[..self.n], &mut out);
                out.extend_from_slice(&z[self.n..]);
                Cow::Owned(out)
            }
        }
    }

    /// The disk's path is an unknown: z = (q, s).
    fn rolls(&self) -> bool {
        self.law.unknowns() == 1
    }

    pub fn beam(&self) -> &Beam {
        self.loaded.beam
    }

    /// (z, ż) at t = 0: the beam at rest in displacements q0 (on the mesh), the disk at s0
    /// rolling at Ω0.
    pub fn initial_state(&self, q0: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let nz = self.dim();
        let mut z = vec![0.0; nz];
        let mut zd = vec![0.0; nz];
        z[..self.n].copy_from_slice(&self.loaded.from_mesh(q0));
        if self.rolls() {
            z[self.n] = self.spec.s0;
            let at = AxisPoint::at(
                self.beam(),
                q0,
                &vec![0.0; q0.len()],
                self.spec.s0,
                0.0,
                self.spec.patch,
            );
            // θ̇ = (ψ_s − |r'|/a) ṡ on the beam at rest; the thesis' v_x = ṡ (|r'| − a ψ_s) is
            // the same condition.
            zd[self.n] = self.spec.v0() / (at.rp.v - self.spec.disk.radius * at.psi_s.v);
        }
        (z, zd)
    }

    /// Where the prescribed load is at time t, and how fast it moves.
    fn travel(&self, t: f64) -> (f64, f64) {
        let v0 = self.spec.v0();
        (self.spec.s0 + v0 * t, v0)
    }

    /// The time a prescribed load leaves the beam, if it does.
    pub fn exit_time(&self) -> Option<f64> {
        if self.rolls() {
            return None;
        }
        let v0 = self.spec.v0();
        let l = self.beam().length;
        if v0 > 0.0 {
            Some((l - self.spec.s0) / v0)
        } else if v0 < 0.0 {
            Some(-self.spec.s0 / v0)
        } else {
            None
        }
    }

    /// The axis at the contact for the state (z, ż).
    pub fn contact(&self, t: f64, z: &[f64], zd: &[f64]) -> AxisPoint {
        let (s, sdot) = if self.rolls() {
            (z[self.n], zd[self.n])
        } else {
            self.travel(t)
        };
        let mut basis = self.basis.borrow_mut();
        if basis.as_ref().is_none_or(|(at, _)| *at != s) {
            *basis = Some((s, self.beam().patch_basis_at(s, self.spec.patch)));
        }
        let nodes = basis.as_ref().expect("filled above").1.clone();
        match self.loaded.modal {
            None => AxisPoint::on(nodes, &z[..self.n], &zd[..self.n], s, sdot),
            Some(modal) => {
                // Only the unknowns under the patch are read.
                let mesh = self.rider.n;
                let (mut q, mut v) = (vec![0.0; mesh], vec![0.0; mesh]);
                let under = || nodes.iter().flat_map(|nb| [nb.u, nb.w, nb.phi]).flatten();
                modal.expand_at(under(), &z[..self.n], &mut q);
                modal.expand_at(under(), &zd[..self.n], &mut v);
                AxisPoint::on(nodes, &q, &v, s, sdot)
            }
        }
    }

    /// [`Self::contact`] at a state that is observed, kept for the next reading of the same
    /// state.
    fn observed_contact(&self, t: f64, z: &[f64], zd: &[f64]) -> Rc<AxisPoint> {
        self.observed.at(t, &[z, zd], || self.contact(t, z, zd))
    }

    /// The generalised force of the disk on z (beam rows, and s for the rolling couplings).
    fn force_row(&self, t: f64, z: &[f64], zd: &[f64]) -> Row {
        let at = self.contact(t, z, zd);
        // Newton's next mass product is at this z: its inertia is formed from this contact
        // rather than from a second one at zero velocity.
        self.inertia.at(t, &[z], || self.added_mass(&at));
        self.force_at(&at)
    }

    /// [`Self::force_row`] at the contact `at`.
    fn force_at(&self, at: &AxisPoint) -> Row {
        let mut force = Vec::new();
        self.law.force(&self.rider, at, &mut force);
        self.reduce(force)
    }

    /// The rider's inertia as z feels it at (t, z), which the velocity does not enter.
    fn inertia_at(&self, t: f64, z: &[f64]) -> Rc<AddedMass> {
        self.inertia.at(t, &[z], || {
            self.added_mass(&self.contact(t, z, &vec![0.0; z.len()]))
        })
    }

    /// The rider's inertia as z feels it.
    fn added_mass(&self, at: &AxisPoint) -> AddedMass {
        self.law
            .added_mass(&self.rider, at)
            .into_iter()
            .map(|(w, row)| (w, self.reduce(row)))
            .collect()
    }

    /// The beam's mass and the rider's inertia on the pattern of where the rider is now: only
    /// what needs the whole of M (a first acceleration, an explicit method's derivative) asks
    /// for it; the implicit methods factorise its split ([`Structure::mass_split`]).
    fn mass_matrix(&self, added: &AddedMass) -> Sparse {
        let mut m = Assembly::new(self.dim());
        m.add_sparse(self.loaded.model_mass(), 1.0, 0, 0);
        linalg::low_rank_entries(added).for_each(|(i, j, v)| m.add(i, j, v));
        m.build()
    }

    /// The true acceleration at a state: M(z) z̈ = f(z, ż), by the Woodbury identity on the
    /// split of M (see [`SecondOrderProblem::mass_split`]) with its constant part factorised
    /// once.
    fn acceleration(&self, t: f64, z: &[f64], zd: &[f64]) -> Option<Vec<f64>> {
        let at = self.observed_contact(t, z, zd);
        let force = self.force_at(&at);
        let mut y = vec![0.0; self.dim()];
        self.force_from(t, z, zd, &force, &mut y);
        if self.lu.borrow().is_none() {
            *self.lu.borrow_mut() = Some(SparseLu::factor(&self.base_mass, None)?);
        }
        let lu = self.lu.borrow();
        let lu = lu.as_ref().expect("factorised above");
        Woodbury::new(lu, self.low_rank_mass(self.added_mass(&at)))?.solve_in_place(lu, &mut y);
        y.iter().all(|v| v.is_finite()).then_some(y)
    }

    /// M(z) − B for the constant part B: the disk's inertia as seen by z, and the unit mass
    /// B puts on the contact coordinate taken back out.
    fn low_rank_mass(&self, mut added: AddedMass) -> LowRank {
        if self.dim() > self.n {
            added.push((-1.0, vec![(self.n, 1.0)]));
        }
        added
    }

    /// Add to f the force of the disk resting at s0 on the beam displaced by q (both on the
    /// mesh): its weight, passed on as the coupling passes it (through the contact patch when
    /// it rolls).
    pub fn add_weight_at_rest(&self, q: &[f64], f: &mut [f64]) {
        let at = AxisPoint::at(
            self.beam(),
            q,
            &vec![0.0; q.len()],
            self.spec.s0,
            0.0,
            self.spec.patch,
        );
        let mut force = Vec::new();
        self.law.force(&self.rider, &at, &mut force);
        for (i, v) in force {
            if i < self.rider.n {
                f[i] += v;
            }
        }
    }

    /// Add the disk's generalised force on the beam's unknowns (not on s) to f.
    pub fn add_disk_force_on_beam(&self, t: f64, z: &[f64], zd: &[f64], f: &mut [f64]) {
        for (i, v) in self.force_row(t, z, zd) {
            if i < self.n {
                f[i] += v;
            }
        }
    }

    fn force_from(&self, t: f64, z: &[f64], zd: &[f64], force: &Row, f: &mut [f64]) {
        self.loaded
            .force(t, &z[..self.n], &zd[..self.n], &mut f[..self.n]);
        if f.len() > self.n {
            f[self.n] = 0.0;
        }
        for &(i, v) in force {
            f[i] += v;
        }
    }

    /// What the run reports of the disk at a state (global axes).
    pub fn observe(&self, t: f64, z: &[f64], zd: &[f64]) -> DiskObservation {
        self.observe_with_acceleration(t, z, zd).0
    }

    /// The observation with the true acceleration it was made from, which the support
    /// reactions need too: one Woodbury solve for both.
    pub fn observe_with_acceleration(
        &self,
        t: f64,
        z: &[f64],
        zd: &[f64],
    ) -> (DiskObservation, Option<Vec<f64>>) {
        let key = [t, z[self.n.min(z.len() - 1)], zd[self.n.min(zd.len() - 1)]];
        if let Some((k, o, a)) = self.cache.borrow().as_ref() {
            if *k == key {
                return (*o, a.clone());
            }
        }
        let zdd = self.acceleration(t, z, zd);
        let obs = self.observe_with(
            t,
            z,
            zd,
            zdd.as_deref().unwrap_or(&vec![f64::NAN; self.dim()]),
        );
        *self.cache.borrow_mut() = Some((key, obs, zdd.clone()));
        (obs, zdd)
    }

    /// The disk's kinetic and potential energy at (t, z, ż). The energy ledger reads them
    /// at every step; unlike the observation's forces they need no acceleration, so the
    /// solve for it is left out.
    pub fn energies(&self, t: f64, z: &[f64], zd: &[f64]) -> (f64, f64) {
        let at = self.observed_contact(t, z, zd);
        // An unknown acceleration, given on the mesh as the law reads it: on a modal beam
        // not expanded from the modes under the patch at every step.
        let unknown = vec![f64::NAN; self.rider.n + zd.len() - self.n];
        let motion = self
            .law
            .motion(&self.rider, &at, &self.on_mesh(&at, zd), &unknown);
        let centre = self.beam().to_global(motion.centre);
        (motion.kinetic, self.potential(&motion, centre))
    }

    fn motion(&self, at: &AxisPoint, zd: &[f64], zdd: &[f64]) -> law::Motion {
        self.law.motion(
            &self.rider,
            at,
            &self.on_mesh(at, zd),
            &self.on_mesh(at, zdd),
        )
    }

    /// The disk's potential energy in gravity, unless its law keeps its own; `centre` is the
    /// motion's centre turned to global axes.
    fn potential(&self, motion: &law::Motion, centre: [f64; 2]) -> f64 {
        let height = self.beam().spec.from[1] + centre[1];
        motion
            .potential
            .unwrap_or(self.spec.disk.mass * self.spec.gravity * height)
    }

    fn observe_with(&self, t: f64, z: &[f64], zd: &[f64], zdd: &[f64]) -> DiskObservation {
        let at = self.observed_contact(t, z, zd);
        let motion = self.motion(&at, zd, zdd);
        let tg = at.tangent();
        let nm = at.normal();
        let beam = self.beam();
        let origin = beam.spec.from;
        let cg = beam.to_global(motion.centre);
        let vg = beam.to_global(motion.velocity);
        let contact = motion.contact;
        DiskObservation {
            s: if self.rolls() {
                z[self.n]
            } else {
                self.travel(t).0
            },
            x: origin[0] + cg[0],
            y: origin[1] + cg[1],
            vx: vg[0],
            vy: vg[1],
            omega: motion.omega,
            phi: 0.0,
            rt: contact[0] * tg[0] + contact[1] * tg[1],
            rn: contact[0] * nm[0] + contact[1] * nm[1],
            kinetic: motion.kinetic,
            potential: self.potential(&motion, cg),
        }
    }

    /// Add the force the disk, observed as `d`, exerts on the beam at (t, z, ż), spread over
    /// the contact patch, to `f` on the mesh's unknowns.
    pub fn add_contact_force_on_beam(
        &self,
        t: f64,
        z: &[f64],
        zd: &[f64],
        d: &DiskObservation,
        f: &mut [f64],
    ) {
        let at = self.observed_contact(t, z, zd);
        let (tg, nm) = (at.tangent(), at.normal());
        let on_disk = [d.rt * tg[0] + d.rn * nm[0], d.rt * tg[1] + d.rn * nm[1]];
        at.spread([-on_disk[0], -on_disk[1]], f);
    }

    /// Tangent and normal of the axis at the contact, global axes.
    pub fn contact_frame(&self, t: f64, z: &[f64], zd: &[f64]) -> [[f64; 2]; 2] {
        let at = self.observed_contact(t, z, zd);
        [
            self.beam().to_global(at.tangent()),
            self.beam().to_global(at.normal()),
        ]
    }

    /// Power of the prescribed moving load on the beam (zero for the rolling couplings, whose
    /// disk belongs to the system): F_beam · ∂r/∂t at s.
    pub fn power_on_beam(&self, t: f64, z: &[f64], zd: &[f64]) -> f64 {
        if self.rolls() {
            return 0.0;
        }
        let obs = self.observe(t, z, zd);
        let at = self.observed_contact(t, z, zd);
        let tg = at.tangent();
        let nm = at.normal();
        let on_disk = [
            obs.rt * tg[0] + obs.rn * nm[0],
            obs.rt * tg[1] + obs.rn * nm[1],
        ];
        let vm = at.material_velocity();
        -(on_disk[0] * vm[0] + on_disk[1] * vm[1])
    }

    /// The disk's energy belongs to the system's budget.
    pub fn disk_in_system(&self) -> bool {
        self.rolls()
    }
}

impl Structure for DiskOnBeam<'_> {
    fn dim(&self) -> usize {
        self.n + self.law.unknowns()
    }

    fn mass(&self, t: f64, q: &[f64]) -> Cow<'_, Sparse> {
        Cow::Owned(self.mass_matrix(&self.inertia_at(t, q)))
    }

    fn mass_is_constant(&self) -> bool {
        false
    }

    /// The beam's mass, with a unit mass standing in on the contact coordinate that the
    /// low-rank part takes back out, plus the disk's inertia as seen by z.
    fn mass_split(&self, t: f64, q: &[f64]) -> Option<(&Sparse, LowRank)> {
        let added = (*self.inertia_at(t, q)).clone();
        Some((&self.base_mass, self.low_rank_mass(added)))
    }

    fn mass_mul(&self, t: f64, q: &[f64], a: &[f64], out: &mut [f64]) {
        linalg::mul(self.loaded.model_mass(), &a[..self.n], &mut out[..self.n]);
        if out.len() > self.n {
            out[self.n] = 0.0;
        }
        for (w, row) in self.inertia_at(t, q).iter() {
            let ga = w * dot(row, a);
            for &(i, gi) in row {
                out[i] += gi * ga;
            }
        }
    }

    fn force(&self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        let force = self.force_row(t, q, v);
        self.force_from(t, q, v, &force, f);
    }

    fn stiffness(&self, t: f64, q: &[f64]) -> Sparse {
        let k = self.loaded.stiffness(t, &q[..self.n]);
        if self.dim() == self.n {
            return k;
        }
        let mut a = Assembly::new(self.dim());
        a.add_sparse(&k, 1.0, 0, 0);
        self.stiffness_pattern.get_or_init(|| a.pattern()).build(&a)
    }

    /// The beam's damping; the contact coordinate is not damped.
    fn damping(&self) -> Option<Cow<'_, Sparse>> {
        let c = self.loaded.damping()?;
        if self.dim() == self.n {
            return Some(c);
        }
        let mut a = Assembly::new(self.dim());
        a.add_sparse(&c, 1.0, 0, 0);
        Some(Cow::Owned(a.build()))
    }

    fn norm_weights(&self) -> Option<Vec<f64>> {
        let mut w = self.loaded.norm_weights()?;
        w.resize(self.dim(), 1.0);
        Some(w)
    }

    fn norm_groups(&self) -> Vec<Range<usize>> {
        let mut g = vec![0..self.n];
        if self.dim() > self.n {
            g.push(self.n..self.dim());
        }
        g
    }
}

impl SecondOrderProblem for DiskOnBeam<'_> {
    type Event = StopReason;

    /// The averaged track changes over the patch half-width b and no faster, and a crest
    /// there shows in the contact force, not in the motion the error estimate measures: a
    /// step moves a rolling disk by at most b/2, so the contact-loss event sees every crest.
    /// A prescribed load crosses at most one element a step (`LoadedBeam::load_step_bound`).
    fn max_step(&self, t: f64, _q: &[f64], v: &[f64]) -> f64 {
        let own = if self.rolls() {
            0.5 * self.spec.patch / v[self.n].abs()
        } else {
            self.beam().element_length() / self.spec.v0().abs()
        };
        own.min(self.loaded.load_step_bound(t))
    }

    fn breakpoints(&self) -> Vec<f64> {
        self.loaded.breakpoints()
    }

    fn enter_segment(&self, start: f64, end: f64) {
        self.loaded.enter_segment(start, end)
    }

    fn events(&self) -> &[EventSpec<StopReason>] {
        if !self.rolls() {
            return &[];
        }
        if self.spec.mu.is_some() {
            &EVENTS
        } else {
            &EVENTS[..4]
        }
    }

    fn event(&self, index: usize, t: f64, q: &[f64], v: &[f64]) -> f64 {
        let s = q[self.n];
        match index {
            0 => self.beam().length - s,
            1 => s,
            2 => self.observe(t, q, v).rn,
            3 => {
                let at = self.contact(t, q, v);
                1.0 - self.spec.disk.radius * at.psi_s.v / at.rp.v - FIT_MARGIN
            }
            _ => {
                let o = self.observe(t, q, v);
                self.spec.mu.unwrap_or(f64::INFINITY) * o.rn - o.rt.abs()
            }
        }
    }
}

//! Disks on the beam: each disk and the beam moving together, coupled by one of four laws,
//! each in a file of its own behind the [`law`] trait (the rider's inertia and force as the
//! beam's unknowns z feel them, and its motion for the observation); `contact.rs` is the
//! geometry of the contact on the deformed axis. [`DiskOnBeam`] holds the list of disks, each
//! with its own law: it observes them and their energy here, and assembles their terms into
//! the beam's equations and watches their events in `equations.rs`; `landing.rs` is a flying
//! disk's impact with the beam, `vehicles/` the vehicles' wheels on it, `last_evaluation.rs`
//! what the readings of one state share. Vehicles beside the
//! disks join their equations: their unknowns follow the contact coordinates, their bodies'
//! masses the constant mass, their unsprung masses the riders' inertia, their forces,
//! stiffness, damping and events the disks'; so one solve gives the acceleration that both
//! the disks' contact forces and the wheels' read.
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
//!   axis as if it were frozen; with Dormand–Prince or TR-BDF2 the run takes the published
//!   3n + 6 system of [`thesis_system`] instead.
//! - `moving_mass.rs`: a point mass at s = s0 + v0 t on the axis, following its displacement
//!   with its inertia; `moving_force.rs`: the constant weight m g at s = s0 + v0 t. Both are
//!   prescribed motions: the system is the beam alone, and the work the moving load does on
//!   it is the `work` of the energy budget.

mod consistent;
pub mod contact;
mod equations;
pub mod landing;
mod last_evaluation;
pub(crate) mod law;
mod moving_force;
mod moving_mass;
pub mod patch;
mod thesis;
pub mod thesis_system;
pub mod vehicles;

use std::borrow::Cow;
use std::cell::{Cell, OnceCell, RefCell};
use std::rc::Rc;

use contact::{AxisPoint, Row};
pub(crate) use last_evaluation::LastEvaluation;
use law::{AddedMass, Law, Rider};

use crate::beam::dynamics::LoadedBeam;
use crate::beam::{Beam, NodeBasis, PastFreeEnd};
use crate::disk::Disk;
use crate::disk::{DiskObservation, StopReason};
use crate::linalg::{self, Assembly, AssemblyPattern, LowRank, Sparse, SparseLu, Woodbury};
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::EventSpec;
use vehicles::VehiclesOnBeam;

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
    pub contact_loss: crate::disk::ContactLoss,
}

impl DiskOnBeamSpec {
    /// Speed along the axis at t = 0 (Ω < 0 rolls towards +s).
    pub fn v0(&self) -> f64 {
        -self.disk.radius * self.omega0
    }
}

/// What a rolling disk watches for, in the order of its events: the far end, the near end,
/// the normal force, the fit of the disk in the curvature, and (with μ) slip.
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

/// What the disks' equations met.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DiskEvent {
    /// A rolling disk (in the scene's order) met `reason`.
    Disk { disk: usize, reason: StopReason },
    /// A vehicle's wheel beside the disks lost or regained the track: the event numbered as
    /// `VehiclesOnBeam`'s events number them.
    Wheel(usize),
}

/// One disk on the beam: its law, the disk as the law sees it, where its contact coordinate
/// sits among z, and what is kept of its contact between evaluations.
struct Mounted {
    spec: DiskOnBeamSpec,
    law: Box<dyn Law>,
    rider: Rider,
    /// The index of its contact coordinate s in z, where its path is an unknown.
    slot: Option<usize>,
    /// The patch-averaged shape functions at its last contact point: a step evaluates the
    /// force and the mass at one s several times.
    basis: RefCell<Option<(f64, Vec<NodeBasis>)>>,
    /// The contact at the last state observed: an output row reads it for the disk, the
    /// reactions, the static correction and the energy.
    observed: LastEvaluation<AxisPoint>,
    /// It has left the beam: it no longer acts on it, and its contact coordinate rests.
    gone: Cell<bool>,
    /// On a modal beam, the mesh's displacements and velocities under its patch, expanded
    /// from the modes at each contact: only the patch's entries are written and read.
    under_patch: RefCell<[Vec<f64>; 2]>,
}

/// The disks on the beam: each with its own law, unknown, events and energy, assembled into
/// the beam's equations together.
pub struct DiskOnBeam<'a> {
    pub loaded: &'a LoadedBeam<'a>,
    disks: Vec<Mounted>,
    /// The beam's unknowns (the disks' contact coordinates follow).
    n: usize,
    /// Every rolling disk's events, disk by disk, and for each the disk and which of
    /// [`EVENTS`] it is.
    events: Vec<EventSpec<DiskEvent>>,
    event_of: Vec<(usize, usize)>,
    /// The last observations and their acceleration, keyed by (t, z's and ż's last
    /// entries): every event function of one state needs them, and so does the output row.
    cache: RefCell<Option<ObservedAt>>,
    /// `base_mass`, factorised once.
    lu: RefCell<Option<SparseLu>>,
    /// The beam's mass and a unit mass on each contact coordinate.
    base_mass: Sparse,
    /// The beam's tangent bordered by the contact coordinates, found at its first assembly.
    stiffness_pattern: OnceCell<AssemblyPattern>,
    /// The riders' inertia at the last state asked: Newton takes the mass product, and the
    /// next step its split, at the state its force was evaluated at.
    inertia: LastEvaluation<AddedMass>,
    /// Vehicles riding beside the disks, whose unknowns follow the contact coordinates: their
    /// bodies' masses (on the diagonal of z) join the constant mass, their unsprung masses the
    /// riders' inertia, their springs and wheels the force.
    beside: Option<Beside<'a>>,
    /// Unknowns of z.
    dim: usize,
}

/// The vehicles beside the disks, and their bodies' masses as (unknown, mass).
struct Beside<'a> {
    vehicles: &'a VehiclesOnBeam<'a>,
    masses: Vec<(usize, f64)>,
}

/// The disks observed at a state (`None` for one that has left), and the acceleration the
/// observation was made from.
type ObservedAt = ([f64; 3], Vec<Option<DiskObservation>>, Option<Vec<f64>>);

impl<'a> DiskOnBeam<'a> {
    /// The disks `specs` on the beam, in the scene's order; the rolling ones' contact
    /// coordinates follow the beam's unknowns in that order, and the unknowns of `vehicles`
    /// riding beside them (built to start there: [`Self::contact_coordinates`]) follow those.
    pub fn new(
        loaded: &'a LoadedBeam<'a>,
        specs: Vec<DiskOnBeamSpec>,
        vehicles: Option<&'a VehiclesOnBeam<'a>>,
    ) -> Self {
        let n = loaded.dim();
        let mut next = n;
        let mut events = Vec::new();
        let mut event_of = Vec::new();
        let disks: Vec<Mounted> = specs
            .into_iter()
            .enumerate()
            .map(|(k, spec)| {
                let law: Box<dyn Law> = match spec.coupling {
                    Coupling::Consistent => Box::new(consistent::Consistent),
                    Coupling::Thesis => Box::new(thesis::Thesis),
                    Coupling::MovingMass => Box::new(moving_mass::MovingMass),
                    Coupling::MovingForce => Box::new(moving_force::MovingForce),
                };
                let slot = (law.unknowns() == 1).then(|| {
                    next += 1;
                    next - 1
                });
                if slot.is_some() {
                    let watched = if spec.mu.is_some() { 5 } else { 4 };
                    events.extend(EVENTS[..watched].iter().map(|e| EventSpec {
                        reason: DiskEvent::Disk {
                            disk: k,
                            reason: e.reason,
                        },
                        terminal: e.terminal,
                    }));
                    event_of.extend((0..watched).map(|e| (k, e)));
                }
                let mesh = loaded.beam.dim();
                Mounted {
                    rider: Rider {
                        disk: spec.disk,
                        gravity: loaded.beam.to_local([0.0, -spec.gravity]),
                        n: mesh,
                        omega0: spec.omega0,
                    },
                    spec,
                    law,
                    slot,
                    basis: RefCell::new(None),
                    observed: LastEvaluation::new(),
                    gone: Cell::new(false),
                    under_patch: RefCell::new([vec![0.0; mesh], vec![0.0; mesh]]),
                }
            })
            .collect();
        if let Some(v) = vehicles {
            // A wheel's event says nothing of a disk: `event` hands it to the vehicles.
            events.extend(Self::wheel_events(v));
            event_of.resize(events.len(), (0, 0));
        }
        let beside = vehicles.map(|v| {
            assert_eq!(
                v.first_unknown(),
                next,
                "the vehicles' unknowns follow the disks'"
            );
            Beside {
                vehicles: v,
                masses: v.constant_terms().0,
            }
        });
        let dim = beside.as_ref().map_or(next, |b| b.vehicles.dim());
        let mut base = Assembly::new(dim);
        base.add_sparse(loaded.model_mass(), 1.0, 0, 0);
        for i in n..next {
            base.add(i, i, 1.0);
        }
        for &(i, m) in beside.iter().flat_map(|b| &b.masses) {
            base.add(i, i, m);
        }
        DiskOnBeam {
            beside,
            dim,
            base_mass: base.build(),
            n,
            loaded,
            disks,
            events,
            event_of,
            cache: RefCell::new(None),
            lu: RefCell::new(None),
            stiffness_pattern: OnceCell::new(),
            inertia: LastEvaluation::new(),
        }
    }

    /// The events of vehicles beside the disks, each as the disks' equations watch it.
    fn wheel_events(v: &VehiclesOnBeam) -> Vec<EventSpec<DiskEvent>> {
        (v.events().iter().enumerate())
            .map(|(i, e)| EventSpec {
                reason: DiskEvent::Wheel(i),
                terminal: e.terminal,
            })
            .collect()
    }

    /// How many contact coordinates the disks `specs` add to z: where vehicles beside them
    /// start theirs.
    pub fn contact_coordinates(specs: &[DiskOnBeamSpec]) -> usize {
        specs.iter().filter(|s| s.coupling.rolls()).count()
    }

    /// The vehicles riding beside the disks.
    pub fn vehicles_beside(&self) -> Option<&'a VehiclesOnBeam<'a>> {
        self.beside.as_ref().map(|b| b.vehicles)
    }

    /// How many disks the scene put on the beam (those that have left included).
    pub fn count(&self) -> usize {
        self.disks.len()
    }

    /// Disk k as the scene gave it.
    pub fn spec_of(&self, k: usize) -> &DiskOnBeamSpec {
        &self.disks[k].spec
    }

    /// The first disk as the scene gave it: the disk, where it is alone. The literal thesis
    /// system is for a lone disk.
    pub fn spec(&self) -> &DiskOnBeamSpec {
        self.spec_of(0)
    }

    /// The disks still on the beam, with their indices.
    fn on(&self) -> impl Iterator<Item = (usize, &Mounted)> {
        self.disks.iter().enumerate().filter(|(_, d)| !d.gone.get())
    }

    /// Whether disk k has left the beam.
    pub fn has_left(&self, k: usize) -> bool {
        self.disks[k].gone.get()
    }

    /// Disk k leaves the beam at the state (z, ż), which it takes out of the equations from
    /// here: its contact coordinate rests where it left. What was kept of the riders is
    /// forgotten.
    pub fn leave(&self, k: usize, zd: &mut [f64]) {
        let d = &self.disks[k];
        d.gone.set(true);
        if let Some(i) = d.slot {
            zd[i] = 0.0;
        }
        self.cache.borrow_mut().take();
        self.inertia.forget();
        d.observed.forget();
    }

    /// Disk k, which left the beam (flying over it), rides on it again; what was kept of the
    /// riders is forgotten.
    pub fn rejoin(&self, k: usize) {
        self.disks[k].gone.set(false);
        self.cache.borrow_mut().take();
        self.inertia.forget();
        self.disks[k].observed.forget();
    }

    /// Disk j may roll on while another flies over the beam: its inertia is its kinetic
    /// energy (the consistent coupling) or it has none (the moving force), so the impulse of
    /// a landing beside it is shared with it as with the beam (`landing`).
    pub fn rides_beside_a_flight(&self, j: usize) -> bool {
        matches!(
            self.disks[j].spec.coupling,
            Coupling::Consistent | Coupling::MovingForce
        )
    }

    /// Every disk has left the beam.
    pub fn all_left(&self) -> bool {
        self.on().next().is_none()
    }

    /// A row over the mesh's unknowns and disk `d`'s contact coordinate (as the laws write
    /// it, s at the mesh's count) as a row over z: on a modal beam the mesh's part through Φᵀ.
    fn reduce(&self, d: &Mounted, row: Row) -> Row {
        let mesh = d.rider.n;
        let Some(modal) = self.loaded.modal else {
            return row
                .into_iter()
                .map(|(i, v)| (if i < mesh { i } else { d.slot.unwrap_or(i) }, v))
                .collect();
        };
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
            out.push((d.slot.expect("a row on s is a rolling disk's"), on_s));
        }
        out
    }

    /// (q, s) on the mesh from z for disk `d`, as its law reads a state at the contact `at`:
    /// on a modal beam q = Φ η, formed only under the patch, where the laws read it.
    fn on_mesh<'y>(&self, d: &Mounted, at: &AxisPoint, z: &'y [f64]) -> Cow<'y, [f64]> {
        let own = |mut q: Vec<f64>| {
            q.extend(d.slot.map(|i| z[i]));
            Cow::Owned(q)
        };
        match self.loaded.modal {
            None if d.slot.is_none_or(|i| i == self.n) => Cow::Borrowed(z),
            None => own(z[..self.n].to_vec()),
            Some(modal) => {
                let mut out = vec![0.0; d.rider.n];
                let under = at
                    .nodes
                    .iter()
                    .flat_map(|nb| [nb.u, nb.w, nb.phi])
                    .flatten();
                modal.expand_at(under, &z[..self.n], &mut out);
                own(out)
            }
        }
    }

    pub fn beam(&self) -> &Beam {
        self.loaded.beam
    }

    /// (z, ż) at t = 0: the beam at rest in displacements q0 (on the mesh), each rolling disk
    /// at its s0 rolling at its Ω0.
    pub fn initial_state(&self, q0: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let nz = self.dim();
        let (mut z, mut zd) = match &self.beside {
            Some(b) => {
                let mut y = b.vehicles.initial_state(&self.loaded.from_mesh(q0));
                let zd = y.split_off(nz);
                (y, zd)
            }
            None => (vec![0.0; nz], vec![0.0; nz]),
        };
        z[..self.n].copy_from_slice(&self.loaded.from_mesh(q0));
        for d in &self.disks {
            let Some(i) = d.slot else { continue };
            z[i] = d.spec.s0;
            let at = AxisPoint::at(
                self.beam(),
                q0,
                &vec![0.0; q0.len()],
                d.spec.s0,
                0.0,
                d.spec.patch,
            );
            zd[i] = Self::starting_rate(d, &at);
        }
        (z, zd)
    }

    /// ṡ of disk `d` rolling at its Ω0 at the contact `at` on the beam at rest:
    /// θ̇ = (ψ_s − |r'|/a) ṡ; the thesis' v_x = ṡ (|r'| − a ψ_s) is the same condition.
    fn starting_rate(d: &Mounted, at: &AxisPoint) -> f64 {
        d.spec.v0() / (at.rp.v - d.spec.disk.radius * at.psi_s.v)
    }

    /// Where a prescribed load is at time t, and how fast it moves.
    fn travel(d: &Mounted, t: f64) -> (f64, f64) {
        let v0 = d.spec.v0();
        (d.spec.s0 + v0 * t, v0)
    }

    /// The time disk k, a prescribed load, leaves the beam, if it does.
    fn exit_time_of(&self, d: &Mounted) -> Option<f64> {
        if d.slot.is_some() {
            return None;
        }
        let v0 = d.spec.v0();
        let l = self.beam().length;
        if v0 > 0.0 {
            Some((l - d.spec.s0) / v0)
        } else if v0 < 0.0 {
            Some(-d.spec.s0 / v0)
        } else {
            None
        }
    }

    /// The next time a prescribed load on the beam leaves it, and which.
    pub fn next_exit(&self) -> Option<(f64, usize)> {
        self.on()
            .filter_map(|(k, d)| self.exit_time_of(d).map(|t| (t, k)))
            .min_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// The axis at disk k's contact for the state (z, ż).
    pub fn contact(&self, k: usize, t: f64, z: &[f64], zd: &[f64]) -> AxisPoint {
        self.contact_of(&self.disks[k], t, z, zd)
    }

    fn contact_of(&self, d: &Mounted, t: f64, z: &[f64], zd: &[f64]) -> AxisPoint {
        let (s, sdot) = match d.slot {
            Some(i) => (z[i], zd[i]),
            None => Self::travel(d, t),
        };
        let mut basis = d.basis.borrow_mut();
        if basis.as_ref().is_none_or(|(at, _)| *at != s) {
            *basis = Some((
                s,
                self.beam()
                    .patch_basis_at(s, d.spec.patch, PastFreeEnd::CarriedOn),
            ));
        }
        let nodes = basis.as_ref().expect("filled above").1.clone();
        match self.loaded.modal {
            None => AxisPoint::on(nodes, &z[..self.n], &zd[..self.n], s, sdot),
            Some(modal) => {
                let mut under_patch = d.under_patch.borrow_mut();
                let [q, v] = &mut *under_patch;
                let under = nodes.iter().flat_map(|nb| [nb.u, nb.w, nb.phi]).flatten();
                modal.expand_pair_at(under, (&z[..self.n], &zd[..self.n]), (q, v));
                AxisPoint::on(nodes, q, v, s, sdot)
            }
        }
    }

    /// [`Self::contact`] at a state that is observed, kept for the next reading of the same
    /// state.
    fn observed_contact(&self, d: &Mounted, t: f64, z: &[f64], zd: &[f64]) -> Rc<AxisPoint> {
        d.observed.at(t, &[z, zd], || self.contact_of(d, t, z, zd))
    }

    /// The generalised force of the disks on z (beam rows, and s for the rolling couplings).
    fn force_row(&self, t: f64, z: &[f64], zd: &[f64]) -> Row {
        let contacts: Vec<(&Mounted, AxisPoint)> = self
            .on()
            .map(|(_, d)| (d, self.contact_of(d, t, z, zd)))
            .collect();
        let (forces, added): (Vec<Row>, Vec<AddedMass>) = (contacts.iter())
            .map(|(d, at)| self.force_and_inertia(d, at))
            .unzip();
        // Newton's next mass product is at this z: its inertia is formed from these contacts
        // rather than from second ones at zero velocity.
        self.inertia.at(t, &[z], || {
            let mut added: AddedMass = (added.into_iter().flatten())
                .chain(self.loaded.axle_inertia(t))
                .collect();
            self.add_unsprung_beside(t, z, &mut added);
            added
        });
        forces.concat()
    }

    /// Disk `d`'s generalised force and inertia at its contact `at`, each as rows over z. A
    /// law whose force is a combination of its inertia's rows
    /// ([`law::Law::force_on_inertia_rows`]) has them formed and reduced once for both: on a
    /// modal beam the reduction through Φᵀ is most of what a disk costs a right-hand side.
    fn force_and_inertia(&self, d: &Mounted, at: &AxisPoint) -> (Row, AddedMass) {
        let added = self.added_mass(d, at);
        let force = match d.law.force_on_inertia_rows(&d.rider, at) {
            Some(weights) => (added.iter().zip(weights))
                .flat_map(|((_, row), c)| row.iter().map(move |&(i, v)| (i, v * c)))
                .collect(),
            None => self.force_at(d, at),
        };
        (force, added)
    }

    /// Disk `d`'s generalised force at its contact `at`.
    fn force_at(&self, d: &Mounted, at: &AxisPoint) -> Row {
        let mut force = Vec::new();
        d.law.force(&d.rider, at, &mut force);
        self.reduce(d, force)
    }

    /// The riders' inertia as z feels it at (t, z), which the velocity does not enter.
    fn inertia_at(&self, t: f64, z: &[f64]) -> Rc<AddedMass> {
        self.inertia.at(t, &[z], || {
            let still = vec![0.0; z.len()];
            let mut added: AddedMass = self
                .on()
                .flat_map(|(_, d)| self.added_mass(d, &self.contact_of(d, t, z, &still)))
                .chain(self.loaded.axle_inertia(t))
                .collect();
            self.add_unsprung_beside(t, z, &mut added);
            added
        })
    }

    /// The unsprung masses of the vehicles beside the disks, to `added`.
    fn add_unsprung_beside(&self, t: f64, z: &[f64], added: &mut AddedMass) {
        if let Some(b) = &self.beside {
            b.vehicles.add_unsprung(t, z, added);
        }
    }

    /// Disk `d`'s inertia as z feels it.
    fn added_mass(&self, d: &Mounted, at: &AxisPoint) -> AddedMass {
        d.law
            .added_mass(&d.rider, at)
            .into_iter()
            .map(|(w, row)| (w, self.reduce(d, row)))
            .collect()
    }

    /// The beam's mass and the riders' inertia on the pattern of where they are now: only
    /// what needs the whole of M (a first acceleration, an explicit method's derivative) asks
    /// for it; the implicit methods factorise its split ([`Structure::mass_split`]).
    fn mass_matrix(&self, added: &AddedMass) -> Sparse {
        let mut m = Assembly::new(self.dim());
        m.add_sparse(self.loaded.model_mass(), 1.0, 0, 0);
        linalg::low_rank_entries(added).for_each(|(i, j, v)| m.add(i, j, v));
        // A disk that has left keeps its contact coordinate at rest under a unit mass.
        for i in self
            .disks
            .iter()
            .filter(|d| d.gone.get())
            .filter_map(|d| d.slot)
        {
            m.add(i, i, 1.0);
        }
        for &(i, mass) in self.beside.iter().flat_map(|b| &b.masses) {
            m.add(i, i, mass);
        }
        m.build()
    }

    /// The true acceleration at a state: M(z) z̈ = f(z, ż), by the Woodbury identity on the
    /// split of M (see [`SecondOrderProblem::mass_split`]) with its constant part factorised
    /// once.
    fn acceleration(&self, t: f64, z: &[f64], zd: &[f64]) -> Option<Vec<f64>> {
        let mut force = Vec::new();
        let mut added = self.loaded.axle_inertia(t);
        for (_, d) in self.on() {
            let at = self.observed_contact(d, t, z, zd);
            let (f, a) = self.force_and_inertia(d, &at);
            force.extend(f);
            added.extend(a);
        }
        self.add_unsprung_beside(t, z, &mut added);
        let mut y = vec![0.0; self.dim()];
        self.force_from(t, z, zd, &force, &mut y);
        if self.lu.borrow().is_none() {
            *self.lu.borrow_mut() = Some(SparseLu::factor(&self.base_mass, None)?);
        }
        let lu = self.lu.borrow();
        let lu = lu.as_ref().expect("factorised above");
        Woodbury::new(lu, self.low_rank_mass(added))?.solve_in_place(lu, &mut y);
        y.iter().all(|v| v.is_finite()).then_some(y)
    }

    /// M(z) − B for the constant part B: the disks' inertia as seen by z, and the unit masses
    /// B puts on the contact coordinates of the disks on the beam taken back out (one that
    /// has left keeps its coordinate at rest under B's).
    fn low_rank_mass(&self, mut added: AddedMass) -> LowRank {
        added.extend(
            self.on()
                .filter_map(|(_, d)| d.slot)
                .map(|i| (-1.0, vec![(i, 1.0)])),
        );
        added
    }

    /// Add to f the force of every disk at its s0 on the beam displaced by q (both on the
    /// mesh), the beam still: its weight, passed on as its coupling passes it (through the
    /// contact patch when it rolls). A disk whose path is an unknown is not held there: it
    /// rolls at its Ω0 (over the deflection's curvature), on a slope it rolls down it, and the
    /// beam carries its weight less what that acceleration takes (on the zip-line's 20 % slope
    /// a held disk's tangential force is m g sin θ, three times a rolling one's: a start that
    /// holds it rings with the difference).
    pub fn add_weight_at_rest(&self, q: &[f64], f: &mut [f64]) {
        let still = vec![0.0; q.len()];
        for d in &self.disks {
            let at =
                |sdot: f64| AxisPoint::at(self.beam(), q, &still, d.spec.s0, sdot, d.spec.patch);
            // The disk as the run starts it: rolling at its Ω0 over the beam at rest.
            let rest = at(0.0);
            let sdot = match d.slot {
                Some(_) => Self::starting_rate(d, &rest),
                None => 0.0,
            };
            let at = at(sdot);
            let mut force = Vec::new();
            d.law.force(&d.rider, &at, &mut force);
            let n = d.rider.n;
            for &(i, v) in &force {
                if i < n {
                    f[i] += v;
                }
            }
            if d.law.unknowns() == 0 {
                continue;
            }
            // The rows index the contact coordinate s at n: with the beam still, s̈ solves its
            // own row of M z̈ = f, and its inertia's coupling to the beam takes M_is s̈.
            let on_s = |row: &Row| -> f64 { row.iter().filter(|e| e.0 == n).map(|e| e.1).sum() };
            let added = d.law.added_mass(&d.rider, &at);
            let mass_s: f64 = added.iter().map(|(w, row)| w * on_s(row).powi(2)).sum();
            if !mass_s.is_finite() || mass_s <= 0.0 {
                continue;
            }
            let sdd = on_s(&force) / mass_s;
            for (w, row) in &added {
                let taken = w * on_s(row) * sdd;
                for &(i, v) in row.iter().filter(|e| e.0 < n) {
                    f[i] -= v * taken;
                }
            }
        }
    }

    /// Add the disks' generalised force on the beam's unknowns (not on s) to f.
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
        f[self.n..].fill(0.0);
        for &(i, v) in force {
            f[i] += v;
        }
        if let Some(b) = &self.beside {
            b.vehicles.add_forces(t, z, zd, f);
        }
    }

    /// z̈ at (t, z, ż) for the vehicles beside the disks: the whole system's.
    pub fn acceleration_beside(&self, t: f64, z: &[f64], zd: &[f64]) -> Vec<f64> {
        self.observe_with_acceleration(t, z, zd)
            .1
            .unwrap_or_else(|| vec![f64::NAN; self.dim()])
    }

    /// What the run reports of the first disk at a state (global axes): the disk, where it
    /// is alone.
    pub fn observe(&self, t: f64, z: &[f64], zd: &[f64]) -> DiskObservation {
        self.observe_all(t, z, zd)[0].expect("the lone disk is on the beam")
    }

    /// What the run reports of each disk at a state (`None` for one that has left).
    pub fn observe_all(&self, t: f64, z: &[f64], zd: &[f64]) -> Vec<Option<DiskObservation>> {
        self.observe_with_acceleration(t, z, zd).0
    }

    /// The observations with the true acceleration they were made from, which the support
    /// reactions need too: one Woodbury solve for all.
    pub fn observe_with_acceleration(
        &self,
        t: f64,
        z: &[f64],
        zd: &[f64],
    ) -> (Vec<Option<DiskObservation>>, Option<Vec<f64>>) {
        let key = [t, z[z.len() - 1], zd[zd.len() - 1]];
        if let Some((k, o, a)) = self.cache.borrow().as_ref() {
            if *k == key {
                return (o.clone(), a.clone());
            }
        }
        let zdd = self.acceleration(t, z, zd);
        let unknown = vec![f64::NAN; self.dim()];
        let obs: Vec<Option<DiskObservation>> = self
            .disks
            .iter()
            .map(|d| {
                (!d.gone.get())
                    .then(|| self.observe_with(d, t, z, zd, zdd.as_deref().unwrap_or(&unknown)))
            })
            .collect();
        *self.cache.borrow_mut() = Some((key, obs.clone(), zdd.clone()));
        (obs, zdd)
    }

    /// Each disk's centre velocity and contact frame (tangent, normal), global, at (t, z, ż)
    /// (`None` for one that has left): what needs no acceleration, so no solve for it.
    pub fn velocities_and_frames(
        &self,
        t: f64,
        z: &[f64],
        zd: &[f64],
    ) -> Vec<Option<([f64; 2], [[f64; 2]; 2])>> {
        let unknown = vec![f64::NAN; self.dim()];
        let beam = self.beam();
        self.disks
            .iter()
            .map(|d| {
                (!d.gone.get()).then(|| {
                    let at = self.observed_contact(d, t, z, zd);
                    let motion = self.motion(d, &at, zd, &unknown);
                    (
                        beam.to_global(motion.velocity),
                        [beam.to_global(at.tangent()), beam.to_global(at.normal())],
                    )
                })
            })
            .collect()
    }

    /// The kinetic and potential energy at (t, z, ż) of the disks on the beam that belong to
    /// the system (the rolling ones). The energy ledger reads them at every step; unlike the
    /// observation's forces they need no acceleration, so the solve for it is left out.
    pub fn energies(&self, t: f64, z: &[f64], zd: &[f64]) -> (f64, f64) {
        let mut total = (0.0, 0.0);
        for (_, d) in self.on().filter(|(_, d)| d.slot.is_some()) {
            let at = self.observed_contact(d, t, z, zd);
            // An unknown acceleration, given on the mesh as the law reads it: on a modal beam
            // not expanded from the modes under the patch at every step.
            let unknown = vec![f64::NAN; d.rider.n + 1];
            let motion = d
                .law
                .motion(&d.rider, &at, &self.on_mesh(d, &at, zd), &unknown);
            let centre = self.beam().to_global(motion.centre);
            total.0 += motion.kinetic;
            total.1 += self.potential(d, &motion, centre);
        }
        total
    }

    fn motion(&self, d: &Mounted, at: &AxisPoint, zd: &[f64], zdd: &[f64]) -> law::Motion {
        d.law.motion(
            &d.rider,
            at,
            &self.on_mesh(d, at, zd),
            &self.on_mesh(d, at, zdd),
        )
    }

    /// A disk's potential energy in gravity, unless its law keeps its own; `centre` is the
    /// motion's centre turned to global axes.
    fn potential(&self, d: &Mounted, motion: &law::Motion, centre: [f64; 2]) -> f64 {
        let height = self.beam().spec.from[1] + centre[1];
        motion
            .potential
            .unwrap_or(d.spec.disk.mass * d.spec.gravity * height)
    }

    fn observe_with(
        &self,
        d: &Mounted,
        t: f64,
        z: &[f64],
        zd: &[f64],
        zdd: &[f64],
    ) -> DiskObservation {
        let at = self.observed_contact(d, t, z, zd);
        let motion = self.motion(d, &at, zd, zdd);
        let tg = at.tangent();
        let nm = at.normal();
        let beam = self.beam();
        let origin = beam.spec.from;
        let cg = beam.to_global(motion.centre);
        let vg = beam.to_global(motion.velocity);
        let contact = motion.contact;
        DiskObservation {
            s: match d.slot {
                Some(i) => z[i],
                None => Self::travel(d, t).0,
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
            potential: self.potential(d, &motion, cg),
        }
    }

    /// Add the force each disk on the beam, observed as `disks`, exerts on it at (t, z, ż),
    /// spread over its contact patch, to `f` on the mesh's unknowns.
    pub fn add_contact_force_on_beam(
        &self,
        t: f64,
        z: &[f64],
        zd: &[f64],
        disks: &[Option<DiskObservation>],
        f: &mut [f64],
    ) {
        for (d, o) in self.disks.iter().zip(disks) {
            let Some(o) = o.filter(|_| !d.gone.get()) else {
                continue;
            };
            let at = self.observed_contact(d, t, z, zd);
            let (tg, nm) = (at.tangent(), at.normal());
            let on_disk = [o.rt * tg[0] + o.rn * nm[0], o.rt * tg[1] + o.rn * nm[1]];
            at.spread([-on_disk[0], -on_disk[1]], f);
        }
    }

    /// Tangent and normal of the axis at disk k's contact, global axes.
    pub fn contact_frame(&self, k: usize, t: f64, z: &[f64], zd: &[f64]) -> [[f64; 2]; 2] {
        let at = self.observed_contact(&self.disks[k], t, z, zd);
        [
            self.beam().to_global(at.tangent()),
            self.beam().to_global(at.normal()),
        ]
    }

    /// Power of the prescribed moving loads on the beam (the rolling disks belong to the
    /// system and do none): F_beam · ∂r/∂t at each one's s.
    pub fn power_on_beam(&self, t: f64, z: &[f64], zd: &[f64]) -> f64 {
        if self.on().all(|(_, d)| d.slot.is_some()) {
            return 0.0;
        }
        let obs = self.observe_all(t, z, zd);
        self.on()
            .filter(|(_, d)| d.slot.is_none())
            .map(|(k, d)| {
                let o = obs[k].expect("observed on the beam");
                let at = self.observed_contact(d, t, z, zd);
                let (tg, nm) = (at.tangent(), at.normal());
                let on_disk = [o.rt * tg[0] + o.rn * nm[0], o.rt * tg[1] + o.rn * nm[1]];
                let vm = at.material_velocity();
                -(on_disk[0] * vm[0] + on_disk[1] * vm[1])
            })
            .sum()
    }

    /// A disk whose path is prescribed is on the beam: its power on the beam is the budget's.
    pub fn carries_prescribed(&self) -> bool {
        self.on().any(|(_, d)| d.slot.is_none())
    }

    /// Disk k's energy belongs to the system's budget (its path is an unknown).
    pub fn in_system(&self, k: usize) -> bool {
        self.disks[k].slot.is_some()
    }

    /// Some disk's energy belongs to the system's budget.
    pub fn disk_in_system(&self) -> bool {
        self.disks.iter().any(|d| d.slot.is_some())
    }
}

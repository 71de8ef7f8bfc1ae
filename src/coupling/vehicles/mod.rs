//! Vehicles on the beam: each a set of bodies on spring–dampers over axles whose point wheels
//! follow the deck and the profile on it (`crate::vehicle`). The unknowns are the beam's (on
//! the mesh or its modes) followed by each vehicle's; the vehicles travel at their prescribed
//! speeds and accelerations.
//!
//! Axle a of a vehicle is at X_a(t) on the deck; its wheel rides on the deck's axis averaged
//! over a contact patch (as a moving-mass axle does: `beam::train`), so the track under it is
//! d_a = gᵀq + r(X_a), with g the patch-averaged shape functions of w. It moves with
//! ḋ_a = gᵀq̇ + V (g'ᵀq + r') and d̈_a = gᵀq̈ + 2V g'ᵀq̇ + V² g''ᵀq + A g'ᵀq + V² r'' + A r'.
//! On a modal beam a point wheel's track adds s_a(t), the static response of the modes left
//! out to the wheels' static loads (`VehiclesOnBeam::settle`), which it rides as a profile.
//! The wheel bears R_a = P_a + m_a d̈_a − S_a: its static load, the unsprung mass's inertia,
//! less S_a = Σ (k e + c ė) of the springs on it (e the stretch from static). The beam feels
//! −R_a through g; the bodies feel the springs.
//!
//! Energy: with the vehicles' kinetic energy (bodies and unsprung masses), the springs' ½ k e²
//! and the weights' potential Σ P_a d_a beside the beam's, the balance closes on the dampers'
//! Σ c ė² and the work of the drive that holds the prescribed horizontal motion against the
//! wheels' forces on the slopes under them, Σ R_a V (g'ᵀq + r'). At a kink of a
//! piecewise-linear profile an unsprung mass's vertical velocity jumps: the drive delivers
//! that impulse's energy, which the run's ledger books with its work.
//!
//! A disk wheel with an unsprung mass flies where R_a falls to zero: its axle's height h_a
//! is then an unknown of its own, m_a ḧ_a = S_a − P_a, its springs pull on it instead of on
//! the track, and the run watches its gap to where the disk would rest. It lands plastically
//! (`VehiclesOnBeam::land`). A point wheel, or a disk on a massless axle, has no motion of its
//! own to fly with: the run stops there.
//!
//! `track.rs` finds the wheels and the track under each at one instant, `disk_wheel.rs` where
//! a disk wheel touches, `hops.rs` a wheel's flight and landing; this file forms from them the
//! forces, the observation and the energy, and `equations.rs` assembles them into the
//! equations of motion, the vehicles' own or those of disks beside them.

mod disk_wheel;
mod equations;
mod hops;
mod track;

use std::cell::{Cell, OnceCell, RefCell};

use super::{DiskOnBeam, LastEvaluation};
use crate::beam::dynamics::{LoadedBeam, STEPS_OVER_AN_ELEMENT_UNDER_A_MASS};
use crate::beam::PastFreeEnd;
use crate::linalg::{Assembly, LowRank, Sparse, SparseLu, Woodbury};
use crate::ode::second_order::Structure;
use crate::ode::EventSpec;
use crate::vehicle::profile::Profile;
use crate::vehicle::{Part, Vehicle, Wheel};
pub use disk_wheel::DiskContact;
use disk_wheel::Resting;
pub use track::Contact;
use track::Track;

/// A sparse row over the beam's unknowns of the model.
type Row = Vec<(usize, f64)>;

/// How often a wheel's events are looked at per shortest wave of a random road. A truck's
/// 1 kg disk-wheel axles at 300 m/s over ISO class D waves of 0.2 m dipped below zero over
/// crests for 7.5 to 24 mm of travel (λ/27 to λ/8), inside steps of 15 mm; at λ/32 each dip is
/// seen.
const CREST_SAMPLES: f64 = 32.0;

/// Steps a wheel's patch takes at least to cross an end where nothing holds w. The track it
/// averages steps there by the tip's deflection within the patch's width, and the drive's
/// power pulses with that step's slope quicker than the motion shows: a sprung car leaving a
/// cantilever's tip under generalized-α, whose trapezoidal rule books the pulse, read a
/// drive's work 21 J off out of 1767 (a drift of 7.8e-3) with the motion right to 1e-6.
const STEPS_OVER_A_FREE_END: f64 = 64.0;

/// Steps a disk wheel takes at least to pivot over a crest of the profile: its contact force
/// dips by about m V²/a there, which the steps, following the vehicle's and the deck's
/// motion, would stride over.
const STEPS_OVER_A_PIVOT: f64 = 8.0;

/// Where a disk of `radius` pivots over the crest (x, left, right) (right < left): from where
/// its contact reaches the corner to where it leaves it, X = x − a s/√(1 + s²) for each face's
/// slope s.
fn pivot((x, left, right): (f64, f64, f64), radius: f64) -> (f64, f64) {
    let lean = |s: f64| s / (1.0 + s * s).sqrt();
    (x - radius * lean(left), x - radius * lean(right))
}

/// The wheels (numbered among all the vehicles') whose disks bridge the road's hollows: each
/// meets the crest ahead where it comes level with the one the disk rests on.
fn bridging<'v>(vehicles: &'v [Vehicle], profile: &'v Profile) -> impl Iterator<Item = usize> + 'v {
    vehicles
        .iter()
        .flat_map(|v| v.axles.iter().map(move |_| v.wheel))
        .enumerate()
        .filter(move |(_, w)| matches!(w, Wheel::Disk { radius } if profile.crest_scan(*radius).is_some()))
        .map(|(k, _)| k)
}

/// Times whose wheels are kept. A step's stages ask at five times, and then the observers
/// come back to its start, middle and end (the watch's samples, the ledger's quadrature): with
/// the last one kept the railway study's four cars formed them 13.0 times a step attempted,
/// with the last eight 9.9.
const KEPT_CONTACTS: usize = 8;

/// What the vehicles are doing at one instant.
#[derive(Clone, Debug, Default)]
pub struct VehicleObservation {
    /// Per vehicle, its first axle's position.
    pub x: Vec<f64>,
    /// Per vehicle, per body: vertical displacement of the centre of mass, pitch (NaN where
    /// it does not pitch), vertical acceleration.
    pub bodies: Vec<Vec<[f64; 3]>>,
    /// Per vehicle, per axle: the wheel's contact force (N).
    pub rn: Vec<Vec<f64>>,
}

pub struct VehiclesOnBeam<'a> {
    pub loaded: &'a LoadedBeam<'a>,
    pub vehicles: &'a [Vehicle],
    pub profile: &'a Profile,
    /// The beam's unknowns.
    n: usize,
    /// Where the vehicles' unknowns start: after the beam's, or after the contact coordinates
    /// of the disks riding beside them.
    first: usize,
    /// Where each vehicle's unknowns start.
    offsets: Vec<usize>,
    dim: usize,
    /// The beam's mass and the bodies', block-diagonal: the constant part of the mass (a unit
    /// mass stands in on each disk's contact coordinate, whose mass the disks assemble).
    base: Sparse,
    base_lu: SparseLu,
    /// The beam's damping and the dampers' with the axles held: constant.
    damping: Option<Sparse>,
    /// The dampers' alone, for the disks' equations to border the beam's with.
    own_damping: Option<Sparse>,
    /// The springs' stiffness with the axles held.
    rigid_track: Sparse,
    /// Half-width of the patch a wheel rides on.
    patch: f64,
    /// Midpoint of the current stretch between breakpoints: which piece of the profile a
    /// wheel on a kink is on.
    segment: Cell<f64>,
    /// The wheels at the last [`KEPT_CONTACTS`] times asked, on the side of the stretch then.
    contacts_at: LastEvaluation<Vec<Contact>>,
    /// Per wheel: its contact force falling to zero, or, flying, its gap closing.
    events: Vec<EventSpec<usize>>,
    /// The wheels' contact forces at the last (t, z, ż) the events asked about: the driver
    /// asks for each wheel's in turn at one state, and with unsprung masses each needs the
    /// accelerations solved for.
    forces_at: LastEvaluation<Vec<f64>>,
    /// Per wheel (in the order of the contacts), the unknown its axle's height is while it
    /// flies: a disk wheel's with unsprung mass. Held at rest while the wheel is on the track.
    hops: Vec<Option<usize>>,
    /// Per wheel, whether it flies now.
    airborne: RefCell<Vec<bool>>,
    /// Per wheel, on a road its disk bridges, the crest it rests on, as the last step taken
    /// left it; `None` until then, and in the air.
    resting: RefCell<Vec<Option<Resting>>>,
    /// The disks beside the vehicles, whose equations hold the vehicles' too: every
    /// acceleration the vehicles read is the whole system's, solved there.
    host: OnceCell<&'a DiskOnBeam<'a>>,
}

impl<'a> VehiclesOnBeam<'a> {
    /// The vehicles on the beam, their unknowns from `first` on in z (the beam's count, or
    /// past the contact coordinates of disks beside them).
    pub fn new(
        loaded: &'a LoadedBeam<'a>,
        vehicles: &'a [Vehicle],
        profile: &'a Profile,
        patch: f64,
        first: usize,
    ) -> Option<Self> {
        let n = loaded.dim();
        let mut offsets = Vec::with_capacity(vehicles.len());
        let mut dim = first;
        for v in vehicles {
            offsets.push(dim);
            dim += v.unknowns();
        }
        // A disk wheel with an unsprung mass can fly: its axle's height is then an unknown.
        let mut hops = Vec::new();
        for v in vehicles {
            for axle in &v.axles {
                let flies = matches!(v.wheel, Wheel::Disk { .. }) && axle.mass > 0.0;
                hops.push(flies.then(|| {
                    dim += 1;
                    dim - 1
                }));
            }
        }
        let mut mass = Assembly::new(dim);
        mass.add_sparse(loaded.model_mass(), 1.0, 0, 0);
        for i in n..first {
            mass.add(i, i, 1.0);
        }
        let mut stiff = Assembly::new(dim);
        let mut damp = Assembly::new(dim);
        let mut own = Assembly::new(dim);
        let mut damped = false;
        if let Some(c) = loaded.damping() {
            damp.add_sparse(&c, 1.0, 0, 0);
            damped = true;
        }
        let mut dampers = false;
        for (v, &o) in vehicles.iter().zip(&offsets) {
            for (i, m) in v.mass_diagonal().into_iter().enumerate() {
                mass.add(o + i, o + i, m);
            }
            let (k, c) = (v.on_rigid_track(true), v.on_rigid_track(false));
            for i in 0..v.unknowns() {
                for j in 0..v.unknowns() {
                    stiff.add(o + i, o + j, k[(i, j)]);
                    damp.add(o + i, o + j, c[(i, j)]);
                    own.add(o + i, o + j, c[(i, j)]);
                }
            }
            dampers |= v.springs.iter().any(|s| s.c != 0.0);
        }
        damped |= dampers;
        let wheels = vehicles.iter().flat_map(|v| v.axles.iter());
        for (axle, h) in wheels.zip(&hops) {
            if let Some(h) = *h {
                mass.add(h, h, axle.mass);
            }
        }
        let base = mass.build();
        let base_lu = SparseLu::factor(&base, None)?;
        let axles = hops.len();
        Some(VehiclesOnBeam {
            loaded,
            vehicles,
            profile,
            n,
            offsets,
            dim,
            base,
            base_lu,
            damping: damped.then(|| damp.build()),
            own_damping: dampers.then(|| own.build()),
            rigid_track: stiff.build(),
            patch,
            segment: Cell::new(f64::NAN),
            contacts_at: LastEvaluation::keeping(KEPT_CONTACTS),
            forces_at: LastEvaluation::new(),
            events: (0..axles)
                .map(|k| EventSpec {
                    reason: k,
                    terminal: true,
                })
                .chain(bridging(vehicles, profile).map(|k| EventSpec {
                    reason: axles + k,
                    terminal: true,
                }))
                .collect(),
            hops,
            airborne: RefCell::new(vec![false; axles]),
            resting: RefCell::new(vec![None; axles]),
            first,
            host: OnceCell::new(),
        })
    }

    /// The vehicles ride beside the disks of `host`, whose equations hold theirs.
    pub fn ride_beside(&self, host: &'a DiskOnBeam<'a>) {
        // A second host would leave the first's equations without the vehicles.
        assert!(
            self.host.set(host).is_ok(),
            "the vehicles ride beside one set of disks"
        );
    }

    /// Where the vehicles' unknowns start in z.
    pub fn first_unknown(&self) -> usize {
        self.first
    }

    /// The beam's unknowns: the first of z.
    pub fn beam_unknowns(&self) -> usize {
        self.n
    }

    /// Where vehicle i's unknowns start in z.
    pub fn offset(&self, i: usize) -> usize {
        self.offsets[i]
    }

    /// The state (z, ż) at the start: the beam at `q0` (the model's unknowns) and at rest,
    /// every vehicle's bodies settled on its axles where the track under them puts them.
    pub fn initial_state(&self, q0: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; 2 * self.dim];
        y[..self.n].copy_from_slice(q0);
        let still = vec![0.0; self.n];
        let contacts = self.contacts(0.0, q0);
        let mut next = contacts.iter();
        for (i, v) in self.vehicles.iter().enumerate() {
            let under: Vec<f64> = v
                .axles
                .iter()
                .map(|_| {
                    self.track(next.next().expect("a contact per axle"), q0, &still)
                        .d
                })
                .collect();
            let o = self.offsets[i];
            y[o..o + v.unknowns()].copy_from_slice(&v.settled_on(&under));
        }
        y
    }

    /// The wheels' static loads at t = 0 on the mesh's unknowns, spread over their patches,
    /// for a start in static equilibrium.
    pub fn add_weights_at_rest(&self, f: &mut [f64]) {
        let beam = self.loaded.beam;
        let (b, length) = (self.patch, beam.length);
        for v in self.vehicles {
            let x_first = v.travel(0.0).0;
            for (a, axle) in v.axles.iter().enumerate() {
                let x = x_first - axle.x;
                if x > -b && x < length + b {
                    for nb in beam.patch_basis_at(x, b, PastFreeEnd::Slab) {
                        if let Some(i) = nb.w {
                            f[i] -= nb.d[0] * v.static_loads[a];
                        }
                    }
                }
            }
        }
    }

    /// The stretch between breakpoints the run is in, by its midpoint (NaN outside a run):
    /// which side of a kink of the profile the wheels read.
    pub fn stretch(&self) -> f64 {
        self.segment.get()
    }

    /// When the last wheel leaves the deck, if every vehicle does.
    pub fn gone(&self) -> Option<f64> {
        let length = self.loaded.beam.length;
        self.vehicles
            .iter()
            .map(|v| {
                v.axles
                    .last()
                    .and_then(|a| v.time_at(length + a.x + v.reach(self.patch)))
            })
            .try_fold(0.0_f64, |m, t| t.map(|t| m.max(t)))
    }

    /// When each vehicle's first wheel comes onto the deck (0 for one that starts on it;
    /// `None` for one that never gets there).
    pub fn arrives(&self) -> Vec<Option<f64>> {
        self.vehicles
            .iter()
            .map(|v| {
                if v.x0 >= -v.reach(self.patch) {
                    Some(0.0)
                } else {
                    v.time_at(-v.reach(self.patch))
                }
            })
            .collect()
    }

    /// d and ḋ of a part of vehicle i at s (an axle's from the track under it).
    fn part_motion(
        &self,
        i: usize,
        part: Part,
        s: f64,
        z: &[f64],
        zd: &[f64],
        tracks: &[Track],
    ) -> (f64, f64) {
        match part {
            Part::Axle(a) => (tracks[a].d, tracks[a].rate),
            Part::Body(b) => self.vehicles[i]
                .lever(b, s)
                .fold((0.0, 0.0), |(d, r), (j, l)| {
                    let k = self.offsets[i] + j;
                    (d + l * z[k], r + l * zd[k])
                }),
        }
    }

    /// Everything of the vehicles at (t, z, ż) in one pass: the tracks under the wheels, the
    /// springs' (e, ė), and the wheels' spring forces S_a; per vehicle.
    fn springs(&self, t: f64, z: &[f64], zd: &[f64]) -> Vec<VehicleState> {
        let contacts = self.contacts(t, &z[..self.n]);
        let (q, v) = (&z[..self.n], &zd[..self.n]);
        let mut next = contacts.iter();
        self.vehicles
            .iter()
            .enumerate()
            .map(|(i, veh)| {
                let tracks: Vec<Track> = veh
                    .axles
                    .iter()
                    .map(|_| {
                        let c = next.next().expect("a contact per axle");
                        match self.flying(c.wheel) {
                            Some(h) => Track {
                                d: z[h],
                                rate: zd[h],
                                convective: 0.0,
                            },
                            None => self.track(c, q, v),
                        }
                    })
                    .collect();
                let mut on_axle = vec![0.0; veh.axles.len()];
                let stretch = veh
                    .springs
                    .iter()
                    .map(|s| {
                        let (du, ru) = self.part_motion(i, s.upper, s.x, z, zd, &tracks);
                        let (dl, rl) = self.part_motion(i, s.lower, s.x, z, zd, &tracks);
                        let (e, ed) = (du - dl, ru - rl);
                        if let Part::Axle(a) = s.lower {
                            on_axle[a] += s.k * e + s.c * ed;
                        }
                        (e, ed)
                    })
                    .collect();
                VehicleState {
                    tracks,
                    stretch,
                    on_axle,
                }
            })
            .collect()
    }

    /// The unsprung masses' m g gᵀ, and the train's moving masses'.
    fn added_mass(&self, t: f64, z: &[f64]) -> LowRank {
        let mut out = self
            .loaded
            .mass_split(t, &z[..self.n])
            .map(|(_, l)| l)
            .unwrap_or_default();
        self.add_unsprung(t, z, &mut out);
        out
    }

    /// The unsprung masses' m g gᵀ, to `out`.
    pub fn add_unsprung(&self, t: f64, z: &[f64], out: &mut LowRank) {
        for c in self.contacts(t, &z[..self.n]).iter() {
            let m = self.vehicles[c.vehicle].axles[c.axle].mass;
            if m > 0.0 && !c.rows[0].is_empty() && self.flying(c.wheel).is_none() {
                out.push((m, c.rows[0].clone()));
            }
        }
    }

    fn unsprung(&self) -> bool {
        self.vehicles.iter().any(|v| v.has_unsprung_mass())
    }

    /// z̈ at (t, z, ż) where the wheels' contact forces feel it, through an unsprung mass's
    /// inertia; empty where no wheel has a mass, whose contact force is then its springs' and
    /// its track's alone ([`Self::contact_forces`] reads no acceleration): the energy budget
    /// and the reactions ask for the forces at every sample, and a solve for z̈ costs a force
    /// evaluation and a mass solve.
    pub fn acceleration_the_wheels_feel(&self, t: f64, z: &[f64], zd: &[f64]) -> Vec<f64> {
        if self.unsprung() {
            self.acceleration(t, z, zd)
        } else {
            Vec::new()
        }
    }

    /// z̈ at (t, z, ż): the whole system's, beside disks.
    pub fn acceleration(&self, t: f64, z: &[f64], zd: &[f64]) -> Vec<f64> {
        if let Some(host) = self.host.get() {
            return host.acceleration_beside(t, z, zd);
        }
        let mut a = vec![0.0; self.dim];
        self.force(t, z, zd, &mut a);
        self.solve_mass(t, z, &mut a);
        a
    }

    /// M(t, z)⁻¹ b, in place.
    fn solve_mass(&self, t: f64, z: &[f64], b: &mut [f64]) {
        let added = self.added_mass(t, z);
        if added.is_empty() {
            self.base_lu.solve_in_place(b);
        } else {
            match Woodbury::new(&self.base_lu, added) {
                Some(w) => w.solve_in_place(&self.base_lu, b),
                None => b.fill(f64::NAN),
            }
        }
    }

    /// Each wheel's contact force R_a = P_a + m_a d̈_a − S_a at (t, z, ż) with z̈ = `zdd`, in
    /// the order of the contacts. Only a wheel with a mass reads `zdd`: where none has one it
    /// may be empty ([`Self::acceleration_the_wheels_feel`]).
    pub fn contact_forces(&self, t: f64, z: &[f64], zd: &[f64], zdd: &[f64]) -> Vec<f64> {
        let contacts = self.contacts(t, &z[..self.n]);
        let states = self.springs(t, z, zd);
        let mut out = Vec::with_capacity(contacts.len());
        let mut next = contacts.iter();
        for (veh, st) in self.vehicles.iter().zip(&states) {
            for (a, axle) in veh.axles.iter().enumerate() {
                let c = next.next().expect("a contact per axle");
                if self.flying(c.wheel).is_some() {
                    out.push(0.0);
                    continue;
                }
                let inertia = if axle.mass > 0.0 {
                    let ga: f64 = c.rows[0].iter().map(|&(i, g)| g * zdd[i]).sum();
                    axle.mass * (ga + st.tracks[a].convective)
                } else {
                    0.0
                };
                out.push(veh.static_loads[a] + inertia - st.on_axle[a]);
            }
        }
        out
    }

    /// What the vehicles do at (t, z, ż, z̈).
    pub fn observe(&self, t: f64, z: &[f64], zd: &[f64], zdd: &[f64]) -> VehicleObservation {
        let rn = self.contact_forces(t, z, zd, zdd);
        let mut next = rn.into_iter();
        let mut out = VehicleObservation::default();
        for (i, v) in self.vehicles.iter().enumerate() {
            out.x.push(v.travel(t).0);
            out.bodies.push(
                (0..v.bodies.len())
                    .map(|b| {
                        let k = self.offsets[i] + v.first(b);
                        let theta = if v.bodies[b].pitches() {
                            z[k + 1]
                        } else {
                            f64::NAN
                        };
                        [z[k], theta, zdd[k]]
                    })
                    .collect(),
            );
            out.rn.push(
                v.axles
                    .iter()
                    .map(|_| next.next().unwrap_or(f64::NAN))
                    .collect(),
            );
        }
        out
    }

    /// The vehicles' energies at (t, z, ż): kinetic (bodies and unsprung masses), the
    /// springs', and the weights' potential Σ P_a d_a.
    pub fn energies(&self, t: f64, z: &[f64], zd: &[f64]) -> (f64, f64, f64) {
        let states = self.springs(t, z, zd);
        let (mut kinetic, mut spring, mut potential) = (0.0, 0.0, 0.0);
        for ((i, v), st) in self.vehicles.iter().enumerate().zip(&states) {
            let o = self.offsets[i];
            kinetic += v
                .mass_diagonal()
                .iter()
                .enumerate()
                .map(|(j, m)| 0.5 * m * zd[o + j] * zd[o + j])
                .sum::<f64>();
            for (a, axle) in v.axles.iter().enumerate() {
                kinetic += 0.5 * axle.mass * st.tracks[a].rate.powi(2);
                potential += v.static_loads[a] * st.tracks[a].d;
            }
            spring += v
                .springs
                .iter()
                .zip(&st.stretch)
                .map(|(s, (e, _))| 0.5 * s.k * e * e)
                .sum::<f64>();
        }
        (kinetic, spring, potential)
    }

    /// The power the dampers take at (t, z, ż): Σ c ė².
    pub fn damper_power(&self, t: f64, z: &[f64], zd: &[f64]) -> f64 {
        let states = self.springs(t, z, zd);
        self.vehicles
            .iter()
            .zip(&states)
            .flat_map(|(v, st)| v.springs.iter().zip(&st.stretch))
            .map(|(s, (_, ed))| s.c * ed * ed)
            .sum()
    }

    /// The drive's power at (t, z, ż, z̈): Σ R_a (V (g'ᵀq + r') + ṡ_a), what holds the
    /// vehicles' horizontal motion against their wheels' forces on the slopes under them, the
    /// static correction's s_a (`Contact::settled`) among them.
    pub fn drive_power(&self, t: f64, z: &[f64], zd: &[f64], zdd: &[f64]) -> f64 {
        let rn = self.contact_forces(t, z, zd, zdd);
        self.contacts(t, &z[..self.n])
            .iter()
            .zip(rn)
            .map(|(c, r)| {
                let rise = match c.disk {
                    Some(d) => d.rise,
                    None => c.rows[1].iter().map(|&(i, g)| g * z[i]).sum::<f64>() + c.r[1],
                };
                r * (c.speed * rise + c.settled[1])
            })
            .sum()
    }

    /// The wheels' forces on the beam (global, +Y up) at their places on the deck, for the
    /// support reactions and the modal beam's static correction: −R_a on each wheel on it.
    pub fn forces_on_beam(&self, t: f64, z: &[f64], zd: &[f64], zdd: &[f64]) -> Vec<(f64, f64)> {
        let rn = self.contact_forces(t, z, zd, zdd);
        let length = self.loaded.beam.length;
        self.contacts(t, &z[..self.n])
            .iter()
            .zip(rn)
            .filter(|(c, _)| !c.rows[0].is_empty())
            .map(|(c, r)| (c.x.clamp(0.0, length), -r))
            .collect()
    }

    /// The wheel of contact index k: its vehicle's index and its axle's name.
    pub fn wheel(&self, k: usize) -> (usize, String) {
        let mut k = k;
        for (i, v) in self.vehicles.iter().enumerate() {
            if k < v.axles.len() {
                return (i, v.axles[k].name.clone());
            }
            k -= v.axles.len();
        }
        (0, String::new())
    }

    /// While a wheel is on the deck, the time the fastest takes to cross the shortest length
    /// the beam's response varies over ([`LoadedBeam::finest_length`]): the drive's power on
    /// the beam changes at that pace. `None` with no wheel on the deck.
    pub fn load_passage(&self, t: f64, q: &[f64]) -> Option<f64> {
        self.fastest_on_deck(t, q)
            .map(|v| self.loaded.finest_length() / v)
    }

    /// The longest step at t: the beam's bound, and while a wheel is on the deck the time it
    /// takes to cross an element (its load has a kink at each node).
    fn step_bound(&self, t: f64, q: &[f64]) -> f64 {
        let beam = self.loaded.load_step_bound(t);
        let bound = self
            .fastest_on_deck(t, q)
            .map_or(beam, |v| beam.min(self.loaded.beam.element_length() / v));
        let bound = self.fastest_mass_on_the_mesh(t, q).map_or(bound, |v| {
            let element = self.loaded.beam.element_length();
            bound.min(element / (STEPS_OVER_AN_ELEMENT_UNDER_A_MASS * v))
        });
        let bound = self.crossing_a_free_end(t, q).map_or(bound, |v| {
            bound.min(2.0 * self.patch / (STEPS_OVER_A_FREE_END * v))
        });
        self.pivot_bound(t, q, bound)
            .map_or(bound, |p| bound.min(p))
    }

    /// While a disk wheel nears or pivots over a crest of the profile: the time to reach the
    /// pivot and a [`STEPS_OVER_A_PIVOT`]th of it more, or, pivoting, that share alone. The
    /// pivot lies where the faces' slopes put it with the deck's slope under the corner
    /// added, which the breakpoints, formed from the profile alone, do not know: a 510 kg disk
    /// wheel of 0.3 m at 8 m/s over a 5 mm ramp's top, on a 30 m steel beam of 6.6 t sloping
    /// about 0.015 there, pivoted 4.4 mm past where they put it, inside a step, and its lift-off
    /// went unseen.
    ///
    /// A crest whose pivot cannot begin within `within` of t (it lies at least a radius
    /// before the corner) leaves the bound as it is, and its deck is not read.
    fn pivot_bound(&self, t: f64, q: &[f64], within: f64) -> Option<f64> {
        if !self
            .vehicles
            .iter()
            .any(|v| matches!(v.wheel, Wheel::Disk { .. }))
        {
            return None;
        }
        let crests: Vec<_> = (self.profile.corners().into_iter())
            .filter(|(_, left, right)| right < left)
            .collect();
        if crests.is_empty() {
            return None;
        }
        // The deck on the mesh, formed at the first crest near a wheel.
        let mut mesh = None;
        let mut bound: Option<f64> = None;
        for v in self.vehicles {
            let Wheel::Disk { radius } = v.wheel else {
                continue;
            };
            let (x, speed, _) = v.travel(t);
            if !(speed > 0.0) {
                continue;
            }
            for a in &v.axles {
                let at = x - a.x;
                let near =
                    |c: &&(f64, f64, f64)| c.0 + radius > at && c.0 - radius - at < speed * within;
                for &(corner, left, right) in crests.iter().filter(near) {
                    let mesh =
                        mesh.get_or_insert_with(|| self.loaded.to_mesh(&q[..self.loaded.dim()]));
                    let deck = self.on_deck(corner, mesh, [0.0; 3])[1];
                    let (from, to) = pivot((corner, left + deck, right + deck), radius);
                    if at >= to {
                        continue;
                    }
                    let share = (to - from) / (STEPS_OVER_A_PIVOT * speed);
                    let b = (from - at).max(0.0) / speed + share;
                    bound = Some(bound.map_or(b, |c| c.min(b)));
                }
            }
        }
        bound
    }

    /// The speed of the fastest wheel whose patch straddles an end where nothing holds w, at
    /// t; `None` with none there.
    fn crossing_a_free_end(&self, t: f64, q: &[f64]) -> Option<f64> {
        self.free_ends().next()?;
        let fastest = self
            .contacts(t, q)
            .iter()
            // A wheel at the breakpoint where its patch reaches the end counts, whatever the
            // round-off in when it gets there.
            .filter(|c| {
                self.free_ends()
                    .any(|(e, _)| (c.x - e).abs() < 1.5 * self.patch)
            })
            .map(|c| c.speed.abs())
            .fold(0.0, f64::max);
        (fastest > 0.0).then_some(fastest)
    }

    /// Each end of the deck where nothing holds w: where it lies along the beam, and which way
    /// the deck lies from it (+1 from x = 0, −1 from x = L).
    fn free_ends(&self) -> impl Iterator<Item = (f64, f64)> + Clone + '_ {
        let beam = self.loaded.beam;
        [(false, 0.0, 1.0), (true, beam.length, -1.0)]
            .into_iter()
            .filter(|&(end, _, _)| !beam.holds_w_at(end))
            .map(|(_, x, inward)| (x, inward))
    }

    /// On a random road, the time the fastest wheel takes over a [`CREST_SAMPLES`]th of its
    /// shortest wave: a contact force dips over each crest sharper than the wheel follows for
    /// about that crest's width over the speed, which the steps, following the vehicle's and
    /// the deck's motion, can span. The events are looked at, and the contact forces watched
    /// for their extremes, at this pace.
    pub fn crest_pace(&self, t: f64) -> Option<f64> {
        let (wave, speed) = (self.profile.shortest_wave()?, self.fastest(t)?);
        Some(wave / (CREST_SAMPLES * speed))
    }

    /// The speed of the fastest vehicle at t, on the deck or off it; `None` with none moving.
    fn fastest(&self, t: f64) -> Option<f64> {
        let fastest = self
            .vehicles
            .iter()
            .map(|v| v.travel(t).1.abs())
            .fold(0.0, f64::max);
        (fastest > 0.0).then_some(fastest)
    }

    /// The speed of the fastest wheel on the deck at t; `None` with none on it, or none moving.
    /// Whether a wheel with a mass is on the deck, and the beam is a mesh: the deck's
    /// acceleration under it then carries every mode of the mesh into its contact force.
    pub fn mass_on_the_mesh(&self, t: f64, q: &[f64]) -> bool {
        self.fastest_mass_on_the_mesh(t, q).is_some()
    }

    /// The speed of the fastest wheel with a mass on the deck, where the beam is a mesh.
    fn fastest_mass_on_the_mesh(&self, t: f64, q: &[f64]) -> Option<f64> {
        if self.loaded.modal.is_some() {
            return None;
        }
        let fastest = self
            .contacts(t, q)
            .iter()
            .filter(|c| !c.rows[0].is_empty() && self.vehicles[c.vehicle].axles[c.axle].mass > 0.0)
            .map(|c| c.speed.abs())
            .fold(0.0, f64::max);
        (fastest > 0.0).then_some(fastest)
    }

    fn fastest_on_deck(&self, t: f64, q: &[f64]) -> Option<f64> {
        let fastest = self
            .contacts(t, q)
            .iter()
            .filter(|c| !c.rows[0].is_empty())
            .map(|c| c.speed.abs())
            .fold(0.0, f64::max);
        (fastest > 0.0).then_some(fastest)
    }
}

struct VehicleState {
    tracks: Vec<Track>,
    /// Per spring: (e, ė).
    stretch: Vec<(f64, f64)>,
    /// Per axle: S_a.
    on_axle: Vec<f64>,
}

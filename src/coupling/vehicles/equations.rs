//! How the vehicles enter the equations of motion as the integrators see them: the mass
//! (the bodies' constant, the unsprung masses' low-rank), the force, the springs' stiffness
//! and the dampers bordered by the beam's, the error norm's groups, the step bound, the
//! breakpoints where the wheels' tracks turn, and every wheel's events; and the same terms
//! as the disks beside them take them into theirs.

use std::borrow::Cow;
use std::ops::Range;

use super::{pivot, VehiclesOnBeam};
use crate::linalg::{self, Assembly, LowRank, Sparse};
use crate::ode::second_order::{SecondOrderProblem, Structure};
use crate::ode::EventSpec;
use crate::vehicle::{Part, Wheel};

impl Structure for VehiclesOnBeam<'_> {
    fn dim(&self) -> usize {
        self.dim
    }
    fn mass(&self, t: f64, z: &[f64]) -> Cow<'_, Sparse> {
        let added = self.added_mass(t, z);
        if added.is_empty() {
            return Cow::Borrowed(&self.base);
        }
        let mut a = Assembly::new(self.dim);
        a.add_sparse(&self.base, 1.0, 0, 0);
        linalg::low_rank_entries(&added).for_each(|(i, j, v)| a.add(i, j, v));
        Cow::Owned(a.build())
    }
    fn mass_is_constant(&self) -> bool {
        self.loaded.mass_is_constant() && !self.unsprung()
    }
    fn mass_split(&self, t: f64, z: &[f64]) -> Option<(&Sparse, LowRank)> {
        (!self.mass_is_constant()).then(|| (&self.base, self.added_mass(t, z)))
    }
    fn mass_mul(&self, t: f64, z: &[f64], a: &[f64], out: &mut [f64]) {
        linalg::mul(&self.base, a, out);
        for (w, g) in self.added_mass(t, z) {
            let ga = w * g.iter().map(|&(i, c)| c * a[i]).sum::<f64>();
            g.iter().for_each(|&(i, c)| out[i] += c * ga);
        }
    }
    fn force(&self, t: f64, z: &[f64], zd: &[f64], f: &mut [f64]) {
        let n = self.n;
        self.loaded.force(t, &z[..n], &zd[..n], &mut f[..n]);
        f[n..].fill(0.0);
        self.add_forces(t, z, zd, f);
    }
    fn stiffness(&self, t: f64, z: &[f64]) -> Sparse {
        let n = self.n;
        let mut a = Assembly::new(self.dim);
        a.add_sparse(&self.loaded.stiffness(t, &z[..n]), 1.0, 0, 0);
        self.add_stiffness(t, z, &mut a);
        a.build()
    }
    fn damping(&self) -> Option<Cow<'_, Sparse>> {
        let base = self.damping.as_ref()?;
        if !self.airborne.borrow().iter().any(|&a| a) {
            return Some(Cow::Borrowed(base));
        }
        let mut a = Assembly::new(self.dim);
        a.add_sparse(base, 1.0, 0, 0);
        self.add_flying_dampers(&mut a);
        Some(Cow::Owned(a.build()))
    }
    fn norm_groups(&self) -> Vec<Range<usize>> {
        if self.dim > self.n {
            vec![0..self.n, self.n..self.dim]
        } else {
            vec![0..self.n]
        }
    }
    fn norm_weights(&self) -> Option<Vec<f64>> {
        self.loaded.norm_weights().map(|mut w| {
            w.resize(self.dim, 1.0);
            w
        })
    }
    fn norm_rows(&self) -> Option<crate::ode::ModeRows> {
        self.loaded.norm_rows()
    }
}

/// The vehicles' terms in the equations of motion, which their own and the disks' beside
/// them assemble.
impl VehiclesOnBeam<'_> {
    /// The bodies' and the flying axles' masses on the diagonal, and the dampers' matrix with
    /// the axles held, as the constant parts of the equations of disks beside them take them.
    pub fn constant_terms(&self) -> (Vec<(usize, f64)>, Option<&Sparse>) {
        let bodies = self
            .vehicles
            .iter()
            .zip(&self.offsets)
            .flat_map(|(v, &o)| {
                v.mass_diagonal()
                    .into_iter()
                    .enumerate()
                    .map(move |(i, m)| (o + i, m))
            })
            .chain(
                self.vehicles
                    .iter()
                    .flat_map(|v| v.axles.iter())
                    .zip(&self.hops)
                    .filter_map(|(axle, h)| h.map(|h| (h, axle.mass))),
            )
            .collect();
        (bodies, self.own_damping.as_ref())
    }

    /// The unknowns of the vehicles, from the first body's to the last flying axle's.
    pub fn own_unknowns(&self) -> Range<usize> {
        self.first..self.dim
    }

    /// The springs' forces on the bodies and the wheels' on the beam (the beam's own are the
    /// caller's), added to f.
    pub fn add_forces(&self, t: f64, z: &[f64], zd: &[f64], f: &mut [f64]) {
        let states = self.springs(t, z, zd);
        let contacts = self.contacts(t, &z[..self.n]);
        let mut next = contacts.iter();
        for ((i, veh), st) in self.vehicles.iter().enumerate().zip(&states) {
            let o = self.offsets[i];
            for (s, &(e, ed)) in veh.springs.iter().zip(&st.stretch) {
                let pull = s.k * e + s.c * ed;
                for (part, sign) in [(s.upper, -1.0), (s.lower, 1.0)] {
                    if let Part::Body(b) = part {
                        for (j, l) in veh.lever(b, s.x) {
                            f[o + j] += sign * pull * l;
                        }
                    }
                }
            }
            for (a, axle) in veh.axles.iter().enumerate() {
                let c = next.next().expect("a contact per axle");
                if let Some(h) = self.flying(c.wheel) {
                    f[h] = st.on_axle[a] - veh.static_loads[a];
                    continue;
                }
                let on_beam =
                    -veh.static_loads[a] - axle.mass * st.tracks[a].convective + st.on_axle[a];
                for &(j, g) in &c.rows[0] {
                    f[j] += g * on_beam;
                }
            }
        }
    }

    /// The springs' stiffness, between the bodies and between each body and the beam under
    /// its wheels, added to `a`.
    pub fn add_stiffness(&self, t: f64, z: &[f64], a: &mut Assembly) {
        a.add_sparse(&self.rigid_track, 1.0, 0, 0);
        let contacts = self.contacts(t, &z[..self.n]);
        let mut next = contacts.iter();
        // Each spring on a wheel that is on the deck couples the beam under it to its body.
        let mut wheels = Vec::new();
        for veh in self.vehicles {
            wheels.push(
                veh.axles
                    .iter()
                    .map(|_| next.next().expect("a contact per axle"))
                    .collect::<Vec<_>>(),
            );
        }
        for (i, veh) in self.vehicles.iter().enumerate() {
            let o = self.offsets[i];
            for s in &veh.springs {
                let (Part::Body(b), Part::Axle(ax)) = (s.upper, s.lower) else {
                    continue;
                };
                let c = wheels[i][ax];
                let hop;
                let g = match self.flying(c.wheel) {
                    Some(h) => {
                        hop = vec![(h, 1.0)];
                        &hop
                    }
                    None => &c.rows[0],
                };
                let lever: Vec<(usize, f64)> = veh.lever(b, s.x).collect();
                for &(p, gp) in g {
                    for &(r, gr) in g {
                        a.add(p, r, s.k * gp * gr);
                    }
                    for &(j, l) in &lever {
                        a.add(p, o + j, -s.k * gp * l);
                        a.add(o + j, p, -s.k * gp * l);
                    }
                }
            }
        }
    }

    /// A flying axle's dampers, which act between it and the bodies above it, added to `a`.
    pub fn add_flying_dampers(&self, a: &mut Assembly) {
        let mut k = 0;
        for (i, veh) in self.vehicles.iter().enumerate() {
            for s in &veh.springs {
                let (Part::Body(b), Part::Axle(ax)) = (s.upper, s.lower) else {
                    continue;
                };
                if let Some(h) = self.flying(k + ax) {
                    a.add(h, h, s.c);
                    for (j, l) in veh.lever(b, s.x) {
                        let o = self.offsets[i] + j;
                        a.add(h, o, -s.c * l);
                        a.add(o, h, -s.c * l);
                    }
                }
            }
            k += veh.axles.len();
        }
    }
}

impl SecondOrderProblem for VehiclesOnBeam<'_> {
    /// The wheel whose contact force fell to zero, or which, flying, touched the track.
    type Event = usize;
    fn max_step(&self, t: f64, _q: &[f64], _v: &[f64]) -> f64 {
        self.step_bound(t, _q)
    }
    /// The beam's, each wheel's arrival on and departure from the deck, its crossing of each
    /// kink of the profile, and each vehicle's stop.
    fn breakpoints(&self) -> Vec<f64> {
        let length = self.loaded.beam.length;
        let kinks = self.profile.kinks();
        let mut out = self.loaded.breakpoints();
        for v in self.vehicles {
            out.extend(v.stops_at());
            let reach = v.reach(self.patch);
            // A point wheel's track turns at each kink. A disk pivots over a crest from where
            // its contact reaches the corner to where it leaves it, X = x − a s/√(1 + s²) for
            // each face's slope s; in a hollow it rests on both faces at one place, where its
            // contact jumps from one to the other: there, with the centre at the height a disk
            // on either face has, line + a √(1 + s²). The drive's power turns at each.
            let turns: Vec<f64> = match v.wheel {
                Wheel::Point => kinks.clone(),
                Wheel::Disk { radius } => self
                    .profile
                    .corners()
                    .into_iter()
                    .flat_map(|(x, left, right)| {
                        if right > left {
                            let lift = |s: f64| (1.0 + s * s).sqrt();
                            vec![x + radius * (lift(right) - lift(left)) / (left - right)]
                        } else {
                            let (from, to) = pivot((x, left, right), radius);
                            vec![from, to]
                        }
                    })
                    .collect(),
            };
            // Where a free end lets the patch's slab step by the tip's deflection, the steps
            // shorten from where the patch reaches it ([`Self::crossing_a_free_end`]).
            let reaching = self.free_ends().map(|(x, inward)| x + inward * reach);
            for a in &v.axles {
                let places = [-reach, length + reach]
                    .into_iter()
                    .chain(reaching.clone())
                    .chain(turns.iter().copied());
                out.extend(places.filter_map(|x| v.time_at(x + a.x)));
            }
        }
        out
    }
    fn enter_segment(&self, start: f64, end: f64) {
        self.loaded.enter_segment(start, end);
        self.segment.set(0.5 * (start + end));
    }
    fn events(&self) -> &[EventSpec<usize>] {
        &self.events
    }
    fn event_pace(&self, t: f64, _q: &[f64], _v: &[f64]) -> f64 {
        self.crest_pace(t).unwrap_or(f64::INFINITY)
    }
    fn accepted(&self, t: f64, q: &[f64], _v: &[f64]) {
        self.remember_crests(t, q);
    }
    fn event(&self, index: usize, t: f64, z: &[f64], zd: &[f64]) -> f64 {
        if let Some(k) = self.crest_event(self.events[index].reason) {
            return self.crest_ahead(k, t, z);
        }
        if let Some(h) = self.flying(index) {
            return self.gap(index, t, z, h);
        }
        let scale = self
            .vehicles
            .iter()
            .flat_map(|v| v.static_loads.iter())
            .fold(0.0_f64, |m, p| m.max(*p));
        let stretch = [self.segment.get()];
        let rn = self.forces_at.at(t, &[z, zd, &stretch], || {
            self.contact_forces(t, z, zd, &self.acceleration_the_wheels_feel(t, z, zd))
        });
        rn[index] / scale
    }
}

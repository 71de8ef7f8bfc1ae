//! A vehicle as bridge dynamics models it: rigid bodies that move vertically, and pitch where
//! they have rotary inertia, carried by linear spring–dampers on axles whose wheels follow the
//! track (VBI-2D's sprung masses and trucks, a railway car's body, bogies and wheelsets).
//! Positions along a vehicle are metres behind its first axle; it travels towards +x.
//!
//! The unknowns are each body's vertical displacement from its static equilibrium on a level
//! rigid track, and its pitch (nose up positive) where it pitches. A point on body b at s
//! behind the first axle moves by y_b + θ_b (x_b − s): its lever over the body's unknowns is
//! (1, x_b − s). An axle moves with the track under it. A spring between an upper and a lower
//! part at s stretches by e = d_upper(s) − d_lower(s) from its static length and pulls the
//! two together with k e + c ė.

pub mod profile;

use nalgebra::{DMatrix, DVector};

/// A rigid body of a vehicle.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    pub name: String,
    pub mass: f64,
    /// Rotary inertia about the centre of mass (kg m²); 0: the body does not pitch.
    pub inertia: f64,
    /// Centre of mass, m behind the first axle.
    pub x: f64,
}

impl Body {
    pub fn pitches(&self) -> bool {
        self.inertia > 0.0
    }
}

/// A wheel and what moves with it (the unsprung mass).
#[derive(Clone, Debug, PartialEq)]
pub struct Axle {
    pub name: String,
    /// m behind the first axle.
    pub x: f64,
    pub mass: f64,
}

/// A body or an axle of one vehicle, by index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    Body(usize),
    Axle(usize),
}

/// A linear spring–damper acting vertically between two parts at one position.
#[derive(Clone, Debug, PartialEq)]
pub struct Spring {
    pub upper: Part,
    pub lower: Part,
    /// m behind the first axle.
    pub x: f64,
    pub k: f64,
    pub c: f64,
}

/// How an axle follows the track.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Wheel {
    /// At one point.
    Point,
    /// A rigid disk of this radius (m) resting on the track where it lifts its centre highest:
    /// it bridges what is shorter than itself and rounds the kinks it rolls over.
    Disk { radius: f64 },
}

#[derive(Clone, Debug)]
pub struct Vehicle {
    pub name: String,
    /// The first axle's position along the beam at t = 0 (m).
    pub x0: f64,
    /// m/s at t = 0.
    pub speed: f64,
    /// m/s², constant until the vehicle stops.
    pub acceleration: f64,
    pub bodies: Vec<Body>,
    pub axles: Vec<Axle>,
    pub springs: Vec<Spring>,
    pub wheel: Wheel,
    /// Where each body's unknowns start among the vehicle's.
    first: Vec<usize>,
    /// The force each axle's wheel bears at rest (N): its share of the weight.
    pub static_loads: Vec<f64>,
}

/// Why a vehicle cannot be built: a sentence for the scene's checker.
pub type Refusal = String;

/// The fastest a vehicle's bodies may ring on their springs with the axles held (Hz). Far
/// above any suspension (a hub on its tyre rings at tens of hertz, a rigid attachment given as
/// a stiff spring at kilohertz: Biggs' sprung mass on 10¹² N/m, 2 kHz, is the moving mass to
/// 10⁻⁶), and far below where round-off in a spring's stretch outweighs the weights: that
/// sprung mass on 10²² N/m (2·10⁸ Hz) reported its wheel losing contact a microsecond into
/// the run, and on 10²¹ N/m (7·10⁷ Hz) its numbers still held.
pub const MAX_SUSPENSION_HZ: f64 = 1e6;

impl Vehicle {
    /// How far from a wheel's centre its contact can touch the deck, given the patch's
    /// half-width: the patch, and a disk's radius.
    pub fn reach(&self, patch: f64) -> f64 {
        patch
            + match self.wheel {
                Wheel::Point => 0.0,
                Wheel::Disk { radius } => radius,
            }
    }

    /// Whether an axle has a mass of its own, which takes an impulse wherever the track turns.
    pub fn has_unsprung_mass(&self) -> bool {
        self.axles.iter().any(|a| a.mass > 0.0)
    }

    /// The vehicle, its static axle loads found under `gravity`; refused where a body is not
    /// held by springs or an axle would have to pull on the track.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        name: String,
        x0: f64,
        speed: f64,
        acceleration: f64,
        bodies: Vec<Body>,
        axles: Vec<Axle>,
        springs: Vec<Spring>,
        gravity: f64,
    ) -> Result<Vehicle, Refusal> {
        let mut first = Vec::with_capacity(bodies.len());
        let mut count = 0;
        for b in &bodies {
            first.push(count);
            count += 1 + usize::from(b.pitches());
        }
        let mut v = Vehicle {
            name,
            x0,
            speed,
            acceleration,
            bodies,
            axles,
            springs,
            wheel: Wheel::Point,
            first,
            static_loads: Vec::new(),
        };
        v.held()?;
        v.static_loads = v.rest(gravity)?;
        v.followable()?;
        Ok(v)
    }

    /// The vehicle's unknowns.
    pub fn unknowns(&self) -> usize {
        self.bodies
            .iter()
            .map(|b| 1 + usize::from(b.pitches()))
            .sum()
    }

    /// Where body b's unknowns start among the vehicle's: y, then θ where it pitches.
    pub fn first(&self, b: usize) -> usize {
        self.first[b]
    }

    /// The lever of body b at s over the vehicle's unknowns: how a unit of each moves the point.
    pub fn lever(&self, b: usize, s: f64) -> impl Iterator<Item = (usize, f64)> {
        let body = &self.bodies[b];
        let first = self.first[b];
        std::iter::once((first, 1.0)).chain(body.pitches().then_some((first + 1, body.x - s)))
    }

    /// The vehicle's own mass matrix, diagonal: each body's mass, and its inertia where it
    /// pitches.
    pub fn mass_diagonal(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.unknowns());
        for b in &self.bodies {
            out.push(b.mass);
            if b.pitches() {
                out.push(b.inertia);
            }
        }
        out
    }

    /// The fastest natural frequency (Hz) of the bodies on their springs with the axles held:
    /// the time scale the steps must follow for the bodies' accelerations to hold.
    pub fn fastest_suspension_hz(&self) -> f64 {
        let k = self.on_rigid_track(true);
        let m = self.mass_diagonal();
        let scaled = DMatrix::from_fn(m.len(), m.len(), |i, j| k[(i, j)] / (m[i] * m[j]).sqrt());
        let largest = scaled.symmetric_eigenvalues().max();
        largest.max(0.0).sqrt() / std::f64::consts::TAU
    }

    /// Σ w l lᵀ over the springs between bodies and of the bodies' ends of the springs on
    /// axles (the axles held still), with w = k (`stiff`) or c: the vehicle's stiffness or
    /// damping on a rigid track.
    pub fn on_rigid_track(&self, stiff: bool) -> DMatrix<f64> {
        let n = self.unknowns();
        let mut m = DMatrix::zeros(n, n);
        for s in &self.springs {
            let w = if stiff { s.k } else { s.c };
            let mut row = vec![0.0; n];
            for (part, sign) in [(s.upper, 1.0), (s.lower, -1.0)] {
                if let Part::Body(b) = part {
                    for (i, l) in self.lever(b, s.x) {
                        row[i] += sign * l;
                    }
                }
            }
            for i in 0..n {
                for j in 0..n {
                    m[(i, j)] += w * row[i] * row[j];
                }
            }
        }
        m
    }

    /// Every body is joined to an axle through springs, and a body that pitches has springs at
    /// two places at least: otherwise it would fall or turn freely.
    fn held(&self) -> Result<(), Refusal> {
        if self.axles.is_empty() {
            return Err(format!("vehicle {} has no axle to rest on", self.name));
        }
        let mut reached = vec![false; self.bodies.len()];
        let mut changed = true;
        while changed {
            changed = false;
            for s in &self.springs {
                for (a, b) in [(s.upper, s.lower), (s.lower, s.upper)] {
                    let holds = match b {
                        Part::Axle(_) => true,
                        Part::Body(j) => reached[j],
                    };
                    if let Part::Body(i) = a {
                        if !reached[i] && holds {
                            reached[i] = true;
                            changed = true;
                        }
                    }
                }
            }
        }
        if let Some(b) = reached.iter().position(|r| !r) {
            return Err(format!(
                "vehicle {}: body {} is joined to no axle through springs, so nothing holds it up",
                self.name, self.bodies[b].name
            ));
        }
        for (i, b) in self.bodies.iter().enumerate().filter(|(_, b)| b.pitches()) {
            let mut places = self
                .springs
                .iter()
                .filter(|s| s.upper == Part::Body(i) || s.lower == Part::Body(i))
                .map(|s| s.x);
            let first = places.next();
            if places.all(|x| Some(x) == first) {
                return Err(format!(
                    "vehicle {}: body {} pitches (inertia > 0) but its springs all act at one place, so nothing holds its pitch: give it springs at two places, or inertia 0",
                    self.name, b.name
                ));
            }
        }
        Ok(())
    }

    /// The bodies ring on their springs no faster than [`MAX_SUSPENSION_HZ`].
    fn followable(&self) -> Result<(), Refusal> {
        let f = self.fastest_suspension_hz();
        if f > MAX_SUSPENSION_HZ {
            return Err(format!(
                "vehicle {}: its bodies ring on their springs at up to {f:.3e} Hz (the axles held), past the {MAX_SUSPENSION_HZ:.0e} Hz a run can follow before round-off in the springs' stretch outweighs the weights; a rigid attachment is a spring whose frequency lies far above the deck's, a few kilohertz: soften the stiffest spring or give the lightest body more mass or inertia",
                self.name
            ));
        }
        Ok(())
    }

    /// The force each wheel bears at rest on a level rigid track: the bodies settle under
    /// their weight on springs whose axle ends stay put, and each axle carries its own weight
    /// and what its springs press on it.
    fn rest(&self, gravity: f64) -> Result<Vec<f64>, Refusal> {
        let n = self.unknowns();
        let k = self.on_rigid_track(true);
        let mut weight = DVector::zeros(n);
        for (b, body) in self.bodies.iter().enumerate() {
            weight[self.first[b]] = -body.mass * gravity;
        }
        let settled = if n == 0 {
            DVector::zeros(0)
        } else {
            k.clone().cholesky().map(|c| c.solve(&weight)).ok_or_else(|| {
                format!(
                    "vehicle {}: its springs do not hold its bodies still (the stiffness on a rigid track is singular)",
                    self.name
                )
            })?
        };
        let mut loads: Vec<f64> = self.axles.iter().map(|a| a.mass * gravity).collect();
        for s in &self.springs {
            let Part::Axle(a) = s.lower else { continue };
            let Part::Body(b) = s.upper else { continue };
            let stretch: f64 = self.lever(b, s.x).map(|(i, l)| l * settled[i]).sum();
            loads[a] -= s.k * stretch;
        }
        if let Some(a) = loads.iter().position(|p| !(*p > 0.0) && gravity > 0.0) {
            return Err(format!(
                "vehicle {} does not rest on its axles: axle {} would bear {:.6e} N, so the bodies' centres of mass lie beyond the axles that carry them",
                self.name, self.axles[a].name, loads[a]
            ));
        }
        Ok(loads)
    }

    /// The bodies' displacements at rest on axles displaced by `under` (m, one per axle) from
    /// where they stood in the static equilibrium.
    pub fn settled_on(&self, under: &[f64]) -> Vec<f64> {
        let n = self.unknowns();
        let mut f = DVector::zeros(n);
        for s in &self.springs {
            if let (Part::Body(b), Part::Axle(a)) = (s.upper, s.lower) {
                for (i, l) in self.lever(b, s.x) {
                    f[i] += s.k * l * under[a];
                }
            }
        }
        match self.on_rigid_track(true).cholesky() {
            Some(c) => c.solve(&f).iter().copied().collect(),
            None => vec![0.0; n],
        }
    }

    /// The fastest it runs from t = 0 to `until`: its speed changes one way, so at either end.
    pub fn top_speed(&self, until: f64) -> f64 {
        self.travel(0.0).1.abs().max(self.travel(until).1.abs())
    }

    /// When the vehicle stops, braking: `None` while it keeps going.
    pub fn stops_at(&self) -> Option<f64> {
        (self.acceleration < 0.0).then(|| -self.speed / self.acceleration)
    }

    /// The first axle's position, speed and acceleration at t.
    pub fn travel(&self, t: f64) -> (f64, f64, f64) {
        let t_run = self.stops_at().map_or(t, |ts| t.min(ts));
        let still = self.stops_at().is_some_and(|ts| t >= ts);
        let x = self.x0 + self.speed * t_run + 0.5 * self.acceleration * t_run * t_run;
        if still {
            (x, 0.0, 0.0)
        } else {
            (x, self.speed + self.acceleration * t_run, self.acceleration)
        }
    }

    /// When the first axle is at `x` (m), if it ever gets there (after t = 0).
    pub fn time_at(&self, x: f64) -> Option<f64> {
        let d = x - self.x0;
        if d < 0.0 {
            return None;
        }
        let (v, a) = (self.speed, self.acceleration);
        if a == 0.0 {
            return Some(d / v);
        }
        let disc = v * v + 2.0 * a * d;
        if disc < 0.0 {
            return None;
        }
        let t = 2.0 * d / (v + disc.sqrt());
        self.stops_at().is_none_or(|ts| t <= ts).then_some(t)
    }

    /// The total weight (N) under `gravity`.
    pub fn weight(&self, gravity: f64) -> f64 {
        gravity
            * (self.bodies.iter().map(|b| b.mass).sum::<f64>()
                + self.axles.iter().map(|a| a.mass).sum::<f64>())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body(name: &str, mass: f64, inertia: f64, x: f64) -> Body {
        Body {
            name: name.into(),
            mass,
            inertia,
            x,
        }
    }

    fn axle(name: &str, x: f64) -> Axle {
        Axle {
            name: name.into(),
            x,
            mass: 100.0,
        }
    }

    /// A body on two axles 4 m apart with its centre 1 m behind the first: statics of a beam
    /// on two supports puts 3/4 of its weight on the first axle, whatever the springs'
    /// stiffnesses; every axle also carries its own weight.
    #[test]
    fn a_pitching_body_shares_its_weight_as_a_beam_on_two_supports() {
        let g = 9.81;
        let springs = vec![
            Spring {
                upper: Part::Body(0),
                lower: Part::Axle(0),
                x: 0.0,
                k: 1e6,
                c: 0.0,
            },
            Spring {
                upper: Part::Body(0),
                lower: Part::Axle(1),
                x: 4.0,
                k: 3e6,
                c: 0.0,
            },
        ];
        let v = Vehicle::new(
            "truck".into(),
            0.0,
            10.0,
            0.0,
            vec![body("body", 1000.0, 500.0, 1.0)],
            vec![axle("front", 0.0), axle("rear", 4.0)],
            springs,
            g,
        )
        .expect("held");
        let expected = [750.0 * g + 100.0 * g, 250.0 * g + 100.0 * g];
        for (p, e) in v.static_loads.iter().zip(expected) {
            assert!((p - e).abs() < 1e-9 * e, "{p} against {e}");
        }
    }

    #[test]
    fn a_loose_body_and_a_body_past_its_axles_are_refused() {
        let on = |lower| Spring {
            upper: Part::Body(0),
            lower,
            x: 0.0,
            k: 1e6,
            c: 0.0,
        };
        let loose = Vehicle::new(
            "v".into(),
            0.0,
            1.0,
            0.0,
            vec![body("body", 1.0, 0.0, 0.0), body("cargo", 1.0, 0.0, 0.0)],
            vec![axle("a", 0.0)],
            vec![on(Part::Axle(0))],
            9.81,
        );
        assert!(loose.unwrap_err().contains("cargo is joined to no axle"));
        let mut springs = vec![on(Part::Axle(0)), on(Part::Axle(1))];
        springs[1].x = 2.0;
        let tipping = Vehicle::new(
            "v".into(),
            0.0,
            1.0,
            0.0,
            vec![body("body", 1000.0, 10.0, 5.0)],
            vec![axle("a", 0.0), axle("b", 2.0)],
            springs,
            9.81,
        );
        assert!(tipping.unwrap_err().contains("does not rest on its axles"));
    }

    /// Braking from 20 m/s at −4 m/s² stops after 5 s and 50 m, and stays there.
    #[test]
    fn a_braking_vehicle_stops_where_kinematics_says() {
        let v = Vehicle {
            name: "v".into(),
            x0: -10.0,
            speed: 20.0,
            acceleration: -4.0,
            bodies: Vec::new(),
            axles: Vec::new(),
            springs: Vec::new(),
            wheel: Wheel::Point,
            first: Vec::new(),
            static_loads: Vec::new(),
        };
        assert_eq!(v.stops_at(), Some(5.0));
        assert_eq!(v.travel(7.0), (40.0, 0.0, 0.0));
        let t = v.time_at(30.0).expect("reached");
        assert!((v.travel(t).0 - 30.0).abs() < 1e-12);
        assert!(v.time_at(40.5).is_none());
    }
}

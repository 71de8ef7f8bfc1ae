//! Vehicles on a beam track and the profile of its running surface.

use super::*;
use crate::vehicle::profile::{iso_terms, Profile, ISO_CLASSES, MAX_CREST_SCAN, MAX_ISO_TERMS};
use crate::vehicle::{Axle, Body, Part, Spring, Vehicle, Wheel};

/// Most vehicles a scene may carry, and parts (bodies, axles, springs) of each: every part is
/// read at every evaluation, and a vehicle's stiffness is formed dense.
pub(super) const MAX_VEHICLES: usize = 100;
pub(super) const MAX_PARTS: usize = 200;
/// Most points a piecewise-linear profile may hold (every one is a breakpoint per axle).
pub(super) const MAX_PROFILE_POINTS: usize = 10_000;
/// Largest radius of a disk wheel (m).
pub(super) const MAX_WHEEL_RADIUS: f64 = 10.0;
/// Least radius of a disk wheel, as a share of the distances it rides over
/// ([`disk_within_round_off`]).
pub(super) const MIN_WHEEL_SHARE: f64 = 1e-6;
/// Most breakpoints the wheels make: each wheel's arrival, departure and crossing of every
/// kink of the profile ends a step, and the driver holds them all.
pub(super) const MAX_WHEEL_BREAKPOINTS: usize = 1_000_000;

/// The wheels' breakpoints within [`MAX_WHEEL_BREAKPOINTS`].
pub(super) fn wheel_breakpoints(
    c: &Checker,
    raw: &SceneFile,
    vehicles: &[Vehicle],
    profile: &Profile,
) -> Result<(), Error> {
    let wheels: usize = vehicles.iter().map(|v| v.axles.len()).sum();
    let kinks = profile.kinks().len();
    let count = wheels.saturating_mul(kinks + 2);
    if count > MAX_WHEEL_BREAKPOINTS {
        let line = profile_line(raw);
        return c.err(
            line,
            "track.profile",
            format!("has {kinks} kinks under {wheels} wheels: {count} crossings, each ending a step, and at most {MAX_WHEEL_BREAKPOINTS} are held; use fewer points or fewer wheels"),
        );
    }
    Ok(())
}

/// The line of `track.profile`, which the checks of the wheels on it report.
fn profile_line(raw: &SceneFile) -> u64 {
    raw.track
        .value
        .profile
        .as_ref()
        .map_or(0, |p| p.referenced.line())
}

/// A disk wheel on a road that bends faster than the disk looks for the crest it rests on
/// over its whole reach, at `SCAN_PER_WAVE` points a shortest wave: refused past
/// [`MAX_CREST_SCAN`] points (a radius of 256 shortest waves), which every contact would scan.
pub(super) fn disk_wheels_on_the_road(
    c: &Checker,
    raw: &SceneFile,
    vehicles: &[Vehicle],
    profile: &Profile,
) -> Result<(), Error> {
    for v in vehicles {
        let Wheel::Disk { radius } = v.wheel else {
            continue;
        };
        let Some(scan) = profile.crest_scan(radius).filter(|s| *s > MAX_CREST_SCAN) else {
            continue;
        };
        let line = profile_line(raw);
        let wave = profile.shortest_wave().unwrap_or(0.0);
        return c.err(
            line,
            "track.profile.iso8608.wavelengths",
            format!("reach down to {wave:.3e} m, which vehicle {}'s disk wheels of radius {radius} m bridge: the road bends faster than the disk, so each contact scans the disk's reach for the crest it rests on, at {scan:.0e} points, past {MAX_CREST_SCAN}; raise the shortest wavelength to at least {:.3e} m (a 256th of the radius) or use point wheels", v.name, radius / 256.0),
        );
    }
    Ok(())
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct VehicleFile {
    pub(super) name: Spanned<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) x0: Option<Spanned<f64>>,
    pub(super) speed: Spanned<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) acceleration: Option<Spanned<f64>>,
    pub(super) bodies: Spanned<Vec<Spanned<BodyFile>>>,
    pub(super) axles: Spanned<Vec<Spanned<AxleFile>>>,
    pub(super) springs: Spanned<Vec<Spanned<SpringFile>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) wheel: Option<Spanned<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) radius: Option<Spanned<f64>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BodyFile {
    pub(super) name: Spanned<String>,
    pub(super) mass: Spanned<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) inertia: Option<Spanned<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) x: Option<Spanned<f64>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct AxleFile {
    pub(super) name: Spanned<String>,
    pub(super) x: Spanned<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) mass: Option<Spanned<f64>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SpringFile {
    pub(super) upper: Spanned<String>,
    pub(super) lower: Spanned<String>,
    pub(super) x: Spanned<f64>,
    pub(super) k: Spanned<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) c: Option<Spanned<f64>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ProfileFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) points: Option<Spanned<Vec<[f64; 2]>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) iso8608: Option<Spanned<IsoFile>>,
}

#[derive(Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(super) struct IsoFile {
    pub(super) class: Spanned<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) seed: Option<Spanned<u64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) wavelengths: Option<Spanned<[f64; 2]>>,
}

/// When vehicle v's last axle (its patch) has left a deck of `length`, or, braking to a
/// stop before that, when it stops.
pub(super) fn vehicle_gone(v: &Vehicle, length: f64, patch: f64) -> f64 {
    let last = v.axles.last().map_or(0.0, |a| a.x);
    v.time_at(length + last + v.reach(patch))
        .or(v.stops_at())
        .unwrap_or(0.0)
}

/// Vehicles ride level beams only: their bodies move vertically.
pub(super) fn vehicles(
    c: &Checker,
    raw: &SceneFile,
    beam: &BeamSpec,
    gravity: f64,
) -> Result<Vec<Vehicle>, Error> {
    let Some(list) = &raw.vehicles else {
        return Ok(Vec::new());
    };
    let line = list.referenced.line();
    if list.value.is_empty() || list.value.len() > MAX_VEHICLES {
        return c.err(
            line,
            "vehicles",
            format!("must list 1 to {MAX_VEHICLES} vehicles"),
        );
    }
    if beam.from[1] != beam.to[1] || beam.to[0] <= beam.from[0] {
        return c.err(
            line,
            "vehicles",
            "ride a level beam whose `to` lies ahead of its `from` in x: their bodies move vertically",
        );
    }
    if !(gravity > 0.0) {
        return c.err(
            line,
            "vehicles",
            format!("rest on their axles under their weight, and gravity is {gravity}: give a positive `gravity`"),
        );
    }
    let mut out: Vec<Vehicle> = Vec::new();
    for v in &list.value {
        let vehicle = one(c, &v.value, gravity)?;
        disk_within_round_off(c, &v.value, &vehicle, beam.to[0] - beam.from[0])?;
        if out.iter().any(|o| o.name == vehicle.name) {
            return c.err(
                v.value.name.referenced.line(),
                "vehicles.name",
                format!("= {} names two vehicles", quote(&vehicle.name)),
            );
        }
        out.push(vehicle);
    }
    Ok(out)
}

/// A name that names columns: `<vehicle>.<part>.<quantity>`.
fn name(c: &Checker, n: &Spanned<String>, key: &str) -> Result<String, Error> {
    let why = name_flaw(&n.value, 40).or_else(|| {
        n.value.contains([',', '"', '.']).then(|| {
            "holds a comma, a quote or a dot, which the output's column names cannot".into()
        })
    });
    match why {
        Some(why) => c.err(
            n.referenced.line(),
            key,
            format!("= {} {why}", quote(&n.value)),
        ),
        None => Ok(n.value.clone()),
    }
}

fn non_negative(c: &Checker, v: &Spanned<f64>, key: &str) -> Result<f64, Error> {
    let x = c.finite(v, key)?;
    if x < 0.0 {
        return c.err(
            v.referenced.line(),
            key,
            format!("must not be negative (got {x})"),
        );
    }
    Ok(x)
}

fn one(c: &Checker, v: &VehicleFile, gravity: f64) -> Result<Vehicle, Error> {
    let vname = name(c, &v.name, "vehicles.name")?;
    let speed = c.positive(&v.speed, "vehicles.speed")?;
    let speed = c.speed(v.speed.referenced.line(), "vehicles.speed", speed)?;
    let x0 =
        v.x0.as_ref()
            .map_or(Ok(0.0), |x| c.finite(x, "vehicles.x0"))?;
    let acceleration = v
        .acceleration
        .as_ref()
        .map_or(Ok(0.0), |a| c.finite(a, "vehicles.acceleration"))?;
    let wheel = wheel_of(c, v)?;
    within_bounds(c, v, &vname)?;
    let (bodies, axles) = bodies_and_axles(c, v, &vname)?;
    let springs = springs_of(c, v, &vname, &bodies, &axles)?;
    let mut vehicle = Vehicle::new(
        vname,
        x0,
        speed,
        acceleration,
        bodies,
        axles,
        springs,
        gravity,
    )
    .or_else(|why| c.err(v.name.referenced.line(), "vehicles", why))?;
    vehicle.wheel = wheel;
    Ok(vehicle)
}

/// The vehicle's wheel: a point, or a disk of a radius within [`MAX_WHEEL_RADIUS`].
fn wheel_of(c: &Checker, v: &VehicleFile) -> Result<Wheel, Error> {
    Ok(match v.wheel.as_ref().map(|w| (w, w.value.as_str())) {
        None | Some((_, "point")) => {
            if let Some(r) = &v.radius {
                return c.err(
                    r.referenced.line(),
                    "vehicles.radius",
                    "is a disk wheel's: give `wheel: disk` with it, or leave it out",
                );
            }
            Wheel::Point
        }
        Some((w, "disk")) => {
            let Some(r) = &v.radius else {
                return c.err(
                    w.referenced.line(),
                    "vehicles.wheel",
                    "is disk, which needs the disk's `radius` (m)",
                );
            };
            let radius = c.positive(r, "vehicles.radius")?;
            if radius > MAX_WHEEL_RADIUS {
                return c.err(
                    r.referenced.line(),
                    "vehicles.radius",
                    format!("= {radius} m is more than a wheel is: at most {MAX_WHEEL_RADIUS} m"),
                );
            }
            Wheel::Disk { radius }
        }
        Some((w, other)) => {
            return c.err(
                w.referenced.line(),
                "vehicles.wheel",
                format!("is {}; a wheel is point or disk", quote(other)),
            );
        }
    })
}

/// A disk wheel at least [`MIN_WHEEL_SHARE`] of the distances its wheels ride over (the
/// deck's length, and the approach from `x0`): its contact is sought to 10⁻¹⁰ of its radius,
/// which positions that far along resolve only to their round-off, and below that share
/// the search and the drive's power turn to round-off noise (a 10⁻⁷ m disk on a 20 m deck ran
/// a hundred times as long as a 10⁻⁴ m one, 10⁻⁹ m did not end in minutes).
fn disk_within_round_off(
    c: &Checker,
    v: &VehicleFile,
    vehicle: &Vehicle,
    length: f64,
) -> Result<(), Error> {
    let Wheel::Disk { radius } = vehicle.wheel else {
        return Ok(());
    };
    let last = vehicle.axles.last().map_or(0.0, |a| a.x);
    let reach = length.max(vehicle.x0.abs()).max((vehicle.x0 - last).abs());
    if radius >= MIN_WHEEL_SHARE * reach {
        return Ok(());
    }
    let line = v.radius.as_ref().map_or(0, |r| r.referenced.line());
    c.err(
        line,
        "vehicles.radius",
        format!("= {radius} m is below a millionth of the {reach} m its wheels ride over, where the disk's contact is lost in the positions' round-off: a disk that small is a point (`wheel: point`), or give at least {:.3e} m", MIN_WHEEL_SHARE * reach),
    )
}

/// At most [`MAX_PARTS`] bodies, axles and springs, and an axle to rest on.
fn within_bounds(c: &Checker, v: &VehicleFile, vname: &str) -> Result<(), Error> {
    for (list, key, count) in [
        (
            v.bodies.referenced.line(),
            "vehicles.bodies",
            v.bodies.value.len(),
        ),
        (
            v.axles.referenced.line(),
            "vehicles.axles",
            v.axles.value.len(),
        ),
        (
            v.springs.referenced.line(),
            "vehicles.springs",
            v.springs.value.len(),
        ),
    ] {
        if count > MAX_PARTS {
            return c.err(
                list,
                key,
                format!("lists {count}; a vehicle has at most {MAX_PARTS}"),
            );
        }
    }
    if v.axles.value.is_empty() {
        return c.err(
            v.axles.referenced.line(),
            "vehicles.axles",
            format!("is empty: vehicle {} has no axle to rest on", quote(vname)),
        );
    }
    Ok(())
}

/// The bodies and axles, each name once, the axles from 0 behind the first and increasing.
fn bodies_and_axles(
    c: &Checker,
    v: &VehicleFile,
    vname: &str,
) -> Result<(Vec<Body>, Vec<Axle>), Error> {
    let mut names: Vec<String> = Vec::new();
    let mut fresh = |n: &Spanned<String>, key: &str| -> Result<String, Error> {
        let s = name(c, n, key)?;
        if names.contains(&s) {
            return c.err(
                n.referenced.line(),
                key,
                format!(
                    "= {} names two parts of vehicle {}",
                    quote(&s),
                    quote(vname)
                ),
            );
        }
        names.push(s.clone());
        Ok(s)
    };
    let mut bodies = Vec::new();
    for b in &v.bodies.value {
        let b = &b.value;
        bodies.push(Body {
            name: fresh(&b.name, "vehicles.bodies.name")?,
            mass: c.positive(&b.mass, "vehicles.bodies.mass")?,
            inertia: b
                .inertia
                .as_ref()
                .map_or(Ok(0.0), |i| non_negative(c, i, "vehicles.bodies.inertia"))?,
            x: b.x
                .as_ref()
                .map_or(Ok(0.0), |x| c.finite(x, "vehicles.bodies.x"))?,
        });
    }
    let mut axles: Vec<Axle> = Vec::new();
    for a in &v.axles.value {
        let a = &a.value;
        let x = c.finite(&a.x, "vehicles.axles.x")?;
        let expected_first = axles.is_empty() && x != 0.0;
        if expected_first || axles.last().is_some_and(|p| x <= p.x) {
            return c.err(
                a.x.referenced.line(),
                "vehicles.axles.x",
                "must be distances behind the first axle (m), from 0 and increasing",
            );
        }
        axles.push(Axle {
            name: fresh(&a.name, "vehicles.axles.name")?,
            x,
            mass: a
                .mass
                .as_ref()
                .map_or(Ok(0.0), |m| non_negative(c, m, "vehicles.axles.mass"))?,
        });
    }
    Ok((bodies, axles))
}

/// The spring–dampers, each between a body and a body or an axle, within the vehicle's
/// reach, one on an axle acting at it.
fn springs_of(
    c: &Checker,
    v: &VehicleFile,
    vname: &str,
    bodies: &[Body],
    axles: &[Axle],
) -> Result<Vec<Spring>, Error> {
    let part = |n: &Spanned<String>, key: &str| -> Result<Part, Error> {
        if let Some(b) = bodies.iter().position(|b| b.name == n.value) {
            return Ok(Part::Body(b));
        }
        if let Some(a) = axles.iter().position(|a| a.name == n.value) {
            return Ok(Part::Axle(a));
        }
        c.err(
            n.referenced.line(),
            key,
            format!(
                "= {} names no body or axle of vehicle {}",
                quote(&n.value),
                quote(vname)
            ),
        )
    };
    let first = axles.first().map_or(0.0, |a| a.x);
    let last = axles.last().map_or(0.0, |a| a.x);
    let reach = bodies
        .iter()
        .map(|b| b.x)
        .chain([first, last])
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
    let mut springs = Vec::new();
    for s in &v.springs.value {
        let s = &s.value;
        let upper = part(&s.upper, "vehicles.springs.upper")?;
        let lower = part(&s.lower, "vehicles.springs.lower")?;
        let x = c.finite(&s.x, "vehicles.springs.x")?;
        if matches!(upper, Part::Axle(_)) {
            return c.err(
                s.upper.referenced.line(),
                "vehicles.springs.upper",
                format!(
                    "= {} is an axle; a spring's upper part is a body, its lower a body or an axle",
                    quote(&s.upper.value)
                ),
            );
        }
        if upper == lower {
            return c.err(
                s.lower.referenced.line(),
                "vehicles.springs.lower",
                "is the spring's upper part too: a spring joins two parts",
            );
        }
        if let Part::Axle(a) = lower {
            if x != axles[a].x {
                return c.err(
                    s.x.referenced.line(),
                    "vehicles.springs.x",
                    format!("= {x} is not where axle {} is ({} m behind the first): a spring on an axle acts at the axle", quote(&axles[a].name), axles[a].x),
                );
            }
        }
        if x < reach.0 || x > reach.1 {
            return c.err(
                s.x.referenced.line(),
                "vehicles.springs.x",
                format!(
                    "= {x} lies outside vehicle {} (its axles and bodies reach from {} to {} m)",
                    quote(vname),
                    reach.0,
                    reach.1
                ),
            );
        }
        springs.push(Spring {
            upper,
            lower,
            x,
            k: c.positive(&s.k, "vehicles.springs.k")?,
            c: s.c
                .as_ref()
                .map_or(Ok(0.0), |d| non_negative(c, d, "vehicles.springs.c"))?,
        });
    }
    Ok(springs)
}

/// The running surface's profile; refused where no vehicle rides on it.
pub(super) fn profile(c: &Checker, raw: &SceneFile, track: &TrackFile) -> Result<Profile, Error> {
    let Some(p) = &track.profile else {
        return Ok(Profile::Smooth);
    };
    let line = p.referenced.line();
    if raw.vehicles.is_none() {
        return c.err(
            line,
            "track.profile",
            "is the surface vehicles ride on; this scene has none",
        );
    }
    match (&p.value.points, &p.value.iso8608) {
        (Some(points), None) => {
            let pts = &points.value;
            let line = points.referenced.line();
            if pts.is_empty() || pts.len() > MAX_PROFILE_POINTS {
                return c.err(
                    line,
                    "track.profile.points",
                    format!("must hold 1 to {MAX_PROFILE_POINTS} points [x, r]"),
                );
            }
            if pts.iter().flatten().any(|v| !v.is_finite()) {
                return c.err(line, "track.profile.points", "must hold finite numbers (m)");
            }
            if pts.windows(2).any(|w| w[1][0] <= w[0][0]) {
                return c.err(
                    line,
                    "track.profile.points",
                    "must be [x, r] with x increasing",
                );
            }
            Ok(Profile::Points(pts.clone()))
        }
        (None, Some(iso)) => {
            let i = &iso.value;
            let class = i.class.value.as_str();
            let known = class.len() == 1 && ISO_CLASSES.contains(class);
            if !known {
                return c.err(
                    i.class.referenced.line(),
                    "track.profile.iso8608.class",
                    format!("is {}; ISO 8608's classes are A to H", quote(class)),
                );
            }
            let [shortest, longest] = match &i.wavelengths {
                None => [0.5, 50.0],
                Some(w) => {
                    let w2 = c.pair(w, "track.profile.iso8608.wavelengths")?;
                    if !(w2[0] > 0.0 && w2[1] > w2[0]) {
                        return c.err(
                            w.referenced.line(),
                            "track.profile.iso8608.wavelengths",
                            "must be [shortest, longest] (m), positive and increasing",
                        );
                    }
                    if iso_terms(w2[0], w2[1]).is_none() {
                        return c.err(
                            w.referenced.line(),
                            "track.profile.iso8608.wavelengths",
                            format!(
                                "= [{:e}, {:e}] m spans more than the road's {MAX_ISO_TERMS} cosines hold (spaced evenly in wavenumber at most half the longest wave's wavenumber apart, so that the long waves carry their variance): keep the longest at most {} times the shortest",
                                w2[0],
                                w2[1],
                                MAX_ISO_TERMS / 2
                            ),
                        );
                    }
                    w2
                }
            };
            let seed = i.seed.as_ref().map_or(1, |s| s.value);
            let ch = class.chars().next().expect("one character");
            Profile::iso8608(ch, seed, shortest, longest).map_or_else(
                || c.err(line, "track.profile.iso8608", "could not be drawn"),
                Ok,
            )
        }
        _ => c.err(
            line,
            "track.profile",
            "needs `points` or `iso8608`, one of them",
        ),
    }
}

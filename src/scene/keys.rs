//! Editing a scene by dotted key (`disk.omega0`, `track.beam.E`): what `sweep --set`, the
//! Python package's `with_values` and the tests change before the scene is checked again.

use super::*;

impl SceneSpec {
    /// Set the number at a dotted key of the scene format (`disk.omega0`, `track.beam.E`,
    /// `track.beam.elements`, `disks.2.s0`, …), whether or not the file gives it. The changed scene is not
    /// checked here: [`SceneSpec::check`] does that.
    pub fn set(&mut self, key: &str, value: f64) -> Result<(), Error> {
        let f = &mut self.file;
        let unset = |what: &str| {
            Err(Error::Input(format!(
                "`{key}` cannot be set: the scene has no {what}"
            )))
        };
        let number = |slot: &mut Spanned<f64>| slot.value = value;
        let option = |slot: &mut Option<Spanned<f64>>| match slot {
            Some(s) => s.value = value,
            None => *slot = Some(given(value)),
        };
        match key.split_once('.') {
            None => match key {
                "gravity" => option(&mut f.gravity),
                "duration" => number(&mut f.duration),
                _ => return Err(not_a_number(key)),
            },
            Some(("track", rest)) => match rest.split_once('.') {
                Some(("beam", field)) => {
                    let Some(b) = f.track.value.beam.as_mut() else {
                        return unset("beam track");
                    };
                    set_beam(&mut b.value, field, value, key)?;
                }
                Some(("curve", "parabola.k")) => {
                    match f
                        .track
                        .value
                        .curve
                        .as_mut()
                        .and_then(|c| c.value.parabola.as_mut())
                    {
                        Some(p) => number(&mut p.k),
                        None => return unset("parabola"),
                    }
                }
                _ => return Err(not_a_number(key)),
            },
            Some(("disk", field)) => {
                let Some(d) = f.disk.as_mut() else {
                    return unset("disk");
                };
                set_disk(&mut d.value, field, value, key)?;
            }
            Some(("disks", rest)) => {
                let (d, field) = listed_disk(f, rest, key)?;
                set_disk(d, field, value, key)?;
            }
            Some(("train", field)) => {
                let Some(t) = f.train.as_mut() else {
                    return unset("train");
                };
                match field {
                    "speed" => number(&mut t.value.speed),
                    _ => return Err(not_a_number(key)),
                }
            }
            Some(("vehicles", rest)) => set_vehicles(f, rest, value, key)?,
            Some(("solver", field)) => {
                let s = f.solver.get_or_insert_with(SolverFile::default);
                match field {
                    "rtol" => option(&mut s.rtol),
                    "atol" => option(&mut s.atol),
                    "rho_inf" => option(&mut s.rho_inf),
                    "accuracy" => option(&mut s.accuracy),
                    _ => return Err(not_a_number(key)),
                }
            }
            Some(("output", field)) => {
                let o = f.output.get_or_insert_with(OutputFile::default);
                match field {
                    "interval" => option(&mut o.interval),
                    "magnify" => option(&mut o.magnify),
                    "acceleration_cutoff_hz" => option(&mut o.acceleration_cutoff_hz),
                    _ => return Err(not_a_number(key)),
                }
            }
            _ => return Err(not_a_number(key)),
        }
        Ok(())
    }

    /// Leave out an optional key, so that its default applies (`output.shapes`, `solver.rtol`,
    /// `track.beam.elements`, …).
    pub fn unset(&mut self, key: &str) -> Result<(), Error> {
        let f = &mut self.file;
        let no = |what: &str| {
            Err(Error::Input(format!(
                "`{key}` cannot be left out: the scene has no {what}"
            )))
        };
        match key {
            "gravity" => f.gravity = None,
            "loads" => f.loads = None,
            "track.beam.elements"
            | "track.beam.order"
            | "track.beam.quadrature"
            | "track.beam.initial"
            | "track.beam.depth"
            | "track.beam.model"
            | "track.beam.modes"
            | "track.beam.damping"
            | "track.beam.self_weight" => {
                let Some(b) = f.track.value.beam.as_mut() else {
                    return no("beam track");
                };
                let b = &mut b.value;
                match key {
                    "track.beam.elements" => b.elements = None,
                    "track.beam.order" => b.order = None,
                    "track.beam.quadrature" => b.quadrature = None,
                    "track.beam.depth" => b.depth = None,
                    "track.beam.model" => b.model = None,
                    "track.beam.modes" => b.modes = None,
                    "track.beam.damping" => b.damping = None,
                    "track.beam.self_weight" => b.self_weight = None,
                    _ => b.initial = None,
                }
            }
            _ if key.starts_with("disk.") && DISK_OPTIONAL.contains(&&key["disk.".len()..]) => {
                let Some(d) = f.disk.as_mut() else {
                    return no("disk");
                };
                unset_disk(&mut d.value, &key["disk.".len()..]);
            }
            _ if key.starts_with("disks.") => {
                let (d, field) = listed_disk(f, &key["disks.".len()..], key)?;
                if !DISK_OPTIONAL.contains(&field) {
                    return Err(Error::Input(format!(
                        "`{key}` is not an optional key of the scene format"
                    )));
                }
                unset_disk(d, field);
            }
            "solver.method" | "solver.rtol" | "solver.atol" | "solver.rho_inf"
            | "solver.accuracy" => {
                if let Some(s) = f.solver.as_mut() {
                    match key {
                        "solver.method" => s.method = None,
                        "solver.rtol" => s.rtol = None,
                        "solver.atol" => s.atol = None,
                        "solver.rho_inf" => s.rho_inf = None,
                        _ => s.accuracy = None,
                    }
                }
            }
            "output.interval"
            | "output.probes"
            | "output.shapes"
            | "output.magnify"
            | "output.acceleration_cutoff_hz" => {
                if let Some(o) = f.output.as_mut() {
                    match key {
                        "output.interval" => o.interval = None,
                        "output.probes" => o.probes = None,
                        "output.shapes" => o.shapes = None,
                        "output.magnify" => o.magnify = None,
                        _ => o.acceleration_cutoff_hz = None,
                    }
                }
            }
            _ => {
                return Err(Error::Input(format!(
                    "`{key}` is not an optional key of the scene format"
                )))
            }
        }
        Ok(())
    }

    /// Set the name at a dotted key of the scene format (`disk.coupling`, `solver.method`,
    /// `track.beam.quadrature`, …), whether or not the file gives it.
    pub fn set_name(&mut self, key: &str, value: &str) -> Result<(), Error> {
        let f = &mut self.file;
        let text = |slot: &mut Option<Spanned<String>>| match slot {
            Some(s) => s.value = value.into(),
            None => *slot = Some(given(value.to_string())),
        };
        match key {
            "name" => text(&mut f.name),
            _ if key
                .strip_prefix("disk.")
                .is_some_and(|field| DISK_NAMES.contains(&field)) =>
            {
                let Some(d) = f.disk.as_mut() else {
                    return Err(Error::Input(format!(
                        "`{key}` cannot be set: the scene has no disk"
                    )));
                };
                text(disk_name(&mut d.value, &key["disk.".len()..]));
            }
            _ if key.starts_with("disks.") => {
                let (d, field) = listed_disk(f, &key["disks.".len()..], key)?;
                if !DISK_NAMES.contains(&field) {
                    return Err(Error::Input(format!("`{key}` does not take a name")));
                }
                text(disk_name(d, field));
            }
            "solver.method" => text(&mut f.solver.get_or_insert_with(SolverFile::default).method),
            "train.hslm" | "train.model" => {
                let Some(t) = f.train.as_mut() else {
                    return Err(Error::Input(format!(
                        "`{key}` cannot be set: the scene has no train"
                    )));
                };
                if key == "train.hslm" {
                    text(&mut t.value.hslm);
                    t.value.axles = None;
                    t.value.load = None;
                } else {
                    text(&mut t.value.model);
                }
            }
            "track.beam.self_weight" => {
                let Some(b) = f.track.value.beam.as_mut() else {
                    return Err(Error::Input(format!(
                        "`{key}` cannot be set: the scene has no beam track"
                    )));
                };
                let on = match value {
                    "true" => true,
                    "false" => false,
                    _ => {
                        return Err(Error::Input(format!(
                            "`{key}` is true or false (got {})",
                            quote(value)
                        )))
                    }
                };
                b.value.self_weight = Some(given(on));
            }
            "track.beam.quadrature" | "track.beam.initial" | "track.beam.model" => {
                let Some(b) = f.track.value.beam.as_mut() else {
                    return Err(Error::Input(format!(
                        "`{key}` cannot be set: the scene has no beam track"
                    )));
                };
                match key {
                    "track.beam.quadrature" => text(&mut b.value.quadrature),
                    "track.beam.model" => text(&mut b.value.model),
                    _ => text(&mut b.value.initial),
                }
            }
            _ if key
                .strip_prefix("vehicles.")
                .and_then(|rest| rest.split_once('.'))
                .is_some_and(|(_, field)| field == "wheel") =>
            {
                let name = &key["vehicles.".len()..key.len() - ".wheel".len()];
                let mut any = false;
                for v in f.vehicles.iter_mut().flat_map(|l| l.value.iter_mut()) {
                    if name == "*" || v.value.name.value == name {
                        text(&mut v.value.wheel);
                        any = true;
                    }
                }
                if !any {
                    return Err(Error::Input(format!(
                        "`{key}` cannot be set: the scene has no vehicle named {}",
                        quote(name)
                    )));
                }
            }
            _ => {
                return Err(Error::Input(format!(
                    "`{key}` does not take a name (a number key is swept as `{key}=FROM:TO:COUNT`); the keys that take names are name, disk.coupling, disk.formulation, disk.contact_loss (and disks.<k>.coupling, disks.<k>.contact_loss), solver.method, train.hslm, train.model, track.beam.model, track.beam.quadrature, track.beam.initial, track.beam.self_weight and vehicles.<name>.wheel"
                )))
            }
        }
        Ok(())
    }
}

/// A disk's keys that may be left out, after `disk.` or `disks.<k>.`.
const DISK_OPTIONAL: [&str; 8] = [
    "s0",
    "omega0",
    "mu",
    "patch",
    "coupling",
    "formulation",
    "contact_loss",
    "restitution",
];

/// A disk's keys that take a name, after `disk.` or `disks.<k>.`.
const DISK_NAMES: [&str; 3] = ["coupling", "formulation", "contact_loss"];

/// Disk k of the list `disks` (k from 1, as errors name it) and the field after it, from
/// `<k>.<field>` of the key `key`.
fn listed_disk<'f>(
    f: &'f mut SceneFile,
    rest: &'f str,
    key: &str,
) -> Result<(&'f mut DiskFile, &'f str), Error> {
    let (k, field) = rest.split_once('.').unwrap_or((rest, ""));
    let count = f.disks.as_ref().map_or(0, |l| l.value.len());
    match k.parse::<usize>() {
        Ok(k) if (1..=count).contains(&k) => {
            let list = f.disks.as_mut().expect("counted above");
            Ok((&mut list.value[k - 1].value, field))
        }
        _ => Err(Error::Input(format!(
            "`{key}` cannot be changed: `disks.<k>` takes k from 1 to the {count} disks the scene lists"
        ))),
    }
}

/// Set the number `field` of a disk.
fn set_disk(d: &mut DiskFile, field: &str, value: f64, key: &str) -> Result<(), Error> {
    let option = |slot: &mut Option<Spanned<f64>>| match slot {
        Some(s) => s.value = value,
        None => *slot = Some(given(value)),
    };
    match field {
        "mass" => d.mass.value = value,
        "radius" => d.radius.value = value,
        "s0" => option(&mut d.s0),
        "omega0" => option(&mut d.omega0),
        "mu" => option(&mut d.mu),
        "patch" => option(&mut d.patch),
        "restitution" => option(&mut d.restitution),
        _ => return Err(not_a_number(key)),
    }
    Ok(())
}

/// Leave out the optional `field` of a disk (one of [`DISK_OPTIONAL`]).
fn unset_disk(d: &mut DiskFile, field: &str) {
    match field {
        "s0" => d.s0 = None,
        "omega0" => d.omega0 = None,
        "mu" => d.mu = None,
        "patch" => d.patch = None,
        "coupling" => d.coupling = None,
        "contact_loss" => d.contact_loss = None,
        "restitution" => d.restitution = None,
        _ => d.formulation = None,
    }
}

/// The slot of a disk's name key `field` (one of [`DISK_NAMES`]).
fn disk_name<'d>(d: &'d mut DiskFile, field: &str) -> &'d mut Option<Spanned<String>> {
    match field {
        "coupling" => &mut d.coupling,
        "formulation" => &mut d.formulation,
        _ => &mut d.contact_loss,
    }
}

/// Set the number `field` (after `track.beam.`) of a beam track.
fn set_beam(b: &mut BeamFile, field: &str, value: f64, key: &str) -> Result<(), Error> {
    let number = |slot: &mut Spanned<f64>| slot.value = value;
    let option = |slot: &mut Option<Spanned<f64>>| match slot {
        Some(s) => s.value = value,
        None => *slot = Some(given(value)),
    };
    let whole = |slot: &mut Option<Spanned<i64>>| whole_number(slot, value, key);
    match field {
        "E" => number(&mut b.E),
        "G" => number(&mut b.G),
        "rho" => number(&mut b.rho),
        "A" => number(&mut b.A),
        "Av" => number(&mut b.Av),
        "I" => number(&mut b.I),
        "depth" => option(&mut b.depth),
        "elements" => whole(&mut b.elements)?,
        "order" => whole(&mut b.order)?,
        "modes" => whole(&mut b.modes)?,
        "damping.ratio" | "damping.alpha" | "damping.beta" => {
            let d = &mut b
                .damping
                .get_or_insert_with(|| given(DampingFile::default()))
                .value;
            match field {
                "damping.ratio" => option(&mut d.ratio),
                "damping.alpha" => option(&mut d.alpha),
                _ => option(&mut d.beta),
            }
        }
        _ => return Err(not_a_number(key)),
    }
    Ok(())
}

/// Set a whole-number key's `slot` to `value`, which must be whole.
fn whole_number(slot: &mut Option<Spanned<i64>>, value: f64, key: &str) -> Result<(), Error> {
    if value.fract() != 0.0 || value.abs() > 1e15 {
        return Err(Error::Input(format!(
            "`{key}` takes a whole number (got {value})"
        )));
    }
    let v = value as i64;
    match slot {
        Some(s) => s.value = v,
        None => *slot = Some(given(v)),
    }
    Ok(())
}

/// A value set rather than read: it has no line in the file.
pub(super) fn given<T>(value: T) -> Spanned<T> {
    Spanned::new(value, Location::UNKNOWN, Location::UNKNOWN)
}

/// Set `<name>.<field>` (after `vehicles.`) on the vehicle named, or with `*` on every one.
fn set_vehicles(f: &mut SceneFile, rest: &str, value: f64, key: &str) -> Result<(), Error> {
    let Some((name, field)) = rest.split_once('.') else {
        return Err(not_a_number(key));
    };
    // `*` sets the key on every vehicle: a train of vehicles runs at one speed.
    let mut any = false;
    for v in f.vehicles.iter_mut().flat_map(|l| l.value.iter_mut()) {
        if name == "*" || v.value.name.value == name {
            set_vehicle(&mut v.value, field, value, key)?;
            any = true;
        }
    }
    if !any {
        return Err(Error::Input(format!(
            "`{key}` cannot be set: the scene has no vehicle named {}",
            quote(name)
        )));
    }
    Ok(())
}

/// Set `field` (after `vehicles.<name>.`) of one vehicle to `value`.
fn set_vehicle(v: &mut VehicleFile, field: &str, value: f64, key: &str) -> Result<(), Error> {
    let name = v.name.value.clone();
    let unset = |what: String| -> Result<(), Error> {
        Err(Error::Input(format!(
            "`{key}` cannot be set: vehicle {} has no {what}",
            quote(&name)
        )))
    };
    let option = |slot: &mut Option<Spanned<f64>>| match slot {
        Some(s) => s.value = value,
        None => *slot = Some(given(value)),
    };
    match field.split('.').collect::<Vec<_>>()[..] {
        ["speed"] => v.speed.value = value,
        ["x0"] => option(&mut v.x0),
        ["acceleration"] => option(&mut v.acceleration),
        ["radius"] => option(&mut v.radius),
        ["springs", i, what @ ("k" | "c")] => {
            let Some(s) = i
                .parse::<usize>()
                .ok()
                .and_then(|i| v.springs.value.get_mut(i))
            else {
                return unset(format!("spring {i}"));
            };
            match what {
                "k" => s.value.k.value = value,
                _ => option(&mut s.value.c),
            }
        }
        [part, what @ ("mass" | "inertia")] => {
            if let Some(b) = v
                .bodies
                .value
                .iter_mut()
                .find(|b| b.value.name.value == part)
            {
                match what {
                    "mass" => b.value.mass.value = value,
                    _ => option(&mut b.value.inertia),
                }
            } else if let Some(a) = v
                .axles
                .value
                .iter_mut()
                .find(|a| a.value.name.value == part && what == "mass")
            {
                option(&mut a.value.mass)
            } else {
                return unset(format!("body or axle {} with {what}", quote(part)));
            }
        }
        _ => return Err(not_a_number(key)),
    }
    Ok(())
}

pub(super) fn not_a_number(key: &str) -> Error {
    Error::Input(format!(
        "`{key}` is not a number the scene format holds (keys are dotted paths such as disk.omega0, track.beam.E or solver.rtol)"
    ))
}

//! Editing a scene by dotted key (`disk.omega0`, `track.beam.E`, `disks.2.s0`): what `sweep
//! --set`, the Python package's `with_values` and the tests change before the scene is
//! checked again. [`KEYS`] lists every key and what it holds; [`find`] matches a key to its
//! row and `slots` to its place in the file; setting a number or a name, leaving a key out
//! and every message about keys read those.

use super::*;

/// What a key holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Holds {
    Number,
    /// A whole number.
    Whole,
    Name,
    /// `true` or `false`.
    Flag,
    /// A section or a list, which an edit can only leave out.
    Part,
}

/// A key of the scene format. In its path, `<k>` is a listed disk (from 1), `<name>` a
/// vehicle's name (or `*`: every vehicle), `<part>` the name of one of its bodies or axles and
/// `<i>` one of its springs (from 0). `disks.<k>.` takes every key `disk.` takes.
#[derive(Clone, Copy, Debug)]
pub struct Key {
    pub path: &'static str,
    pub holds: Holds,
}

const fn key(path: &'static str, holds: Holds) -> Key {
    Key { path, holds }
}

use Holds::{Flag, Name, Number, Part, Whole};

/// Every key an edit can reach.
pub const KEYS: &[Key] = &[
    key("name", Name),
    key("gravity", Number),
    key("duration", Number),
    key("loads", Part),
    key("track.curve.parabola.k", Number),
    key("track.beam.E", Number),
    key("track.beam.G", Number),
    key("track.beam.rho", Number),
    key("track.beam.A", Number),
    key("track.beam.Av", Number),
    key("track.beam.I", Number),
    key("track.beam.depth", Number),
    key("track.beam.elements", Whole),
    key("track.beam.order", Whole),
    key("track.beam.modes", Whole),
    key("track.beam.quadrature", Name),
    key("track.beam.initial", Name),
    key("track.beam.model", Name),
    key("track.beam.self_weight", Flag),
    key("track.beam.damping", Part),
    key("track.beam.damping.ratio", Number),
    key("track.beam.damping.alpha", Number),
    key("track.beam.damping.beta", Number),
    key("disk.mass", Number),
    key("disk.radius", Number),
    key("disk.s0", Number),
    key("disk.omega0", Number),
    key("disk.mu", Number),
    key("disk.patch", Number),
    key("disk.restitution", Number),
    key("disk.coupling", Name),
    key("disk.formulation", Name),
    key("disk.contact_loss", Name),
    key("train.hslm", Name),
    key("train.model", Name),
    key("train.speed", Number),
    key("track.profile.iso8608.class", Name),
    key("track.profile.iso8608.seed", Whole),
    key("vehicles.<name>.speed", Number),
    key("vehicles.<name>.x0", Number),
    key("vehicles.<name>.acceleration", Number),
    key("vehicles.<name>.radius", Number),
    key("vehicles.<name>.wheel", Name),
    key("vehicles.<name>.springs.<i>.k", Number),
    key("vehicles.<name>.springs.<i>.c", Number),
    key("vehicles.<name>.<part>.mass", Number),
    key("vehicles.<name>.<part>.inertia", Number),
    key("solver.method", Name),
    key("solver.rtol", Number),
    key("solver.atol", Number),
    key("solver.rho_inf", Number),
    key("solver.accuracy", Number),
    key("output.interval", Number),
    key("output.probes", Part),
    key("output.shapes", Part),
    key("output.magnify", Number),
    key("output.acceleration_cutoff_hz", Number),
];

/// A key matched to its row of [`KEYS`], with what its placeholders stand for.
#[derive(Clone, Debug)]
pub struct Found<'k> {
    pub key: Key,
    /// The listed disk, where the key is `disks.<k>.…` (as written: not yet checked).
    disk: Option<&'k str>,
    /// `<name>`, `<part>` and `<i>`, in the order the path names them.
    names: Vec<&'k str>,
}

/// The row of [`KEYS`] a dotted key is, if any.
pub fn find(dotted: &str) -> Option<Found<'_>> {
    let (disk, rest) = match dotted.strip_prefix("disks.").map(|r| r.split_once('.')) {
        Some(Some((k, field))) if !k.is_empty() => (Some(k), vec!["disk", field]),
        Some(_) => return None,
        None => (None, vec![dotted]),
    };
    let parts: Vec<&str> = rest.iter().flat_map(|p| p.split('.')).collect();
    KEYS.iter().find_map(|key| {
        let pattern: Vec<&str> = key.path.split('.').collect();
        if pattern.len() != parts.len() {
            return None;
        }
        let mut names = Vec::new();
        for (want, got) in pattern.iter().zip(&parts) {
            if want.starts_with('<') && !got.is_empty() {
                names.push(*got);
            } else if want != got {
                return None;
            }
        }
        Some(Found {
            key: *key,
            disk,
            names,
        })
    })
}

/// Whether a dotted key holds a number (`train.speed`), where a sweep lists numbers for it.
pub fn holds_number(dotted: &str) -> bool {
    find(dotted).is_some_and(|f| matches!(f.key.holds, Number | Whole))
}

/// Whether a dotted key is one of the scene format's, of any kind.
pub fn is_key(dotted: &str) -> bool {
    find(dotted).is_some()
}

/// A key's place in the file.
enum Slot<'f> {
    /// A number the file must give.
    Number(&'f mut Spanned<f64>),
    /// A number the file may leave out.
    MaybeNumber(&'f mut Option<Spanned<f64>>),
    Whole(&'f mut Option<Spanned<i64>>),
    Name(&'f mut Option<Spanned<String>>),
    /// A name the file must give.
    RequiredName(&'f mut Spanned<String>),
    /// A whole number that is not negative, which the file may leave out.
    Count(&'f mut Option<Spanned<u64>>),
    Flag(&'f mut Option<Spanned<bool>>),
    Part(&'f mut dyn LeftOut),
    /// The train's HSLM name, which replaces the axles and loads the file gives.
    Hslm(&'f mut TrainFile),
}

/// What an edit can leave out whole.
trait LeftOut {
    fn leave_out(&mut self);
}

impl<T> LeftOut for Option<T> {
    fn leave_out(&mut self) {
        *self = None;
    }
}

/// Why a key has no place in this scene: the end of "`key` cannot be set: …".
struct Absent(String);

fn no(what: &str) -> Absent {
    Absent(format!("the scene has no {what}"))
}

/// The places of a found key in the file (several for `vehicles.*.…`). A section that only
/// holds optional keys (`solver`, `output`, a beam's `damping`) is made where `make`, and
/// otherwise its keys have no place, which leaves nothing to do.
fn slots<'f>(f: &'f mut SceneFile, found: &Found, make: bool) -> Result<Vec<Slot<'f>>, Absent> {
    let path = found.key.path;
    let (section, field) = path.split_once('.').unwrap_or((path, ""));
    let one = |slot| Ok(vec![slot]);
    match section {
        "name" => one(Slot::Name(&mut f.name)),
        "gravity" => one(Slot::MaybeNumber(&mut f.gravity)),
        "duration" => one(Slot::Number(&mut f.duration)),
        "loads" => one(Slot::Part(&mut f.loads)),
        "track" => track_slot(&mut f.track.value, field, make).map(|s| s.into_iter().collect()),
        "disk" => {
            let d = match found.disk {
                Some(k) => listed_disk(f, k)?,
                None => &mut f.disk.as_mut().ok_or_else(|| no("disk"))?.value,
            };
            one(disk_slot(d, field))
        }
        "train" => {
            let t = &mut f.train.as_mut().ok_or_else(|| no("train"))?.value;
            one(match field {
                "hslm" => Slot::Hslm(t),
                "model" => Slot::Name(&mut t.model),
                _ => Slot::Number(&mut t.speed),
            })
        }
        "vehicles" => vehicle_slots(f, field, &found.names),
        "solver" => Ok(solver_slot(&mut f.solver, field, make)
            .into_iter()
            .collect()),
        _ => Ok(output_slot(&mut f.output, field, make)
            .into_iter()
            .collect()),
    }
}

fn track_slot<'f>(
    t: &'f mut TrackFile,
    field: &str,
    make: bool,
) -> Result<Option<Slot<'f>>, Absent> {
    if let Some(iso) = field.strip_prefix("profile.iso8608.") {
        let road = t.profile.as_mut().and_then(|p| p.value.iso8608.as_mut());
        let road = &mut road
            .ok_or_else(|| no("ISO 8608 road (`track.profile.iso8608`)"))?
            .value;
        return Ok(Some(match iso {
            "class" => Slot::RequiredName(&mut road.class),
            _ => Slot::Count(&mut road.seed),
        }));
    }
    if field == "curve.parabola.k" {
        let p = t.curve.as_mut().and_then(|c| c.value.parabola.as_mut());
        return Ok(Some(Slot::Number(&mut p.ok_or_else(|| no("parabola"))?.k)));
    }
    let b = &mut t.beam.as_mut().ok_or_else(|| no("beam track"))?.value;
    Ok(Some(match field.strip_prefix("beam.").unwrap_or(field) {
        "E" => Slot::Number(&mut b.E),
        "G" => Slot::Number(&mut b.G),
        "rho" => Slot::Number(&mut b.rho),
        "A" => Slot::Number(&mut b.A),
        "Av" => Slot::Number(&mut b.Av),
        "I" => Slot::Number(&mut b.I),
        "depth" => Slot::MaybeNumber(&mut b.depth),
        "elements" => Slot::Whole(&mut b.elements),
        "order" => Slot::Whole(&mut b.order),
        "modes" => Slot::Whole(&mut b.modes),
        "quadrature" => Slot::Name(&mut b.quadrature),
        "initial" => Slot::Name(&mut b.initial),
        "model" => Slot::Name(&mut b.model),
        "self_weight" => Slot::Flag(&mut b.self_weight),
        "damping" => Slot::Part(&mut b.damping),
        damping => {
            if b.damping.is_none() && !make {
                return Ok(None);
            }
            let d = &mut b
                .damping
                .get_or_insert_with(|| given(DampingFile::default()))
                .value;
            Slot::MaybeNumber(match damping {
                "damping.ratio" => &mut d.ratio,
                "damping.alpha" => &mut d.alpha,
                _ => &mut d.beta,
            })
        }
    }))
}

/// Disk k of the list `disks`, k from 1 as errors name it.
fn listed_disk<'f>(f: &'f mut SceneFile, k: &str) -> Result<&'f mut DiskFile, Absent> {
    let count = f.disks.as_ref().map_or(0, |l| l.value.len());
    match k.parse::<usize>() {
        Ok(k) if (1..=count).contains(&k) => {
            let list = f.disks.as_mut().expect("counted above");
            Ok(&mut list.value[k - 1].value)
        }
        _ => Err(Absent(format!(
            "`disks.<k>` takes k from 1 to the {count} disks the scene lists"
        ))),
    }
}

fn disk_slot<'f>(d: &'f mut DiskFile, field: &str) -> Slot<'f> {
    match field {
        "mass" => Slot::Number(&mut d.mass),
        "radius" => Slot::Number(&mut d.radius),
        "s0" => Slot::MaybeNumber(&mut d.s0),
        "omega0" => Slot::MaybeNumber(&mut d.omega0),
        "mu" => Slot::MaybeNumber(&mut d.mu),
        "patch" => Slot::MaybeNumber(&mut d.patch),
        "restitution" => Slot::MaybeNumber(&mut d.restitution),
        "coupling" => Slot::Name(&mut d.coupling),
        "formulation" => Slot::Name(&mut d.formulation),
        _ => Slot::Name(&mut d.contact_loss),
    }
}

/// `vehicles.<name>.…` on the vehicle named, or with `*` on every one (a train of vehicles
/// runs at one speed).
fn vehicle_slots<'f>(
    f: &'f mut SceneFile,
    field: &str,
    names: &[&str],
) -> Result<Vec<Slot<'f>>, Absent> {
    let name = names[0];
    let field = field.split_once('.').map_or(field, |(_, rest)| rest);
    let mut out = Vec::new();
    for v in f.vehicles.iter_mut().flat_map(|l| l.value.iter_mut()) {
        if name == "*" || v.value.name.value == name {
            out.push(vehicle_slot(&mut v.value, field, &names[1..])?);
        }
    }
    if out.is_empty() {
        return Err(Absent(format!(
            "the scene has no vehicle named {}",
            quote(name)
        )));
    }
    Ok(out)
}

fn vehicle_slot<'f>(
    v: &'f mut VehicleFile,
    field: &str,
    names: &[&str],
) -> Result<Slot<'f>, Absent> {
    let whose = quote(&v.name.value);
    let lacks = |what: String| Absent(format!("vehicle {whose} has no {what}"));
    Ok(match field.rsplit('.').next().unwrap_or(field) {
        "speed" => Slot::Number(&mut v.speed),
        "x0" => Slot::MaybeNumber(&mut v.x0),
        "acceleration" => Slot::MaybeNumber(&mut v.acceleration),
        "radius" => Slot::MaybeNumber(&mut v.radius),
        "wheel" => Slot::Name(&mut v.wheel),
        what @ ("k" | "c") => {
            let i = names[0];
            let s = i
                .parse::<usize>()
                .ok()
                .and_then(|i| v.springs.value.get_mut(i))
                .ok_or_else(|| lacks(format!("spring {i}")))?;
            match what {
                "k" => Slot::Number(&mut s.value.k),
                _ => Slot::MaybeNumber(&mut s.value.c),
            }
        }
        what => {
            let part = names[0];
            if let Some(b) = v
                .bodies
                .value
                .iter_mut()
                .find(|b| b.value.name.value == part)
            {
                match what {
                    "mass" => Slot::Number(&mut b.value.mass),
                    _ => Slot::MaybeNumber(&mut b.value.inertia),
                }
            } else {
                let axle = v.axles.value.iter_mut();
                match axle
                    .filter(|_| what == "mass")
                    .find(|a| a.value.name.value == part)
                {
                    Some(a) => Slot::MaybeNumber(&mut a.value.mass),
                    None => return Err(lacks(format!("body or axle {} with {what}", quote(part)))),
                }
            }
        }
    })
}

fn solver_slot<'f>(s: &'f mut Option<SolverFile>, field: &str, make: bool) -> Option<Slot<'f>> {
    let s = if make {
        s.get_or_insert_with(SolverFile::default)
    } else {
        s.as_mut()?
    };
    Some(match field {
        "method" => Slot::Name(&mut s.method),
        "rtol" => Slot::MaybeNumber(&mut s.rtol),
        "atol" => Slot::MaybeNumber(&mut s.atol),
        "rho_inf" => Slot::MaybeNumber(&mut s.rho_inf),
        _ => Slot::MaybeNumber(&mut s.accuracy),
    })
}

fn output_slot<'f>(o: &'f mut Option<OutputFile>, field: &str, make: bool) -> Option<Slot<'f>> {
    let o = if make {
        o.get_or_insert_with(OutputFile::default)
    } else {
        o.as_mut()?
    };
    Some(match field {
        "interval" => Slot::MaybeNumber(&mut o.interval),
        "probes" => Slot::Part(&mut o.probes),
        "shapes" => Slot::Part(&mut o.shapes),
        "magnify" => Slot::MaybeNumber(&mut o.magnify),
        _ => Slot::MaybeNumber(&mut o.acceleration_cutoff_hz),
    })
}

/// What an edit does, for its messages.
#[derive(Clone, Copy)]
enum Edit {
    Set,
    LeaveOut,
}

impl Edit {
    fn cannot(self, dotted: &str, why: Absent) -> Error {
        let verb = match self {
            Edit::Set => "set",
            Edit::LeaveOut => "left out",
        };
        Error::Input(format!("`{dotted}` cannot be {verb}: {}", why.0))
    }
}

impl SceneSpec {
    /// The places of `dotted` in the file, or why it has none: `wrong` says why a key that is
    /// not in [`KEYS`], or holds what `takes` refuses, cannot take the edit.
    fn places(
        &mut self,
        dotted: &str,
        edit: Edit,
        takes: impl Fn(Holds) -> bool,
        wrong: impl FnOnce() -> Error,
    ) -> Result<Vec<Slot<'_>>, Error> {
        let Some(found) = find(dotted).filter(|f| takes(f.key.holds)) else {
            // `disks[1].s0`, as Python and most formats index a list: say the key's spelling.
            let spelled = dotted.replace('[', ".").replace(']', "");
            if spelled != dotted && find(&spelled).is_some() {
                return Err(Error::Input(format!(
                    "`{dotted}` is spelled `{spelled}` (a list's item is a key by its index)"
                )));
            }
            return Err(wrong());
        };
        slots(&mut self.file, &found, matches!(edit, Edit::Set))
            .map_err(|why| edit.cannot(dotted, why))
    }

    /// Set the number at a dotted key of the scene format (`disk.omega0`, `track.beam.E`,
    /// `track.beam.elements`, `disks.2.s0`, …), whether or not the file gives it. The changed
    /// scene is not checked here: [`SceneSpec::check`] does that.
    pub fn set(&mut self, dotted: &str, value: f64) -> Result<(), Error> {
        let number = |h| matches!(h, Number | Whole);
        for slot in self.places(dotted, Edit::Set, number, || not_a_number(dotted))? {
            match slot {
                Slot::Number(s) => s.value = value,
                Slot::MaybeNumber(s) => put(s, value),
                Slot::Whole(s) => put(s, whole_number(value, dotted)?),
                Slot::Count(s) => put(s, count(value, dotted)?),
                _ => return Err(not_a_number(dotted)),
            }
        }
        Ok(())
    }

    /// Leave out an optional key, so that its default applies (`output.shapes`, `solver.rtol`,
    /// `track.beam.elements`, …).
    pub fn unset(&mut self, dotted: &str) -> Result<(), Error> {
        let required = || {
            Error::Input(format!(
                "`{dotted}` is not an optional key of the scene format"
            ))
        };
        for slot in self.places(dotted, Edit::LeaveOut, |_| true, required)? {
            match slot {
                Slot::Number(_) | Slot::RequiredName(_) | Slot::Hslm(_) => return Err(required()),
                Slot::MaybeNumber(s) => *s = None,
                Slot::Whole(s) => *s = None,
                Slot::Count(s) => *s = None,
                Slot::Name(s) => *s = None,
                Slot::Flag(s) => *s = None,
                Slot::Part(s) => s.leave_out(),
            }
        }
        Ok(())
    }

    /// Set the name at a dotted key of the scene format (`disk.coupling`, `solver.method`,
    /// `track.beam.quadrature`, …), whether or not the file gives it.
    pub fn set_name(&mut self, dotted: &str, value: &str) -> Result<(), Error> {
        let named = |h| matches!(h, Name | Flag);
        let not_a_name = || {
            let names: Vec<&str> = KEYS
                .iter()
                .filter(|k| named(k.holds))
                .map(|k| k.path)
                .collect();
            Error::Input(format!(
                "`{dotted}` does not take a name (a number key is swept as `{dotted}=FROM:TO:COUNT`); the keys that take names are {} (and disks.<k>.… as disk.…)",
                names.join(", ")
            ))
        };
        for slot in self.places(dotted, Edit::Set, named, not_a_name)? {
            match slot {
                Slot::Name(s) => put(s, value.to_string()),
                Slot::RequiredName(s) => s.value = value.to_string(),
                Slot::Flag(s) => put(s, flag(value, dotted)?),
                Slot::Hslm(t) => {
                    put(&mut t.hslm, value.to_string());
                    t.axles = None;
                    t.load = None;
                }
                _ => return Err(not_a_name()),
            }
        }
        Ok(())
    }
}

/// Set an optional value: where the file gives it, in its place (its line stays in messages).
fn put<T>(slot: &mut Option<Spanned<T>>, value: T) {
    match slot {
        Some(s) => s.value = value,
        None => *slot = Some(given(value)),
    }
}

/// `value` as a whole number, which it must be.
fn whole_number(value: f64, dotted: &str) -> Result<i64, Error> {
    if value.fract() != 0.0 || value.abs() > 1e15 {
        return Err(Error::Input(format!(
            "`{dotted}` takes a whole number (got {value})"
        )));
    }
    Ok(value as i64)
}

/// `value` as a whole number that is not negative (a seed), which it must be.
fn count(value: f64, dotted: &str) -> Result<u64, Error> {
    if value < 0.0 {
        return Err(Error::Input(format!(
            "`{dotted}` takes a whole number that is not negative (got {value})"
        )));
    }
    whole_number(value, dotted).map(|v| v as u64)
}

fn flag(value: &str, dotted: &str) -> Result<bool, Error> {
    match value {
        "true" => Ok(true),
        "false" => Ok(false),
        _ => Err(Error::Input(format!(
            "`{dotted}` is true or false (got {})",
            quote(value)
        ))),
    }
}

/// A value set rather than read: it has no line in the file.
fn given<T>(value: T) -> Spanned<T> {
    Spanned::new(value, Location::UNKNOWN, Location::UNKNOWN)
}

pub(super) fn not_a_number(dotted: &str) -> Error {
    Error::Input(format!(
        "`{dotted}` is not a number the scene format holds (keys are dotted paths such as disk.omega0, track.beam.E or solver.rtol)"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file holding every section an edit can reach (read, not checked: a curve and a beam,
    /// a road, a disk and a list of them).
    const EVERYTHING: &str = "
name: all
duration: 1.0
track:
  curve: {parabola: {k: 0.1}}
  beam:
    from: [0.0, 0.0]
    to: [10.0, 0.0]
    E: 1.0e9
    G: 1.0e9
    rho: 1000
    A: 1.0
    Av: 1.0
    I: 1.0
    supports: {from: pinned, to: roller}
  profile: {iso8608: {class: B}}
disk: {mass: 1.0, radius: 0.1}
disks: [{mass: 1.0, radius: 0.1}, {mass: 2.0, radius: 0.1}]
train: {hslm: A1, speed: 50.0}
vehicles:
  - name: car
    speed: 10.0
    bodies: [{name: body, mass: 100.0}]
    axles: [{name: wheel, x: 0.0}]
    springs: [{upper: body, lower: wheel, x: 0.0, k: 1.0e5}]
";

    fn everything() -> SceneSpec {
        SceneSpec {
            file: serde_saphyr::from_str(EVERYTHING).expect("the test file reads"),
            source: "test".into(),
            stem: "test".into(),
            lined: true,
        }
    }

    /// A row's path with its placeholders filled in as `EVERYTHING` names them.
    fn example(path: &str) -> String {
        path.replace("<name>", "car").replace("<i>", "0").replace(
            "<part>",
            if path.ends_with("inertia") {
                "body"
            } else {
                "wheel"
            },
        )
    }

    /// Every row of the table has a place in a file that holds its section, and an edit of the
    /// kind the row says reaches it: the table and the places agree.
    #[test]
    fn every_key_in_the_table_can_be_edited() {
        for k in KEYS {
            for dotted in [
                example(k.path),
                example(k.path).replacen("disk.", "disks.2.", 1),
            ] {
                let mut spec = everything();
                let done = match k.holds {
                    Number | Whole => spec.set(&dotted, 3.0),
                    Name => spec.set_name(&dotted, "x"),
                    Flag => spec.set_name(&dotted, "true"),
                    Part => spec.unset(&dotted),
                };
                assert!(
                    done.is_ok(),
                    "{dotted}: {:?}",
                    done.err().map(|e| e.to_string())
                );
            }
        }
    }

    /// What no row matches, and a placeholder left empty, is no key.
    #[test]
    fn keys_outside_the_table_are_refused() {
        for dotted in [
            "",
            "disk",
            "disk.",
            "disks.1",
            "disks..mass",
            "track.beam.E.x",
            "vehicles.car..mass",
        ] {
            assert!(find(dotted).is_none(), "{dotted}");
        }
        let mut spec = everything();
        assert!(spec.set("train.hslm", 1.0).is_err());
        assert!(spec.set_name("track.beam.E", "steel").is_err());
        assert!(spec.unset("track.beam.E").is_err());
        assert!(spec
            .set("disks.3.mass", 1.0)
            .unwrap_err()
            .to_string()
            .contains("the 2 disks"));
        // An index in brackets, as Python writes it, is told the key's spelling.
        let bracketed = spec.set("disks[1].mass", 1.0).unwrap_err().to_string();
        assert!(bracketed.contains("`disks.1.mass`"), "{bracketed}");
        assert!(spec
            .set("track[1].E", 1.0)
            .unwrap_err()
            .to_string()
            .contains("dotted paths"));
    }
}

//! The checker every section reports through ("FILE line N: `KEY` ..."), its bounds, and the
//! scene's name.

use super::*;

/// Finest `solver.accuracy`: with a switched load its rtol is a ten-thousandth of it, 1e-11.
pub(super) const MIN_ACCURACY: f64 = 1e-7;

/// Rows of history.csv a run may write.
pub(super) const MAX_ROWS: f64 = 1e6;

/// Probes and shape times a beam scene may name: each probe is four columns of history.csv at
/// every row and each shape time a curve of `shapes.svg`; 40 000 probes wrote 360 MB and held
/// 700 MB, 200 000 shape times held 1.3 GB, from scenes of a few megabytes.
pub(super) const MAX_PROBES: usize = 1000;
pub(super) const MAX_SHAPES: usize = 1000;

/// Mesh nodes a beam may have (three unknowns each): its sparse factor then takes some
/// hundred megabytes, and one solve about a second.
pub(super) const MAX_NODES: f64 = 100_001.0;

/// Intermediate bearings must sit at nodes of a uniform mesh of at most this many elements.
pub(super) const MAX_SPANS: usize = 1000;

/// The speed of light (m/s): what a vehicle, a train or a disk moves faster than is not a
/// scene the model describes, and past it the squares of speeds in its energies and forces
/// head for overflow (a vehicle at 1e308 m/s summed its energy to NaN).
const SPEED_OF_LIGHT: f64 = 299_792_458.0;

/// Reports problems as "FILE line N: KEY ...".
pub(super) struct Checker<'a> {
    pub(super) file: &'a str,
    /// Whether the text's lines are ones its author can look up: not where a program wrote the
    /// text from data (a Python dict), whose keys alone say where.
    pub(super) lined: bool,
}

impl Checker<'_> {
    /// "FILE line N", or "FILE" for line 0 (a value set rather than read) or a text without
    /// lines to name.
    pub(super) fn place(&self, line: u64) -> String {
        if line == 0 || !self.lined {
            self.file.to_string()
        } else {
            format!("{} line {line}", self.file)
        }
    }

    pub(super) fn err<T>(
        &self,
        line: u64,
        key: &str,
        msg: impl std::fmt::Display,
    ) -> Result<T, Error> {
        Err(Error::Input(format!("{}: `{key}` {msg}", self.place(line))))
    }

    pub(super) fn finite(&self, v: &Spanned<f64>, key: &str) -> Result<f64, Error> {
        if !v.value.is_finite() {
            return self.err(
                v.referenced.line(),
                key,
                format!("must be a finite number, not {}", v.value),
            );
        }
        Ok(v.value)
    }

    pub(super) fn positive(&self, v: &Spanned<f64>, key: &str) -> Result<f64, Error> {
        let x = self.finite(v, key)?;
        if x <= 0.0 {
            return self.err(
                v.referenced.line(),
                key,
                format!("must be positive (got {x})"),
            );
        }
        Ok(x)
    }

    /// A speed `v` (m/s) that `key` on `line` sets: slower than light.
    pub(super) fn speed(&self, line: u64, key: &str, v: f64) -> Result<f64, Error> {
        if v.abs() <= SPEED_OF_LIGHT {
            return Ok(v);
        }
        self.err(
            line,
            key,
            format!(
                "sets a speed of {:e} m/s, faster than light ({SPEED_OF_LIGHT:e} m/s)",
                v.abs()
            ),
        )
    }

    /// A length of the section or the contact (m): positive, at least a millionth of the beam's
    /// length `length` and at most all of it; `short` says what a shorter one would be, and
    /// `long` how a longer one exceeds the beam and why that cannot be.
    pub(super) fn part_of_length(
        &self,
        v: &Spanned<f64>,
        key: &str,
        length: f64,
        short: &str,
        long: (&str, &str),
    ) -> Result<f64, Error> {
        let x = self.positive(v, key)?;
        let line = v.referenced.line();
        if x < MIN_PATCH_PER_LENGTH * length {
            return self.err(line, key, format!("= {x:e} m is below a millionth of the beam's length (L = {length:e} m): {short}"));
        }
        if x > length {
            return self.err(
                line,
                key,
                format!("= {x:e} m {} (L = {length:e} m): {}", long.0, long.1),
            );
        }
        Ok(x)
    }

    /// A quantity derived from the scene's values (a length, a stiffness, an inertia) that the
    /// model divides by or squares: it must be a normal positive double, neither overflowed
    /// to infinity nor underflowed towards zero by extreme inputs.
    pub(super) fn derived(&self, line: u64, key: &str, what: &str, v: f64) -> Result<f64, Error> {
        if v.is_normal() && v > 0.0 {
            return Ok(v);
        }
        self.err(
            line,
            key,
            format!(
                "makes {what} {}, which is not a finite positive number a double holds; the values are too extreme",
                if v.is_finite() { format!("= {v:e}") } else { "infinite".into() }
            ),
        )
    }

    /// The disk of a scene, its mass, radius and what the model derives from them.
    pub(super) fn disk(&self, d: &DiskFile, gravity: f64, at: &str) -> Result<Disk, Error> {
        let disk = Disk {
            mass: self.positive(&d.mass, &format!("{at}.mass"))?,
            radius: self.positive(&d.radius, &format!("{at}.radius"))?,
        };
        let line = d.radius.referenced.line();
        self.derived(
            line,
            &format!("{at}.radius"),
            "the disk's moment of inertia C = m a²/2",
            disk.inertia(),
        )?;
        self.derived(
            line,
            &format!("{at}.radius"),
            "the disk's rolling mass m + C/a²",
            disk.rolling_mass(),
        )?;
        if gravity != 0.0 {
            self.derived(
                d.mass.referenced.line(),
                &format!("{at}.mass"),
                "the disk's weight m |g|",
                disk.mass * gravity.abs(),
            )?;
        }
        Ok(disk)
    }

    pub(super) fn pair(&self, v: &Spanned<[f64; 2]>, key: &str) -> Result<[f64; 2], Error> {
        if v.value.iter().any(|x| !x.is_finite()) {
            return self.err(
                v.referenced.line(),
                key,
                format!("must hold finite numbers, not {:?}", v.value),
            );
        }
        Ok(v.value)
    }
}

/// Why a user's name cannot name a folder or a column, if it cannot: what every such name
/// must be (not empty, no control character, at most `max` characters).
pub(super) fn name_flaw(name: &str, max: usize) -> Option<String> {
    if name.trim().is_empty() {
        Some("is empty".into())
    } else if name.chars().any(char::is_control) {
        Some("holds a control character".into())
    } else if name.chars().count() > max {
        Some(format!("is longer than {max} characters"))
    } else {
        None
    }
}

/// Longest scene name: it names the output folder.
pub(super) const MAX_NAME_CHARS: usize = 100;

/// The scene's name, which names its default output folder `out/<name>`: so it must be a
/// plain folder name, never a path that leads elsewhere. Refused rather than rewritten, so
/// that the folder a run writes is always the name the user gave.
pub(super) fn scene_name(
    c: &Checker,
    given: Option<&Spanned<String>>,
    stem: &str,
) -> Result<String, Error> {
    let (name, line, key) = match given {
        Some(n) => (n.value.as_str(), n.referenced.line(), "name"),
        None => (stem, 0, "name (the file's stem, as the scene gives none)"),
    };
    let why = name_flaw(name, MAX_NAME_CHARS).or_else(|| {
        if name == "." || name == ".." {
            Some("would name a folder outside out/".into())
        } else if name.contains(['/', '\\']) {
            Some("holds a path separator; a name names one folder in out/".into())
        } else {
            None
        }
    });
    match why {
        Some(why) => c.err(line, key, format!("= {} {why}", quote(name))),
        None => Ok(name.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use crate::scene::SceneSpec;

    const SCENE: &str = "duration: 1.0\ntrack:\n  curve:\n    parabola: {k: 1.0}\ndisk:\n  mass: 1.0\n  radius: 0.1\n  s0: -1.0\n";

    /// A text a program wrote (a Python dict as JSON) is placed by its keys alone, both where
    /// the reader refuses it and where the checker does; a file's messages name the line.
    #[test]
    fn a_text_without_lines_is_placed_by_its_keys() {
        let message = |text: &str, lined: bool| {
            let read = if lined {
                SceneSpec::parse
            } else {
                SceneSpec::parse_unlined
            };
            read(text, "src", "s").err().expect("refused").to_string()
        };
        let unknown = format!("{SCENE}colour: red\n");
        let negative = SCENE.replace("mass: 1.0", "mass: -1.0");
        for (text, key, line) in [(&unknown, "`colour`", 9), (&negative, "`disk.mass`", 6)] {
            let lined = message(text, true);
            assert!(
                lined.starts_with(&format!("src line {line}: {key}")),
                "{lined}"
            );
            let unlined = message(text, false);
            assert!(unlined.starts_with(&format!("src: {key}")), "{unlined}");
        }
    }
}

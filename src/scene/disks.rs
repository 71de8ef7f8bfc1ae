//! The disks that ride a beam track, `disk:` or `disks: [...]`: each checked against the beam
//! it rolls on (its coupling, where it starts, what it does where it loses contact).

use super::*;

/// The most disks a scene may put on one beam.
pub(super) const MAX_DISKS: usize = 100;

/// The disks of a beam scene, `disk:` or `disks: [...]`, each checked against the beam it
/// rolls on.
pub(super) fn disks_on_beam(
    c: &Checker,
    raw: &SceneFile,
    beam: &BeamSpec,
    length: f64,
    gravity: f64,
) -> Result<Vec<DiskOnBeamSpec>, Error> {
    let beside = raw.vehicles.is_some();
    let list =
        match (&raw.disk, &raw.disks) {
            (None, None) => return Ok(Vec::new()),
            (Some(d), None) => {
                return Ok(vec![disk_on_beam(
                    c,
                    d,
                    "disk",
                    beam,
                    (length, gravity),
                    beside,
                )?])
            }
            (Some(d), Some(_)) => return c.err(
                d.referenced.line(),
                "disk",
                "and `disks` are both given: write one disk as `disk`, several as the list `disks`",
            ),
            (None, Some(list)) => list,
        };
    if list.value.is_empty() || list.value.len() > MAX_DISKS {
        return c.err(
            list.referenced.line(),
            "disks",
            format!("must list 1 to {MAX_DISKS} disks"),
        );
    }
    let disks = list
        .value
        .iter()
        .enumerate()
        .map(|(k, d)| {
            let at = format!("disks[{}]", k + 1);
            disk_on_beam(c, d, &at, beam, (length, gravity), beside)
        })
        .collect::<Result<Vec<_>, _>>()?;
    if disks.len() > 1 {
        if let Some(k) = disks.iter().position(|d| d.coupling == Coupling::Thesis) {
            let line = list.value[k].referenced.line();
            return c.err(line, &format!("disks[{}].coupling", k + 1), "is thesis: the thesis coupling transcribes the published system, which carries one disk; give the disks the consistent coupling, or ride this one alone");
        }
    }
    Ok(disks)
}

/// A disk of a beam scene (`at` names it in messages: `disk` or `disks[k]`), checked
/// against the beam it rolls on (of `length`, under `gravity`), `beside` vehicles or not.
pub(super) fn disk_on_beam(
    c: &Checker,
    file: &Spanned<DiskFile>,
    at: &str,
    beam: &BeamSpec,
    (length, gravity): (f64, f64),
    beside: bool,
) -> Result<DiskOnBeamSpec, Error> {
    let d = &file.value;
    let disk = c.disk(d, gravity, at)?;
    if let Some(f) = &d.formulation {
        return c.err(
            f.referenced.line(),
            &format!("{at}.formulation"),
            "applies to rigid curves only; on a beam choose `coupling`",
        );
    }
    let coupling = coupling(c, d, at)?;
    let contact_loss = loss_on_beam(c, file, at, coupling, beside)?;
    let (s0, omega0) = start_on_beam(c, file, at, disk.radius, coupling, length)?;
    let mu = match &d.mu {
        Some(m) => Some(c.positive(m, &format!("{at}.mu"))?),
        None => None,
    };
    let patch = match &d.patch {
        Some(p) => c.part_of_length(
            p,
            &format!("{at}.patch"),
            length,
            "a contact that short is a point, on which the disk's contact force is not defined (see REPORT.md, \"What depends on the patch\")",
            (
                "is wider than the beam",
                "the patch is the half-width of the contact, about the section's depth",
            ),
        )?,
        None => {
            patch::physical_half_width(&beam.section, beam.depth, disk.radius, disk.mass * gravity)
                .min(length)
        }
    };
    Ok(DiskOnBeamSpec {
        disk,
        s0,
        omega0,
        coupling,
        mu,
        gravity,
        patch,
        contact_loss,
    })
}

/// How disk `d` (named `at`) rides on the beam: the consistent coupling where the file says
/// nothing.
fn coupling(c: &Checker, d: &DiskFile, at: &str) -> Result<Coupling, Error> {
    let Some(cp) = &d.coupling else {
        return Ok(Coupling::Consistent);
    };
    Coupling::from_name(&cp.value).map_or_else(
        || {
            c.err(
                cp.referenced.line(),
                &format!("{at}.coupling"),
                format!(
                    "is {}; use one of {}",
                    quote(&cp.value),
                    Coupling::ALL.map(|k| k.name()).join(", ")
                ),
            )
        },
        Ok,
    )
}

/// Where disk `file` (named `at`) starts on a beam of `length`, and its spin: on the beam,
/// moving where its coupling needs it to, and not off or at rest on an end.
fn start_on_beam(
    c: &Checker,
    file: &Spanned<DiskFile>,
    at: &str,
    radius: f64,
    coupling: Coupling,
    length: f64,
) -> Result<(f64, f64), Error> {
    let d = &file.value;
    let s0_line =
        d.s0.as_ref()
            .map_or(file.referenced.line(), |s| s.referenced.line());
    let s0 = match &d.s0 {
        Some(s) => c.finite(s, &format!("{at}.s0"))?,
        None => 0.0,
    };
    if !(0.0..=length).contains(&s0) {
        return c.err(
            s0_line,
            &format!("{at}.s0"),
            format!("= {s0} is off the beam, which runs over x in [0, {length}]"),
        );
    }
    let omega_line = d
        .omega0
        .as_ref()
        .map_or(file.referenced.line(), |s| s.referenced.line());
    let omega0 = match &d.omega0 {
        Some(w) => c.finite(w, &format!("{at}.omega0"))?,
        None => 0.0,
    };
    if !coupling.rolls() && omega0 == 0.0 {
        return c.err(
            omega_line,
            &format!("{at}.omega0"),
            format!(
                "is 0: a {} travels at the constant speed −radius × omega0, so it needs a non-zero omega0",
                coupling.name()
            ),
        );
    }
    // Rolling off the end it starts on leaves nothing to simulate; a disk resting exactly on
    // an end support with no speed has nowhere to go but off or nowhere.
    let v0 = c.speed(omega_line, &format!("{at}.omega0"), -radius * omega0)?;
    if (s0 == 0.0 && v0 < 0.0) || (s0 == length && v0 > 0.0) {
        return c.err(
            omega_line,
            &format!("{at}.omega0"),
            format!("= {omega0} rolls the disk off the end of the beam it starts on (s0 = {s0}); Ω < 0 rolls towards +x"),
        );
    }
    if (s0 == 0.0 || s0 == length) && v0 == 0.0 {
        return c.err(
            s0_line,
            &format!("{at}.s0"),
            format!("= {s0} puts the disk at rest on the end support, where it would load only the support and never move onto the beam; give it a speed (omega0) or start it inside"),
        );
    }
    Ok((s0, omega0))
}

/// What happens where disk `file` (named `at`) on a beam loses contact, as its coupling
/// allows: `fly` only where the disk can leave the beam, only with the consistent coupling,
/// and not `beside` vehicles; left out, it flies with the consistent coupling alone and stops
/// otherwise.
fn loss_on_beam(
    c: &Checker,
    file: &Spanned<DiskFile>,
    at: &str,
    coupling: Coupling,
    beside: bool,
) -> Result<ContactLoss, Error> {
    let d = &file.value;
    let line = d
        .contact_loss
        .as_ref()
        .map(|k| k.referenced.line())
        .or(d.restitution.as_ref().map(|e| e.referenced.line()))
        .unwrap_or(file.referenced.line());
    let key = if d.contact_loss.is_some() {
        format!("{at}.contact_loss")
    } else {
        format!("{at}.restitution")
    };
    Ok(match (contact_loss(c, d, at)?, coupling) {
        (Some(_), Coupling::MovingForce | Coupling::MovingMass) => {
            return c.err(
                line,
                &key,
                format!(
                    "applies to a disk that can leave the beam; the {} coupling's load is held to the beam and never leaves it",
                    coupling.name()
                ),
            );
        }
        (Some(ContactLoss::Fly { .. }), Coupling::Thesis) => {
            return c.err(
                line,
                &key,
                "asks the disk to fly off the beam, which only the consistent coupling does: the thesis coupling rolls the disk on the axis as if it were frozen, which gives a landing no meaning; write `contact_loss: stop` or use `coupling: consistent`",
            );
        }
        (Some(ContactLoss::Fly { .. }), _) if beside => {
            return c.err(
                line,
                &key,
                "asks the disk to fly off the beam, which it does not beside vehicles (their wheels and the disk share one system, which a flight would split); write `contact_loss: stop` or leave it out: the run stops where the disk loses contact",
            );
        }
        (Some(loss), _) => loss,
        (None, Coupling::Consistent) if !beside => ContactLoss::Fly { restitution: 0.0 },
        (None, _) => ContactLoss::Stop,
    })
}

//! A beam track: its section, supports, mesh, damping, model, start, loads and probes; the disks
//! that ride it are `disks.rs`.

use super::*;

/// Keys that belong to beam tracks, refused on a rigid curve with the reason.
pub(super) fn refuse_beam_keys(c: &Checker, raw: &SceneFile) -> Result<(), Error> {
    if let Some(t) = &raw.train {
        return c.err(
            t.referenced.line(),
            "train",
            "crosses beam tracks only; on a rigid curve give a disk",
        );
    }
    if let Some(v) = &raw.vehicles {
        return c.err(
            v.referenced.line(),
            "vehicles",
            "ride beam tracks only; on a rigid curve give a disk",
        );
    }
    if let Some(d) = &raw.disks {
        return c.err(
            d.referenced.line(),
            "disks",
            "ride beam tracks only; a rigid curve carries one disk, as `disk`",
        );
    }
    if let Some(p) = &raw.track.value.profile {
        return c.err(
            p.referenced.line(),
            "track.profile",
            "is the running surface of a beam track's vehicles; a rigid curve has none",
        );
    }
    if let Some(loads) = &raw.loads {
        return c.err(
            loads.referenced.line(),
            "loads",
            "apply to beam tracks only; a rigid curve carries no loads",
        );
    }
    if let Some(rho) = raw.solver.as_ref().and_then(|s| s.rho_inf.as_ref()) {
        return c.err(
            rho.referenced.line(),
            "solver.rho_inf",
            "applies to genalpha on beam tracks only",
        );
    }
    if let Some(a) = raw.solver.as_ref().and_then(|s| s.accuracy.as_ref()) {
        return c.err(
            a.referenced.line(),
            "solver.accuracy",
            "chooses a beam's mesh and tolerances; on a rigid curve set solver.rtol",
        );
    }
    if let Some(o) = &raw.output {
        let beam_only = [
            o.probes.as_ref().map(|v| v.referenced.line()),
            o.shapes.as_ref().map(|v| v.referenced.line()),
            o.magnify.as_ref().map(|v| v.referenced.line()),
            o.acceleration_cutoff_hz
                .as_ref()
                .map(|v| v.referenced.line()),
        ];
        for (line, key) in beam_only.iter().zip([
            "output.probes",
            "output.shapes",
            "output.magnify",
            "output.acceleration_cutoff_hz",
        ]) {
            if let Some(line) = line {
                return c.err(*line, key, "applies to beam tracks only");
            }
        }
    }
    Ok(())
}

pub(super) fn beam_scene(
    c: &Checker,
    raw: &SceneFile,
    file: &Spanned<BeamFile>,
    duration: f64,
    gravity: f64,
) -> Result<(BeamScene, MeshAsGiven), Error> {
    let b = &file.value;
    let (mut beam, length, multiple, model_given) = beam_spec(c, b)?;
    beam.damping = damping(c, b)?;
    if b.self_weight.as_ref().is_some_and(|w| w.value) {
        beam.self_weight = Some(gravity);
    }
    let start = beam_start(c, b, &beam)?;
    let loads = point_loads(c, raw, length)?;
    let disks = disks_on_beam(c, raw, &beam, length, gravity)?;
    let train = match &raw.train {
        None => None,
        Some(t) => Some(train(c, t, &beam, gravity)?),
    };
    let vehicles = vehicles(c, raw, &beam, gravity)?;
    let profile = profile(c, raw, &raw.track.value)?;
    wheel_breakpoints(c, raw, &vehicles, &profile)?;
    disk_wheels_on_the_road(c, raw, &vehicles, &profile)?;
    let riders = (train.as_ref(), vehicles.as_slice(), disks.as_slice());
    let duration = run_length(c, raw, duration, (&beam, length), riders)?;
    let (probes, shapes, magnify) = outputs(c, raw, length, duration)?;
    let rho_inf = rho_inf(c, raw)?;
    let accuracy = accuracy(c, raw)?;
    let given = MeshAsGiven {
        elements: b.elements.as_ref().map(|_| beam.elements),
        order: b.order.as_ref().map(|_| beam.order),
        multiple,
        model: model_given,
        duration,
    };
    let mut scene = BeamScene {
        beam,
        start,
        disks,
        train,
        vehicles,
        profile,
        loads,
        probes,
        shapes,
        magnify,
        rho_inf,
        rho_inf_chosen: None,
        accuracy,
        discretisation: None,
        model_choice: None,
        static_gap: None,
        plan_warnings: Vec::new(),
        left_out_share: None,
        acceleration_cutoff_hz: match raw
            .output
            .as_ref()
            .and_then(|o| o.acceleration_cutoff_hz.as_ref())
        {
            None => None,
            Some(f) => Some(c.positive(f, "output.acceleration_cutoff_hz")?),
        },
        response: None,
        response_turned: false,
        passage: None,
    };
    scene.probe_mid_when_none_given(length);
    Ok((scene, given))
}

/// A train, the vehicles and the disks on the beam.
type Riders<'r> = (
    Option<&'r Train>,
    &'r [crate::vehicle::Vehicle],
    &'r [DiskOnBeamSpec],
);

/// The run's length: with a train or vehicles `duration` is the free vibration after the
/// last axle has left (or the last vehicle has stopped), and beside vehicles after each disk
/// has crossed at its starting speed.
fn run_length(
    c: &Checker,
    raw: &SceneFile,
    duration: f64,
    (beam, length): (&BeamSpec, f64),
    (train, vehicles, disks): Riders,
) -> Result<f64, Error> {
    let disks_cross = || {
        let v0 = |d: &DiskOnBeamSpec| d.v0();
        (disks.iter())
            .filter(|d| v0(d) != 0.0)
            .map(|d| (if v0(d) > 0.0 { length - d.s0 } else { d.s0 }) / v0(d).abs())
            .fold(0.0, f64::max)
    };
    let crossing = train.map_or(0.0, |t| t.gone(length)).max(
        vehicles
            .iter()
            .map(|v| vehicle_gone(v, length, patch::dispersed_half_width(beam.depth)))
            .fold(0.0, f64::max),
    );
    let crossing = if vehicles.is_empty() {
        crossing
    } else {
        crossing.max(disks_cross())
    };
    match (&raw.train, &raw.vehicles) {
        (None, None) => Ok(duration),
        (Some(file), _) => c.derived(
            file.value.speed.referenced.line(),
            "train.speed",
            "the run's length, the crossing plus `duration`,",
            crossing + duration,
        ),
        (None, Some(file)) => c.derived(
            file.referenced.line(),
            "vehicles",
            "the run's length, the crossing plus `duration`,",
            crossing + duration,
        ),
    }
}

/// Generalized-α's ρ∞ as the file gives it, in [0, 1] (1 where it does not).
fn rho_inf(c: &Checker, raw: &SceneFile) -> Result<f64, Error> {
    let Some(r) = raw.solver.as_ref().and_then(|s| s.rho_inf.as_ref()) else {
        return Ok(1.0);
    };
    let v = c.finite(r, "solver.rho_inf")?;
    if !(0.0..=1.0).contains(&v) {
        return c.err(
            r.referenced.line(),
            "solver.rho_inf",
            format!("= {v} must lie in [0, 1]"),
        );
    }
    Ok(v)
}

/// The relative accuracy the run is planned for.
fn accuracy(c: &Checker, raw: &SceneFile) -> Result<f64, Error> {
    let Some(a) = raw.solver.as_ref().and_then(|s| s.accuracy.as_ref()) else {
        return Ok(DEFAULT_ACCURACY);
    };
    let v = c.positive(a, "solver.accuracy")?;
    if v >= 0.5 {
        return c.err(
            a.referenced.line(),
            "solver.accuracy",
            format!("= {v} is a relative error and must be below 0.5"),
        );
    }
    if v < MIN_ACCURACY {
        return c.err(
            a.referenced.line(),
            "solver.accuracy",
            format!("= {v:e} asks for more than the beam's equations hold: the tolerances it implies (down to accuracy/10000) would pass the round-off of a step; use at least {MIN_ACCURACY:e}"),
        );
    }
    Ok(v)
}

/// What of the mesh and model a beam scene gives itself (the plan chooses the rest).
pub struct MeshAsGiven {
    pub elements: Option<usize>,
    pub order: Option<usize>,
    /// Element counts are kept to multiples of this, which puts a node at each bearing.
    pub multiple: usize,
    /// The scene names its beam model.
    pub model: bool,
    /// The run's duration: the scene's, or with a train the crossing plus the scene's.
    pub duration: f64,
}

/// The beam as the file gives it: its axis, section, supports and mesh (the element count 0
/// where the file leaves it to the plan); its length; and the multiple element counts are kept
/// to, which puts a node at each bearing.
pub(super) fn beam_spec(c: &Checker, b: &BeamFile) -> Result<(BeamSpec, f64, usize, bool), Error> {
    let from = c.pair(&b.from, "track.beam.from")?;
    let to = c.pair(&b.to, "track.beam.to")?;
    let length = (to[0] - from[0]).hypot(to[1] - from[1]);
    if length == 0.0 {
        return c.err(
            b.to.referenced.line(),
            "track.beam.to",
            "equals `from`: the beam has zero length",
        );
    }
    c.derived(
        b.to.referenced.line(),
        "track.beam.to",
        "the beam's length",
        length,
    )?;
    let section = section(c, b)?;
    let (supports, bearings, multiple) = supports(c, b, length)?;
    let (elements, order, quadrature) = mesh(c, b, multiple)?;
    let depth = depth(c, b, &section, length)?;
    let unknowns = (elements > 0).then(|| {
        let held: usize = supports.iter().map(|s| s.held_components().len()).sum();
        3 * (elements * order + 1) - held - bearings.len()
    });
    let model = beam_model(c, b, unknowns)?;
    let beam = BeamSpec {
        from,
        to,
        section,
        depth,
        supports,
        bearings,
        elements,
        order,
        quadrature,
        model: model.unwrap_or(BeamModel::Exact),
        damping: None,
        self_weight: None,
    };
    Ok((beam, length, multiple, model.is_some()))
}

/// The section's stiffnesses and inertias from E, G, ρ, A, Av and I, each finite.
fn section(c: &Checker, b: &BeamFile) -> Result<Section, Error> {
    let e = c.positive(&b.E, "track.beam.E")?;
    let g = c.positive(&b.G, "track.beam.G")?;
    let rho = c.positive(&b.rho, "track.beam.rho")?;
    let a = c.positive(&b.A, "track.beam.A")?;
    let av = c.positive(&b.Av, "track.beam.Av")?;
    let i = c.positive(&b.I, "track.beam.I")?;
    let section = Section {
        ea: e * a,
        gav: g * av,
        ei: e * i,
        rho_a: rho * a,
        rho_i: rho * i,
    };
    for (v, given, key, what) in [
        (section.ea, &b.E, "track.beam.E", "the axial stiffness E A"),
        (
            section.gav,
            &b.G,
            "track.beam.G",
            "the shear stiffness G Av",
        ),
        (
            section.ei,
            &b.I,
            "track.beam.I",
            "the bending stiffness E I",
        ),
        (
            section.rho_a,
            &b.rho,
            "track.beam.rho",
            "the mass per length ρ A",
        ),
        (
            section.rho_i,
            &b.rho,
            "track.beam.rho",
            "the rotary inertia per length ρ I",
        ),
        (
            section.ea / section.rho_a,
            &b.rho,
            "track.beam.rho",
            "the squared axial wave speed E/ρ",
        ),
    ] {
        c.derived(given.referenced.line(), key, what, v)?;
    }
    Ok(section)
}

/// The section's depth: the file's, or a rectangle's of the section's A and I.
fn depth(c: &Checker, b: &BeamFile, section: &Section, length: f64) -> Result<f64, Error> {
    match &b.depth {
        Some(d) => c.part_of_length(
            d,
            "track.beam.depth",
            length,
            "the depth sets the contact patch, which would be a point",
            ("is deeper than the beam is long", "that is not a beam"),
        ),
        None => {
            let depth = patch::rectangular_depth(section);
            if !(depth <= length) {
                return c.err(
                    b.I.referenced.line(),
                    "track.beam.I",
                    format!(
                        "with A makes the rectangle √(12 I/A) = {} m deep, deeper than the beam is long: that is not a beam (give `track.beam.depth` if the section is not a rectangle)",
                        crate::error::short_numbers(&format!("{depth:e}"))
                    ),
                );
            }
            Ok(depth)
        }
    }
}

/// Rayleigh damping as the file gives it: a ratio at two modes, or α and β.
pub(super) fn damping(c: &Checker, b: &BeamFile) -> Result<Option<DampingSpec>, Error> {
    let Some(d) = &b.damping else {
        return Ok(None);
    };
    let line = d.referenced.line();
    let d = &d.value;
    let non_negative = |v: &Spanned<f64>, key: &str| -> Result<f64, Error> {
        let x = c.finite(v, key)?;
        if x < 0.0 {
            return c.err(
                v.referenced.line(),
                key,
                format!("= {x} must not be negative"),
            );
        }
        Ok(x)
    };
    match (&d.ratio, d.alpha.is_some() || d.beta.is_some()) {
        (Some(r), true) => c.err(
            r.referenced.line(),
            "track.beam.damping",
            "gives a ratio and alpha or beta: give {ratio, modes} or {alpha, beta}, not both",
        ),
        (None, false) => c.err(
            line,
            "track.beam.damping",
            "is empty: give {ratio: ζ, modes: [i, j]} or {alpha: α, beta: β}",
        ),
        (Some(r), false) => {
            let zeta = c.finite(r, "track.beam.damping.ratio")?;
            if !(0.0..1.0).contains(&zeta) {
                return c.err(
                    r.referenced.line(),
                    "track.beam.damping.ratio",
                    format!(
                        "= {zeta} must lie in [0, 1): {}",
                        if zeta < 0.0 {
                            "a negative ratio would feed the vibration energy instead of taking it"
                        } else {
                            "a ratio of 1 or more is no longer a vibration"
                        }
                    ),
                );
            }
            let modes = match &d.modes {
                None => [1, 2],
                Some(m) => match m.value.as_slice() {
                    &[i, j] if i >= 1 && j >= 1 && i != j && i.max(j) <= MAX_MODES as i64 => {
                        [i as usize, j as usize]
                    }
                    _ => {
                        return c.err(
                            m.referenced.line(),
                            "track.beam.damping.modes",
                            format!(
                            "must be two distinct mode numbers from 1 to {MAX_MODES}, e.g. [1, 2]"
                        ),
                        )
                    }
                },
            };
            Ok(Some(DampingSpec::Ratio { zeta, modes }))
        }
        (None, true) => {
            if let Some(m) = &d.modes {
                return c.err(
                    m.referenced.line(),
                    "track.beam.damping.modes",
                    "anchors a ratio; alpha and beta need no modes",
                );
            }
            let alpha = d
                .alpha
                .as_ref()
                .map_or(Ok(0.0), |v| non_negative(v, "track.beam.damping.alpha"))?;
            let beta = d
                .beta
                .as_ref()
                .map_or(Ok(0.0), |v| non_negative(v, "track.beam.damping.beta"))?;
            Ok(Some(DampingSpec::Rayleigh { alpha, beta }))
        }
    }
}

/// The beam model as the file gives it, `None` where it leaves the choice to the plan; a
/// modal beam whose `modes` are left out has 0 until the plan chooses them. `unknowns`: the
/// mesh's, where the file gives the element count.
pub(super) fn beam_model(
    c: &Checker,
    b: &BeamFile,
    unknowns: Option<usize>,
) -> Result<Option<BeamModel>, Error> {
    let model = match &b.model {
        None => None,
        Some(m) => Some(match m.value.as_str() {
            "exact" => BeamModel::Exact,
            "linear" => BeamModel::Linear,
            "modal" => BeamModel::Modal { modes: 0 },
            other => {
                return c.err(
                    m.referenced.line(),
                    "track.beam.model",
                    format!("is {}; use exact, linear or modal", quote(other)),
                )
            }
        }),
    };
    let Some(modes) = &b.modes else {
        return Ok(model);
    };
    let line = modes.referenced.line();
    if let Some(m @ (BeamModel::Exact | BeamModel::Linear)) = model {
        return c.err(
            line,
            "track.beam.modes",
            format!(
                "counts the modes of a modal beam; `model: {}` keeps every unknown of the mesh (use `model: modal`, or leave `modes` out)",
                m.name()
            ),
        );
    }
    if modes.value < 1 {
        return c.err(
            line,
            "track.beam.modes",
            format!("must be at least 1 (got {})", modes.value),
        );
    }
    if let Some(n) = unknowns {
        if modes.value as u64 > n as u64 {
            return c.err(
                line,
                "track.beam.modes",
                format!(
                    "= {} is more than the mesh has: its {n} unknowns have {n} modes",
                    modes.value
                ),
            );
        }
    }
    if modes.value > MAX_MODES as i64 {
        return c.err(
            line,
            "track.beam.modes",
            format!(
                "= {} is more than a modal beam keeps ({MAX_MODES}); use `model: linear` for the whole mesh",
                modes.value
            ),
        );
    }
    Ok(Some(BeamModel::Modal {
        modes: modes.value as usize,
    }))
}

/// The end supports, the intermediate bearings (sorted), and the multiple of elements that
/// puts a node at each.
pub(super) fn supports(
    c: &Checker,
    b: &BeamFile,
    length: f64,
) -> Result<([Support; 2], Vec<f64>, usize), Error> {
    let support = |v: &Spanned<String>, key: &str| {
        Support::from_name(&v.value).map_or_else(
            || {
                c.err(
                    v.referenced.line(),
                    key,
                    format!(
                        "is {}; use clamped, pinned, roller or free",
                        quote(&v.value)
                    ),
                )
            },
            Ok,
        )
    };
    let supports = [
        support(&b.supports.value.from, "track.beam.supports.from")?,
        support(&b.supports.value.to, "track.beam.supports.to")?,
    ];
    let mut bearings = Vec::new();
    for x in b
        .supports
        .value
        .intermediate
        .iter()
        .flat_map(|v| v.value.iter())
    {
        let key = "track.beam.supports.intermediate";
        let v = c.finite(x, key)?;
        // Within the tolerance two bearings are one, a bearing and an end are one too: the
        // mesh's node there is the end's.
        let near = 1e-9 * length;
        if !(v > near && v < length - near) {
            return c.err(
                x.referenced.line(),
                key,
                format!("has x = {v}, which is not strictly inside the beam (0, {length}) by more than {near:e} m"),
            );
        }
        if bearings.iter().any(|&b: &f64| (b - v).abs() <= near) {
            return c.err(x.referenced.line(), key, format!("names x = {v} twice"));
        }
        bearings.push(v);
    }
    bearings.sort_by(f64::total_cmp);
    let fractions: Vec<f64> = bearings.iter().map(|x| x / length).collect();
    let Some(multiple) = mesh_multiple(&fractions, MAX_SPANS) else {
        // The first bearing that no mesh fits together with those before it is the one named:
        // a list of hundreds would not be a sentence.
        let k = (1..=fractions.len())
            .find(|&k| mesh_multiple(&fractions[..k], MAX_SPANS).is_none())
            .unwrap_or(fractions.len());
        let before = match k - 1 {
            0 => String::new(),
            1 => format!(" with the bearing at x = {} before it", bearings[0]),
            n => format!(" with the {n} bearings before it"),
        };
        return c.err(
            b.supports.referenced.line(),
            "track.beam.supports.intermediate",
            format!("has a bearing at x = {}{before} that does not divide the beam into spans of commensurable length (a uniform mesh of at most {MAX_SPANS} elements needs a node at each)", bearings[k - 1]),
        );
    };
    Ok((supports, bearings, multiple))
}

/// Element count (0 when left out: the plan chooses it), degree and quadrature.
pub(super) fn mesh(
    c: &Checker,
    b: &BeamFile,
    multiple: usize,
) -> Result<(usize, usize, Quadrature), Error> {
    // Left out, the element count is chosen from the accuracy once the loads are read (below).
    let elements = match &b.elements {
        None => 0,
        Some(n) if n.value >= 1 => n.value as usize,
        Some(n) => {
            return c.err(
                n.referenced.line(),
                "track.beam.elements",
                format!("must be at least 1 (got {})", n.value),
            )
        }
    };
    if let Some(n) = &b.elements {
        if n.value as usize % multiple != 0 {
            return c.err(
                n.referenced.line(),
                "track.beam.elements",
                format!(
                    "= {} puts no node at an intermediate bearing: use a multiple of {multiple}",
                    n.value
                ),
            );
        }
    }
    let order = match &b.order {
        None => DEFAULT_ORDER,
        Some(n) if (1..=MAX_ORDER as i64).contains(&n.value) => n.value as usize,
        Some(n) => {
            return c.err(
                n.referenced.line(),
                "track.beam.order",
                format!(
                    "must be a Lagrange degree from 1 to {MAX_ORDER} (got {})",
                    n.value
                ),
            )
        }
    };
    if let Some(n) = &b.elements {
        let nodes = n.value as f64 * order as f64 + 1.0;
        if nodes > MAX_NODES {
            return c.err(
                n.referenced.line(),
                "track.beam.elements",
                format!(
                    "= {} of degree {order} makes {nodes:.0} nodes; a beam may have at most {MAX_NODES:.0} (three unknowns each)",
                    n.value
                ),
            );
        }
    }
    let quadrature = match &b.quadrature {
        None => Quadrature::Reduced,
        Some(q) => Quadrature::from_name(&q.value).map_or_else(
            || {
                c.err(
                    q.referenced.line(),
                    "track.beam.quadrature",
                    format!("is {}; use reduced, full or lobatto", quote(&q.value)),
                )
            },
            Ok,
        )?,
    };
    Ok((elements, order, quadrature))
}

pub(super) fn beam_start(c: &Checker, b: &BeamFile, beam: &BeamSpec) -> Result<BeamStart, Error> {
    let start = match &b.initial {
        None => BeamStart::Rest,
        Some(v) if v.value == "rest" => BeamStart::Rest,
        Some(v) if v.value == "static" => BeamStart::Static,
        Some(v) => {
            return c.err(
                v.referenced.line(),
                "track.beam.initial",
                format!("is {}; use rest or static", quote(&v.value)),
            )
        }
    };
    if start == BeamStart::Static && !statically_supported(beam.supports, beam.bearings.len()) {
        return c.err(
            b.initial.as_ref().map_or(0, |v| v.referenced.line()),
            "track.beam.initial",
            "is static, but the supports leave the beam free to move as a rigid body, so it has no static equilibrium",
        );
    }

    Ok(start)
}

/// A material point of the beam, x in [0, L].
pub(super) fn within(c: &Checker, x: &Spanned<f64>, key: &str, length: f64) -> Result<f64, Error> {
    let v = c.finite(x, key)?;
    if !(0.0..=length).contains(&v) {
        return c.err(
            x.referenced.line(),
            key,
            format!("= {v} lies outside the beam, which runs over x in [0, {length}]"),
        );
    }
    Ok(v)
}

/// The shortest time a point load may act, relative to the run's times: a hundred times the
/// driver's floor on a step.
const SHORTEST_LOAD: f64 = 1e-12;

pub(super) fn point_loads(
    c: &Checker,
    raw: &SceneFile,
    length: f64,
) -> Result<Vec<PointLoad>, Error> {
    let mut loads = Vec::new();
    if let Some(list) = &raw.loads {
        for l in &list.value {
            let lf = &l.value;
            let opt = |v: &Option<Spanned<f64>>, key: &str| {
                v.as_ref().map_or(Ok(0.0), |v| c.finite(v, key))
            };
            let from_t = opt(&lf.from, "loads.from")?;
            let until = match &lf.until {
                None => f64::INFINITY,
                Some(u) => {
                    let u_v = c.finite(u, "loads.until")?;
                    if u_v <= from_t {
                        return c.err(
                            u.referenced.line(),
                            "loads.until",
                            format!(
                                "= {u_v} is not after `from` = {from_t}: the load would never act"
                            ),
                        );
                    }
                    // Steps shorter than 1e-14 of the run's times are not taken (the driver's
                    // floor): a load on for less lies inside a step, whose stages see it or
                    // not by where they fall. On for 1e-300 s from t = 0, a 3 kN tip load
                    // threw C1's cantilever 19 mm, the impulse of a whole step.
                    let resolved =
                        SHORTEST_LOAD * from_t.abs().max(u_v).max(raw.duration.value).max(1.0);
                    if u_v - from_t < resolved {
                        return c.err(
                            u.referenced.line(),
                            "loads.until",
                            format!("= {u_v} leaves the load on for {:e} s after `from` = {from_t}, less than {resolved:e} s (a trillionth of the run's times), within which the steps cannot hold its start and end apart: give it longer, or leave it out (its impulse is below the force times that)", u_v - from_t),
                        );
                    }
                    u_v
                }
            };
            loads.push(PointLoad {
                x: within(c, &lf.x, "loads.x", length)?,
                force: [opt(&lf.fx, "loads.fx")?, opt(&lf.fy, "loads.fy")?],
                mz: opt(&lf.mz, "loads.mz")?,
                from: from_t,
                until,
            });
        }
    }
    Ok(loads)
}

/// Probes (default: `mid` at L/2), shape times and their magnification.
pub(super) fn outputs(
    c: &Checker,
    raw: &SceneFile,
    length: f64,
    duration: f64,
) -> Result<(Vec<Probe>, Vec<f64>, f64), Error> {
    let mut probes = Vec::new();
    let mut shapes = Vec::new();
    let mut magnify = 1.0;
    if let Some(o) = &raw.output {
        for (list, key, most) in [
            (
                o.probes
                    .as_ref()
                    .map(|v| (v.referenced.line(), v.value.len())),
                "output.probes",
                MAX_PROBES,
            ),
            (
                o.shapes
                    .as_ref()
                    .map(|v| (v.referenced.line(), v.value.len())),
                "output.shapes",
                MAX_SHAPES,
            ),
        ] {
            if let Some((line, n)) = list.filter(|&(_, n)| n > most) {
                return c.err(
                    line,
                    key,
                    format!("lists {n} entries; at most {most} are allowed"),
                );
            }
        }
        for p in o.probes.iter().flat_map(|v| v.value.iter()) {
            let name = &p.value.name;
            let why = name_flaw(&name.value, 40).or_else(|| {
                if name.value.contains([',', '"']) {
                    Some(
                        "holds a comma or a quote, which cannot head a column of history.csv"
                            .into(),
                    )
                } else if probes.iter().any(|q: &Probe| q.name == name.value) {
                    Some("names two probes".into())
                } else {
                    None
                }
            });
            if let Some(why) = why {
                return c.err(
                    name.referenced.line(),
                    "output.probes.name",
                    format!("= {} {why}", quote(&name.value)),
                );
            }
            probes.push(Probe {
                name: name.value.clone(),
                x: within(c, &p.value.x, "output.probes.x", length)?,
            });
        }
        for t in o.shapes.iter().flat_map(|v| v.value.iter()) {
            let tv = c.finite(t, "output.shapes")?;
            if !(0.0..=duration).contains(&tv) {
                return c.err(
                    t.referenced.line(),
                    "output.shapes",
                    format!("time {tv} lies outside the run [0, {duration}]"),
                );
            }
            shapes.push(tv);
        }
        if let Some(m) = &o.magnify {
            magnify = c.positive(m, "output.magnify")?;
        }
    }
    Ok((probes, shapes, magnify))
}

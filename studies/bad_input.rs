//! Bad input: each case must end with exit status 1 and one sentence on stderr that names the
//! problem (and, for scene errors, the line and key), never a panic, a NaN or a silent run.

use std::path::PathBuf;
use std::process::Command;

const GOOD_DISK: &str = "disk:\n  mass: 1.0\n  radius: 0.1\n  s0: -1.0\n";
const PARABOLA: &str = "track:\n  curve:\n    parabola: {k: 1.0}\n";

fn scene_path(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rollbeam-bad-input-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(format!("{name}.yaml"));
    std::fs::write(&path, text).expect("write scene");
    path
}

/// Run `rollbeam ARGS` and return (exit code, stderr).
fn rollbeam(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_rollbeam"))
        .args(args)
        .env("CI", "true")
        .output()
        .expect("run rollbeam");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The scene is rejected by both `check` and `run` with one sentence holding every `needle`.
fn rejected(name: &str, text: &str, needles: &[&str]) {
    let path = scene_path(name, text);
    let p = path.to_str().expect("utf-8 path");
    let out = format!("{p}.out");
    for args in [vec!["check", p], vec!["run", p, "--out", &out]] {
        let cmd = args[0];
        let (code, err) = rollbeam(&args);
        assert_eq!(code, 1, "{name}/{cmd}: exit {code}, stderr: {err}");
        assert_eq!(
            err.trim().lines().count(),
            1,
            "{name}/{cmd}: not one sentence: {err}"
        );
        assert!(
            !err.contains("panicked") && !err.contains("NaN") || err.contains("not NaN"),
            "{name}: {err}"
        );
        for n in needles {
            assert!(err.contains(n), "{name}/{cmd}: '{n}' missing from: {err}");
        }
    }
}

#[test]
fn unknown_keys() {
    rejected(
        "unknown-top",
        &format!("duration: 1\ndurration: 2\n{PARABOLA}{GOOD_DISK}"),
        &["line 2", "`durration` is not a key"],
    );
    rejected(
        "unknown-disk",
        &format!("duration: 1\n{PARABOLA}{GOOD_DISK}  mas: 3\n"),
        &["line 9", "`disk.mas` is not a key"],
    );
    rejected(
        "unknown-curve",
        &format!("duration: 1\ntrack:\n  curve:\n    circle: {{r: 1}}\n{GOOD_DISK}"),
        &["line 4", "`track.curve.circle` is not a key"],
    );
}

#[test]
fn duration_missing_or_not_positive() {
    rejected(
        "no-duration",
        &format!("{PARABOLA}{GOOD_DISK}"),
        &["`duration` is missing"],
    );
    rejected(
        "zero-duration",
        &format!("duration: 0\n{PARABOLA}{GOOD_DISK}"),
        &["line 1", "`duration` must be positive"],
    );
    rejected(
        "negative-duration",
        &format!("duration: -2\n{PARABOLA}{GOOD_DISK}"),
        &["line 1", "`duration` must be positive"],
    );
}

#[test]
fn disk_sizes_not_positive() {
    rejected(
        "zero-mass",
        &format!("duration: 1\n{PARABOLA}disk:\n  mass: 0\n  radius: 0.1\n"),
        &["line 6", "`disk.mass` must be positive"],
    );
    rejected(
        "negative-radius",
        &format!("duration: 1\n{PARABOLA}disk:\n  mass: 1\n  radius: -0.1\n"),
        &["line 7", "`disk.radius` must be positive"],
    );
}

/// On Y = kX² the curvature peaks at 2k at the vertex, which a disk released anywhere reaches:
/// a ≥ 1/(2k) cannot roll there. Just below the limit the scene is accepted.
#[test]
fn disk_that_cannot_fit_the_parabola() {
    for a in ["0.5", "0.8"] {
        rejected(
            &format!("fit-{a}"),
            &format!("duration: 1\n{PARABOLA}disk:\n  mass: 1\n  radius: {a}\n  s0: -1.5\n"),
            &["line 7", "`disk.radius`", "does not fit"],
        );
    }
    let ok = scene_path(
        "fit-ok",
        &format!("duration: 1\n{PARABOLA}disk:\n  mass: 1\n  radius: 0.499\n  s0: -1.5\n"),
    );
    assert_eq!(rollbeam(&["check", ok.to_str().unwrap()]).0, 0);
}

#[test]
fn formulas_that_do_not_parse() {
    let expr = |x: &str, y: &str| {
        format!("duration: 1\ntrack:\n  curve:\n    expr: {{x: \"{x}\", y: \"{y}\"}}\n{GOOD_DISK}")
    };
    rejected(
        "expr-function",
        &expr("s", "foo(s)"),
        &["line 4", "track.curve.expr.y", "unknown function 'foo'"],
    );
    rejected(
        "expr-syntax",
        &expr("s + ", "0"),
        &["line 4", "track.curve.expr.x", "does not parse"],
    );
    rejected("expr-name", &expr("s", "2*x"), &["unknown name 'x'"]);
}

#[test]
fn bad_point_lists() {
    let pts = |p: &str| {
        format!("duration: 1\ntrack:\n  curve:\n    points: {p}\ndisk:\n  mass: 1\n  radius: 0.1\n  s0: 0.5\n")
    };
    rejected(
        "three-points",
        &pts("[[0, 0], [1, 0], [2, 0]]"),
        &["line 4", "has 3 points", "at least 4"],
    );
    rejected(
        "x-decreasing",
        &pts("[[0, 0], [1, 0], [0.5, 0], [2, 0]]"),
        &["X increasing", "point 3"],
    );
    // Past the YAML reader's budget of values: its sentence, not its Debug text.
    let long: Vec<String> = (0..90_000).map(|i| format!("[{i}, 0]")).collect();
    rejected(
        "past-the-readers-budget",
        &pts(&format!("[{}]", long.join(", "))),
        &[
            "line 4",
            "`track.curve.points` holds more values",
            "than the scene reader takes",
        ],
    );
}

#[test]
fn start_off_a_finite_track() {
    let line = "duration: 1\ntrack:\n  curve:\n    line: {from: [0, 0], to: [3, 4]}\ndisk:\n  mass: 1\n  radius: 0.1\n  s0: 6\n";
    rejected(
        "off-line",
        line,
        &["line 8", "`disk.s0`", "off the track", "[0, 5]"],
    );
}

/// A curve without a finite tangent where the disk starts, and an output grid too fine to write.
#[test]
fn degenerate_curve_and_output() {
    rejected("sqrt-curve", "duration: 1\ntrack:\n  curve:\n    expr: {x: \"s\", y: \"sqrt(s)\"}\ndisk:\n  mass: 1\n  radius: 0.1\n  s0: 0\n", &["line 4", "track.curve", "no finite tangent or curvature"]);
    rejected(
        "tiny-interval",
        &format!("duration: 1\n{PARABOLA}{GOOD_DISK}output:\n  interval: 1e-300\n"),
        &["line 10", "output.interval", "rows"],
    );
}

#[test]
fn tolerances_not_positive() {
    rejected(
        "rtol-zero",
        &format!("duration: 1\n{PARABOLA}{GOOD_DISK}solver:\n  rtol: 0\n"),
        &["line 10", "`solver.rtol` must be positive"],
    );
    let good = scene_path("good", &format!("duration: 0.1\n{PARABOLA}{GOOD_DISK}"));
    let (code, err) = rollbeam(&["run", good.to_str().unwrap(), "--rtol", "-1"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("--rtol must be a positive number"), "{err}");
    let (code, err) = rollbeam(&["run", good.to_str().unwrap(), "--method", "euler"]);
    assert!(
        code == 1 && err.contains("--method 'euler' is unknown"),
        "{err}"
    );
}

#[test]
fn non_finite_numbers_anywhere() {
    rejected(
        "nan-duration",
        &format!("duration: .nan\n{PARABOLA}{GOOD_DISK}"),
        &["line 1", "`duration` must be a finite number"],
    );
    rejected(
        "inf-k",
        "duration: 1\ntrack:\n  curve:\n    parabola: {k: .inf}\ndisk:\n  mass: 1\n  radius: 0.1\n",
        &["line 4", "parabola.k", "finite"],
    );
    rejected("inf-point", "duration: 1\ntrack:\n  curve:\n    line: {from: [0, 0], to: [.inf, 1]}\ndisk:\n  mass: 1\n  radius: 0.1\n", &["line 4", "line.to", "finite"]);
    rejected(
        "nan-mass",
        &format!("duration: 1\n{PARABOLA}disk:\n  mass: .nan\n  radius: 0.1\n"),
        &["line 6", "disk.mass", "finite"],
    );
    rejected(
        "inf-omega",
        &format!("duration: 1\n{PARABOLA}{GOOD_DISK}  omega0: -.inf\n"),
        &["line 9", "disk.omega0", "finite"],
    );
}

#[test]
fn track_must_be_curve_xor_beam() {
    rejected(
        "both",
        &format!(
            "duration: 1\ntrack:\n  curve:\n    parabola: {{k: 1}}\n  beam:\n{}{GOOD_DISK}",
            beam_body(&[])
        ),
        &["`track` must name exactly one of `curve` or `beam`"],
    );
    rejected(
        "neither",
        &format!("duration: 1\ntrack: {{}}\n{GOOD_DISK}"),
        &["line 2", "exactly one of `curve` or `beam`"],
    );
}

#[test]
fn files_that_are_missing_or_not_yaml() {
    for cmd in ["check", "run"] {
        let (code, err) = rollbeam(&[cmd, "/nonexistent/scene.yaml"]);
        assert!(
            code == 1 && err.contains("cannot read scene file") && err.trim().lines().count() == 1,
            "{err}"
        );
    }
    rejected(
        "not-yaml",
        "duration: [1, 2\n  : : :\n",
        &["`duration` must be one value", "line 1"],
    );
    rejected(
        "wrong-type",
        &format!("duration: soon\n{PARABOLA}{GOOD_DISK}"),
        &["`duration` must be a number", "line 1"],
    );
    rejected(
        "list-for-a-number",
        &format!("duration: [1]\n{PARABOLA}{GOOD_DISK}"),
        &[
            "`duration` must be one value, not a list or a map",
            "line 1",
        ],
    );
    rejected(
        "a-list-not-a-scene",
        "- duration: 1\n",
        &["line 1", "a scene file is a map of keys"],
    );
    rejected(
        "a-number-for-a-list",
        &beam_scene(&[], "train: {axles: 3, load: 1.0e4, speed: 10.0}\n"),
        &["`train.axles` must be a list"],
    );
    rejected(
        "axle-load-as-text",
        &beam_scene(&[], "train: {axles: [0.0], load: heavy, speed: 10.0}\n"),
        &["`train.load` must be a number (N on every axle) or a list of numbers"],
    );
}

#[test]
fn command_line_errors() {
    for args in [
        &["bogus"][..],
        &["run"][..],
        &["run", "a.yaml", "--frobnicate"][..],
    ] {
        let (code, err) = rollbeam(args);
        assert_eq!(code, 1, "{args:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
    }
}

/// An absolute tolerance the size of the beam holds no step (C2's 3 m cantilever at atol 1000
/// ran 45 s into a singular iteration matrix): refused before the run, in the scene and on the
/// command line alike; one below it runs.
#[test]
fn an_absolute_tolerance_past_the_beam_is_refused() {
    rejected(
        "atol-past-the-beam",
        &beam_scene(&[], "solver:\n  atol: 8.0\n"),
        &["`solver.atol` = 8 is not below the beam's length (8 m)"],
    );
    let good = scene_path("atol-within", &beam_scene(&[], "solver:\n  atol: 1.0e-3\n"));
    let (code, err) = rollbeam(&["check", good.to_str().expect("utf-8")]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = rollbeam(&["run", good.to_str().expect("utf-8"), "--atol", "1e3"]);
    assert!(
        code == 1 && err.contains("--atol = 1000 is not below the beam's length (8 m)"),
        "{err}"
    );
}

/// A point load on for less than a trillionth of the run's times lies inside one step, whose
/// stages see it or not by where they fall (on for 1e-300 s from t = 0, 3 kN threw C1's
/// cantilever 19 mm): refused; one on for a microsecond runs.
#[test]
fn a_load_shorter_than_the_steps_can_resolve_is_refused() {
    let load = |until: &str| {
        beam_scene(
            &[],
            &format!("loads:\n  - {{x: 8.0, fy: -3.0e3, from: 0.0, until: {until}}}\n"),
        )
    };
    rejected(
        "load-too-short",
        &load("1.0e-300"),
        &[
            "`loads.until` = 1e-300 leaves the load on for 1e-300 s",
            "a trillionth",
        ],
    );
    let good = scene_path("load-short", &load("1.0e-6"));
    let (code, err) = rollbeam(&["check", good.to_str().expect("utf-8")]);
    assert_eq!(code, 0, "{err}");
}

/// The body of a valid beam under `track:` (indented), with keys replaced by `changes`.
fn beam_body(changes: &[(&str, &str)]) -> String {
    let mut keys = vec![
        ("from", "[0, 0]"),
        ("to", "[8, 0]"),
        ("E", "210e9"),
        ("G", "81e9"),
        ("rho", "7850"),
        ("A", "59.8e-4"),
        ("Av", "29.9e-4"),
        ("I", "3620e-8"),
        ("supports", "{from: clamped, to: pinned}"),
        ("elements", "4"),
        ("order", "2"),
    ];
    for (k, v) in changes {
        match keys.iter_mut().find(|(key, _)| key == k) {
            Some(entry) => entry.1 = v,
            None => keys.push((k, v)),
        }
    }
    keys.iter()
        .map(|(k, v)| format!("    {k}: {v}\n"))
        .collect()
}

fn beam_scene(changes: &[(&str, &str)], rest: &str) -> String {
    format!(
        "duration: 0.01\ntrack:\n  beam:\n{}{rest}",
        beam_body(changes)
    )
}

#[test]
fn bad_beams() {
    rejected(
        "support",
        &beam_scene(&[("supports", "{from: hinge, to: pinned}")], ""),
        &[
            "track.beam.supports.from",
            "'hinge'",
            "clamped, pinned, roller or free",
        ],
    );
    rejected(
        "zero-length",
        &beam_scene(&[("to", "[0, 0]")], ""),
        &["zero length"],
    );
    for key in ["E", "G", "rho", "A", "Av", "I"] {
        rejected(
            &format!("nonpositive-{key}"),
            &beam_scene(&[(key, "0")], ""),
            &[&format!("`track.beam.{key}` must be positive")],
        );
    }
    rejected(
        "no-elements",
        &beam_scene(&[("elements", "0")], ""),
        &["track.beam.elements", "at least 1"],
    );
    rejected(
        "order-11",
        &beam_scene(&[("order", "11")], ""),
        &["track.beam.order", "from 1 to 10"],
    );
    rejected(
        "order-0",
        &beam_scene(&[("order", "0")], ""),
        &["track.beam.order"],
    );
    rejected(
        "load-outside",
        &beam_scene(&[], "loads:\n  - {x: 9.5, fy: -1}\n"),
        &["loads.x", "outside the beam", "[0, 8]"],
    );
    rejected(
        "until-before-from",
        &beam_scene(&[], "loads:\n  - {x: 4, fy: -1, from: 0.5, until: 0.2}\n"),
        &["loads.until", "not after `from`"],
    );
    rejected(
        "probe-outside",
        &beam_scene(&[], "output:\n  probes: [{name: p, x: -1}]\n"),
        &["output.probes.x", "outside the beam"],
    );
    rejected(
        "depth-zero",
        &beam_scene(&[("depth", "0")], ""),
        &["`track.beam.depth` must be positive"],
    );
    rejected(
        "depth-deeper-than-long",
        &beam_scene(&[("depth", "9")], ""),
        &["track.beam.depth", "deeper than the beam is long"],
    );
}

/// Intermediate bearings and the static start: each bad setting is named with its key.
#[test]
fn bad_bearings_and_starts() {
    rejected(
        "bearing-at-end",
        &beam_scene(
            &[("supports", "{from: pinned, to: roller, intermediate: [8]}")],
            "",
        ),
        &["track.beam.supports.intermediate", "not strictly inside"],
    );
    // A bearing a picometre from an end is that end's: refused as at it, not run as a span of
    // 1e-12 m whose mesh node coincides with the end's.
    rejected(
        "bearing-a-picometre-in",
        &beam_scene(
            &[(
                "supports",
                "{from: pinned, to: roller, intermediate: [1.0e-12]}",
            )],
            "",
        ),
        &[
            "track.beam.supports.intermediate",
            "x = 0.000000000001",
            "not strictly inside",
        ],
    );
    rejected(
        "bearing-twice",
        &beam_scene(
            &[(
                "supports",
                "{from: pinned, to: roller, intermediate: [4, 4]}",
            )],
            "",
        ),
        &["track.beam.supports.intermediate", "twice"],
    );
    rejected(
        "bearing-incommensurable",
        &beam_scene(
            &[(
                "supports",
                "{from: pinned, to: roller, intermediate: [2.8284271247461903]}",
            )],
            "",
        ),
        &["track.beam.supports.intermediate", "commensurable"],
    );
    rejected(
        "bearing-off-node",
        &beam_scene(
            &[
                (
                    "supports",
                    "{from: pinned, to: roller, intermediate: [2.0]}",
                ),
                ("elements", "2"),
            ],
            "",
        ),
        &["track.beam.elements", "multiple of 4"],
    );
    rejected(
        "start-unknown",
        &beam_scene(&[("initial", "deflected")], ""),
        &["track.beam.initial", "'deflected'", "rest or static"],
    );
    rejected(
        "start-static-mechanism",
        &beam_scene(
            &[
                ("supports", "{from: roller, to: free}"),
                ("initial", "static"),
            ],
            "",
        ),
        &["track.beam.initial", "rigid body"],
    );
    // One past the bound each: refused before a run allocates a column or a curve for each.
    let probes: Vec<String> = (0..1001).map(|i| format!("{{name: p{i}, x: 1}}")).collect();
    rejected(
        "too-many-probes",
        &beam_scene(
            &[],
            &format!("output:\n  probes: [{}]\n", probes.join(", ")),
        ),
        &["output.probes", "1001 entries", "at most 1000"],
    );
    let shapes: Vec<String> = (0..1001).map(|i| format!("{}", i as f64 * 1e-5)).collect();
    rejected(
        "too-many-shapes",
        &beam_scene(
            &[],
            &format!("output:\n  shapes: [{}]\n", shapes.join(", ")),
        ),
        &["output.shapes", "1001 entries", "at most 1000"],
    );
    // Three reactions, all across the axis: the beam still slides along it.
    rejected(
        "start-static-sliding",
        &beam_scene(
            &[
                ("supports", "{from: roller, to: roller, intermediate: [4]}"),
                ("initial", "static"),
            ],
            "",
        ),
        &["track.beam.initial", "rigid body"],
    );
}

/// A disk on a beam: each bad setting is named with its key.
#[test]
fn bad_disks_on_beams() {
    let disk = |body: &str| beam_scene(&[], &format!("disk:\n{body}"));
    rejected(
        "coupling",
        &disk("  mass: 1500\n  radius: 0.4\n  s0: 1\n  coupling: rigid\n"),
        &[
            "disk.coupling",
            "'rigid'",
            "consistent, thesis, moving-mass, moving-force",
        ],
    );
    rejected(
        "s0-beyond",
        &disk("  mass: 1500\n  radius: 0.4\n  s0: 9\n  omega0: -10\n"),
        &["disk.s0", "off the beam", "[0, 8]"],
    );
    rejected(
        "s0-negative",
        &disk("  mass: 1500\n  radius: 0.4\n  s0: -0.5\n  omega0: -10\n"),
        &["disk.s0", "off the beam"],
    );
    rejected(
        "radius",
        &disk("  mass: 1500\n  radius: 0\n  s0: 1\n"),
        &["disk.radius", "must be positive"],
    );
    rejected(
        "mass",
        &disk("  mass: -3\n  radius: 0.4\n  s0: 1\n"),
        &["disk.mass", "must be positive"],
    );
    rejected(
        "moving-without-speed",
        &disk("  mass: 1500\n  radius: 0.4\n  s0: 1\n  coupling: moving-force\n"),
        &["disk.omega0", "is 0", "moving-force", "non-zero omega0"],
    );
    rejected(
        "rolls-off-its-support",
        &disk("  mass: 1500\n  radius: 0.4\n  s0: 0\n  omega0: 20\n"),
        &["disk.omega0", "rolls the disk off the end", "s0 = 0"],
    );
    rejected(
        "resting-on-support",
        &disk("  mass: 1500\n  radius: 0.4\n  s0: 8\n"),
        &["disk.s0", "at rest on the end support"],
    );
    rejected(
        "formulation-on-beam",
        &disk("  mass: 1500\n  radius: 0.4\n  s0: 1\n  formulation: thesis\n"),
        &["disk.formulation", "rigid curves only"],
    );
}

/// Lift-off and landing: an unknown `contact_loss`, a restitution outside [0, 1] or not
/// finite, a restitution with nothing to land, either key on a coupling whose load cannot
/// leave the beam, and flight with the thesis coupling, which rolls the disk on a frozen axis.
#[test]
fn bad_contact_loss_and_restitution() {
    let curve = |extra: &str| format!("duration: 1\n{PARABOLA}{GOOD_DISK}{extra}");
    rejected(
        "contact-loss-unknown",
        &curve("  contact_loss: bounce\n"),
        &["disk.contact_loss", "'bounce'", "fly or stop"],
    );
    for (name, e) in [("above-one", "1.5"), ("negative", "-0.1"), ("nan", ".nan")] {
        rejected(
            &format!("restitution-{name}"),
            &curve(&format!("  restitution: {e}\n")),
            &["disk.restitution"],
        );
    }
    rejected(
        "restitution-outside",
        &curve("  restitution: 2\n"),
        &["disk.restitution", "outside [0, 1]"],
    );
    rejected(
        "restitution-with-stop",
        &curve("  contact_loss: stop\n  restitution: 0.5\n"),
        &["disk.restitution", "never lands"],
    );
    let on_beam = |extra: &str| {
        beam_scene(
            &[],
            &format!("disk:\n  mass: 10\n  radius: 0.1\n  s0: 1\n  omega0: -10\n{extra}"),
        )
    };
    rejected(
        "thesis-flies",
        &on_beam("  coupling: thesis\n  contact_loss: fly\n"),
        &["disk.contact_loss", "only the consistent coupling"],
    );
    for coupling in ["moving-force", "moving-mass"] {
        for key in ["contact_loss: stop", "restitution: 0.2"] {
            rejected(
                &format!("{coupling}-{}", &key[..4]),
                &beam_scene(
                    &[],
                    &format!("disk:\n  mass: 10\n  radius: 0.1\n  s0: 1\n  omega0: -10\n  coupling: {coupling}\n  {key}\n"),
                ),
                &[key.split(':').next().unwrap_or(key), coupling, "never leaves it"],
            );
        }
    }
}

/// The beam model: an unknown name, a mode count below 1 or past the mesh's unknowns, a mode
/// count on a model that keeps every unknown, and the thesis' 3n + 6 system on a reduced beam.
#[test]
fn bad_beam_models() {
    rejected(
        "model-unknown",
        &beam_scene(&[("model", "nonlinear")], ""),
        &["track.beam.model", "'nonlinear'", "exact, linear or modal"],
    );
    rejected(
        "modes-zero",
        &beam_scene(&[("model", "modal"), ("modes", "0")], ""),
        &["track.beam.modes", "at least 1"],
    );
    // 4 elements of degree 2 clamped–pinned: 27 nodal unknowns less 5 held.
    rejected(
        "modes-past-mesh",
        &beam_scene(&[("model", "modal"), ("modes", "23")], ""),
        &["track.beam.modes", "more than the mesh has", "22 unknowns"],
    );
    for model in ["exact", "linear"] {
        rejected(
            &format!("modes-on-{model}"),
            &beam_scene(&[("model", model), ("modes", "4")], ""),
            &[
                "track.beam.modes",
                &format!("`model: {model}` keeps every unknown"),
            ],
        );
    }
    rejected(
        "thesis-system-on-modal",
        &beam_scene(
            &[("model", "modal"), ("modes", "4")],
            "disk:\n  mass: 1500\n  radius: 0.4\n  s0: 1\n  coupling: thesis\nsolver:\n  method: trbdf2\n",
        ),
        &["solver.method", "3n + 6", "model: exact"],
    );
}

/// Damping: a ratio outside [0, 1), anchors that are not two distinct mode numbers, a
/// negative α or β, both forms at once, or none.
#[test]
fn bad_damping() {
    let damped = |d: &str| beam_scene(&[("damping", d)], "");
    rejected(
        "ratio-one",
        &damped("{ratio: 1.0}"),
        &["track.beam.damping.ratio", "[0, 1)"],
    );
    rejected(
        "ratio-negative",
        &damped("{ratio: -0.01}"),
        &[
            "track.beam.damping.ratio",
            "[0, 1)",
            "feed the vibration energy",
        ],
    );
    for modes in ["[1]", "[2, 2]", "[0, 1]", "[1, 2, 3]"] {
        rejected(
            &format!("anchors-{modes}"),
            &damped(&format!("{{ratio: 0.02, modes: {modes}}}")),
            &["track.beam.damping.modes", "two distinct mode numbers"],
        );
    }
    rejected(
        "alpha-negative",
        &damped("{alpha: -0.5, beta: 1.0e-4}"),
        &["track.beam.damping.alpha", "must not be negative"],
    );
    rejected(
        "beta-negative",
        &damped("{alpha: 0.5, beta: -1.0e-4}"),
        &["track.beam.damping.beta", "must not be negative"],
    );
    rejected(
        "both-forms",
        &damped("{ratio: 0.02, beta: 1.0e-4}"),
        &["track.beam.damping", "not both"],
    );
    rejected("empty", &damped("{}"), &["track.beam.damping", "is empty"]);
}

/// An anchor mode the mesh does not have is found when the modes are computed: one sentence,
/// exit 1, from `run` (4 elements of degree 2, 22 unknowns).
#[test]
fn damping_anchored_past_the_mesh() {
    let path = scene_path(
        "damping-past-mesh",
        &beam_scene(&[("damping", "{ratio: 0.02, modes: [1, 40]}")], ""),
    );
    let p = path.to_str().unwrap();
    let (code, err) = rollbeam(&["run", p, "--out", "/tmp/rollbeam-damping-past-mesh"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("names bending mode 40, but the mesh has") && err.trim().lines().count() == 1,
        "{err}"
    );
}

/// A train: an unknown HSLM name (A01 too), a negative load on moving masses, axles not increasing or negative, a load list of the wrong
/// length, a speed not above zero, a train beside a disk, an HSLM name with axles, a train on
/// a rigid curve, an unknown model, and moving masses without gravity to weigh them.
#[test]
fn bad_trains() {
    let train = |body: &str| beam_scene(&[], &format!("train:\n{body}"));
    rejected(
        "hslm-unknown",
        &train("  hslm: A11\n  speed: 50\n"),
        &["train.hslm", "'A11'", "A1 to A10"],
    );
    rejected(
        "hslm-leading-zero",
        &train("  hslm: A01\n  speed: 50\n"),
        &["train.hslm", "'A01'", "A1 to A10"],
    );
    rejected(
        "moving-mass-negative-load",
        &train("  axles: [0, 3]\n  load: -1.0e5\n  speed: 50\n  model: moving-mass\n"),
        &["train.load", "positive forces", "moving-mass"],
    );
    for axles in ["[0, 3, 3]", "[0, -3]", "[5, 3]"] {
        rejected(
            &format!("axles-{axles}"),
            &train(&format!("  axles: {axles}\n  load: 1.0e5\n  speed: 50\n")),
            &["train.axles", "from 0 and increasing"],
        );
    }
    rejected(
        "load-count",
        &train("  axles: [0, 3, 14]\n  load: [1.0e5, 2.0e5]\n  speed: 50\n"),
        &["train.load", "2 loads for 3 axles"],
    );
    for speed in ["0", "-90"] {
        rejected(
            &format!("speed-{speed}"),
            &train(&format!("  hslm: A1\n  speed: {speed}\n")),
            &["train.speed", "must be positive"],
        );
    }
    rejected(
        "speed-subnormal",
        &train("  hslm: A1\n  speed: 1.0e-320\n"),
        &["train.speed", "infinite"],
    );
    rejected(
        "hslm-and-axles",
        &train("  hslm: A1\n  axles: [0, 3]\n  load: 1.0e5\n  speed: 50\n"),
        &["train.hslm", "leave `axles` and `load` out"],
    );
    rejected(
        "train-on-curve",
        &format!("duration: 1\n{PARABOLA}{GOOD_DISK}train:\n  hslm: A1\n  speed: 50\n"),
        &["train", "beam tracks only"],
    );
    rejected(
        "train-model",
        &train(
            "  hslm: A1
  speed: 50
  model: sprung-mass
",
        ),
        &[
            "train.model",
            "'sprung-mass'",
            "moving-force or moving-mass",
        ],
    );
    rejected(
        "moving-mass-weightless",
        &format!(
            "gravity: 0\n{}",
            train("  hslm: A1\n  speed: 50\n  model: moving-mass\n")
        ),
        &["train.model", "gravity is 0", "moving-force"],
    );
}

/// A modal beam that is a mechanism has no static answer either, and `modes` asks no more of
/// a modal beam than the modes it keeps.
#[test]
fn modal_mechanism_and_mode_count() {
    let path = scene_path(
        "modal-mechanism",
        &beam_scene(
            &[
                ("supports", "{from: free, to: free}"),
                ("model", "modal"),
                ("modes", "6"),
            ],
            "loads:\n  - {x: 4, fy: -1}\n",
        ),
    );
    let p = path.to_str().unwrap();
    let (code, err) = rollbeam(&["static", p, "--out", "/tmp/rollbeam-modal-mechanism"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("not supported enough for a static solution")
            && err.trim().lines().count() == 1,
        "{err}"
    );
    let (code, err) = rollbeam(&[
        "modes",
        p,
        "--count",
        "7",
        "--out",
        "/tmp/rollbeam-modal-mechanism",
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("more than the modal beam keeps (6 modes"),
        "{err}"
    );
}

/// Nor does `modes` give fewer modes than asked on a beam that keeps its mesh: D44's mesh
/// holds 120 unknowns, so 120 modes are computed and a 121st is one sentence, exit 1.
#[test]
fn modes_past_the_mesh() {
    let d44 = crate::common::studies_dir().join("bridge-d44.yaml");
    let p = d44.to_str().unwrap();
    let out = "/tmp/rollbeam-modes-past-the-mesh";
    let (code, err) = rollbeam(&["modes", p, "--count", "120", "--out", out]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = rollbeam(&["modes", p, "--count", "121", "--out", out]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("--count 121 is more than the 120 modes the mesh holds")
            && err.trim().lines().count() == 1,
        "{err}"
    );
}

/// A free–free beam has no static equilibrium under a load: one sentence, exit 1.
#[test]
fn static_solution_of_a_mechanism() {
    let path = scene_path(
        "mechanism",
        &beam_scene(
            &[("supports", "{from: free, to: free}")],
            "loads:\n  - {x: 4, fy: -1}\n",
        ),
    );
    let (code, err) = rollbeam(&[
        "static",
        path.to_str().unwrap(),
        "--out",
        "/tmp/rollbeam-mechanism",
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("the beam is not supported enough for a static solution")
            && err.trim().lines().count() == 1,
        "{err}"
    );
}

/// `sweep`: a malformed range or a key the scene cannot hold is one sentence and exit 1; a
/// value only some runs cannot take is a failed row, not a failed command.
#[test]
fn sweep_ranges_and_keys() {
    let path = scene_path(
        "sweep",
        &beam_scene(&[], "disk:\n  mass: 10\n  radius: 0.1\n  s0: 1\n"),
    );
    let p = path.to_str().expect("utf-8 path");
    let out = format!("{p}.sweep");
    for (set, needles) in [
        ("disk.mass=1:2", vec!["--set", "three fields"]),
        ("disk.mass=a:2:3", vec!["--set", "'a'", "finite number"]),
        ("disk.mass=1:2:0", vec!["--set", "count from 1 to 100000"]),
        (
            "disk.mass=1:2:1000000000000000000",
            vec!["--set", "count from 1 to 100000"],
        ),
        (
            "disk.mass=1:2:1e18",
            vec!["--set", "count from 1 to 100000"],
        ),
        (
            "track.beam.elements=4:9:3",
            vec![
                "--set track.beam.elements",
                "takes a whole number (got 6.5)",
            ],
        ),
        (
            "disk.nothing=1:2:2",
            vec![
                "--set disk.nothing",
                "is not a number the scene format holds",
            ],
        ),
        (
            "track.curve.k=1:2:2",
            vec![
                "--set track.curve.k",
                "is not a number the scene format holds",
            ],
        ),
        (
            "track.curve.parabola.k=1:2:2",
            vec!["--set track.curve.parabola.k", "the scene has no parabola"],
        ),
        (
            "mass=1:2:2",
            vec!["--set mass", "is not a number the scene format holds"],
        ),
        (
            "disk.nothing=1,1e3",
            vec![
                "--set disk.nothing",
                "is not a number the scene format holds",
            ],
        ),
        (
            "track.beam.elements=4.5:8:2",
            vec!["--set track.beam.elements", "takes a whole number"],
        ),
        (
            "disks.1.mass=1:2:2",
            vec!["--set disks.1.mass", "k from 1 to the 0 disks"],
        ),
    ] {
        let (code, err) = rollbeam(&["sweep", p, "--set", set, "--out", &out]);
        assert_eq!(code, 1, "{set}: exit {code}, {err}");
        assert_eq!(err.trim().lines().count(), 1, "{set}: {err}");
        for n in needles {
            assert!(err.contains(n), "{set}: '{n}' missing from {err}");
        }
    }
    let (code, err) = rollbeam(&["sweep", p, "--set", "disk.mass=-10:10:3", "--out", &out]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(format!("{out}/sweep.csv")).expect("sweep.csv");
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 3);
    assert!(rows[0].contains("failed") && rows[0].contains("must be positive"));
    assert!(rows[1].contains("failed") && rows[2].contains(",ok,"));
}

/// A planned sweep (`--plan`, `--shard`, `--merge`): flags that do not fit together, a shard
/// that is not K/N, a folder without a plan, a plan not yet run, and a plan file edited to
/// name cases outside its folder are one sentence and exit 1, with nothing run or written.
#[test]
fn sweep_plans_shards_and_merges() {
    let path = scene_path(
        "planned",
        &beam_scene(&[], "disk:\n  mass: 10\n  radius: 0.1\n  s0: 1\n"),
    );
    let p = path.to_str().expect("utf-8 path");
    let dir = format!("{p}.plan");
    let _ = std::fs::remove_dir_all(&dir);
    let (code, err) = rollbeam(&["sweep", p, "--set", "disk.mass=5:10:2", "--plan", &dir]);
    assert_eq!(code, 0, "{err}");
    let empty = format!("{p}.empty");
    std::fs::create_dir_all(&empty).expect("dir");
    for (args, needles) in [
        (
            vec!["sweep", "--plan", &dir, "--shard", "0/2"],
            vec!["--shard '0/2'", "K/N"],
        ),
        (
            vec!["sweep", "--plan", &dir, "--shard", "3/2"],
            vec!["1 ≤ K ≤ N"],
        ),
        (
            vec!["sweep", "--plan", &dir, "--shard", "x"],
            vec!["--shard 'x'"],
        ),
        (
            vec!["sweep", "--shard", "1/2"],
            vec!["give the plan folder with --plan"],
        ),
        (
            vec!["sweep", p, "--plan", &dir, "--shard", "1/2"],
            vec!["--shard takes no scene"],
        ),
        (
            vec!["sweep", "--merge", &dir, "--rtol", "1e-4"],
            vec!["--merge takes no scene"],
        ),
        (
            vec!["sweep", "--merge", &dir, "--plan", &dir],
            vec!["--merge is given alone"],
        ),
        (
            vec!["sweep", "--merge", &dir],
            vec!["2 of the 2 cases", "no record yet", "--shard K/N"],
        ),
        (vec!["sweep", "--merge", &empty], vec!["holds no plan.yaml"]),
        (
            vec!["sweep", "--plan", &empty, "--shard", "1/1"],
            vec!["holds no plan.yaml"],
        ),
        (
            vec!["sweep", "--plan", &dir],
            vec!["sweep needs a scene file"],
        ),
        (vec!["sweep", p, "--plan", &dir], vec!["at least one --set"]),
    ] {
        let (code, err) = rollbeam(&args);
        assert_eq!(code, 1, "{args:?}: exit {code}, {err}");
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        for n in &needles {
            assert!(err.contains(n), "{args:?}: '{n}' missing from {err}");
        }
    }
    // A planned case carries its solver settings.
    let case = std::fs::read_dir(format!("{dir}/cases"))
        .expect("cases")
        .next()
        .expect("a case")
        .expect("entry")
        .path();
    let (code, err) = rollbeam(&["run", case.to_str().expect("utf-8"), "--rtol", "1e-3"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("carries its solver settings"), "{err}");
    // A plan edited to point outside its folder is refused before anything runs.
    let plan = std::fs::read_to_string(format!("{dir}/plan.yaml")).expect("plan");
    let first = plan
        .lines()
        .find(|l| l.starts_with("- 0"))
        .expect("a case id");
    std::fs::write(
        format!("{dir}/plan.yaml"),
        plan.replace(first, "- ../../../../tmp/evil"),
    )
    .expect("write");
    let (code, err) = rollbeam(&["sweep", "--plan", &dir, "--shard", "1/1"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("'../../../../tmp/evil'") && err.contains("not a case id"),
        "{err}"
    );
    assert!(std::fs::read_dir(format!("{dir}/done"))
        .expect("done")
        .next()
        .is_none());
}

/// `tradeoff`: settings a scene cannot take are one sentence and exit 1, before any run; a
/// good one writes its table, figure and the cheapest settings.
#[test]
fn tradeoff_settings() {
    let path = scene_path("tradeoff", &format!("duration: 0.5\n{PARABOLA}{GOOD_DISK}"));
    let p = path.to_str().expect("utf-8 path");
    let out = format!("{p}.tradeoff");
    let beam_path = scene_path("tradeoff-beam", &beam_scene(&[], ""));
    let beam = beam_path.to_str().expect("utf-8 path").to_string();
    for (args, needles) in [
        (
            vec!["--methods", "genalpha"],
            vec!["genalpha", "rigid curve"],
        ),
        (
            vec!["--methods", "euler"],
            vec!["--methods 'euler' is unknown"],
        ),
        (vec!["--rtols", "1e-3,-1"], vec!["--rtols", "positive"]),
        (vec!["--elements", "4"], vec!["--elements", "rigid curve"]),
        (vec!["--orders", "4"], vec!["--orders", "rigid curve"]),
        (vec!["--max-steps", "0"], vec!["--max-steps", "at least 1"]),
        (
            vec!["beam", "--orders", "0"],
            vec!["--orders 0", "from 1 to 10"],
        ),
        (
            vec!["beam", "--orders", "2,11"],
            vec!["--orders 11", "from 1 to 10"],
        ),
        (
            vec!["--point", "esdirk4:1e-4:20:6"],
            vec!["--point", "rigid curve"],
        ),
        (
            vec!["beam", "--point", "esdirk4:1e-4:20"],
            vec!["--point", "METHOD:RTOL:ELEMENTS:DEGREE"],
        ),
        (
            vec!["beam", "--point", "rk45:1e-4:20:6"],
            vec!["--point's method 'rk45' is unknown"],
        ),
        (
            vec!["beam", "--point", "esdirk4:tight:20:6"],
            vec!["--point", "'tight' is not a number"],
        ),
        (
            vec!["beam", "--point", "esdirk4:-1e-4:20:6"],
            vec!["--point's rtol", "positive"],
        ),
        (
            vec!["beam", "--point", "esdirk4:1e-4:100000000000000000000:6"],
            vec!["--point", "from 1 to 1000"],
        ),
        (
            vec!["beam", "--point", "esdirk4:1e-4:20:11"],
            vec!["--point", "from 1 to 10"],
        ),
    ] {
        // "beam" asks for the same flags on a beam scene.
        let (scene, args) = match args.split_first() {
            Some((&"beam", rest)) => (beam.as_str(), rest.to_vec()),
            _ => (p, args),
        };
        let mut all = vec!["tradeoff", scene, "--out", &out];
        all.extend(&args);
        let (code, err) = rollbeam(&all);
        assert_eq!(code, 1, "{args:?}: exit {code}, {err}");
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        for n in needles {
            assert!(err.contains(n), "{args:?}: '{n}' missing from {err}");
        }
    }
    let (code, err) = rollbeam(&["tradeoff", p, "--out", &out, "--rtols", "1e-3,1e-5"]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(format!("{out}/tradeoff.csv")).expect("tradeoff.csv");
    assert_eq!(csv.lines().count(), 1 + 3 * 2);
    assert!(std::path::Path::new(&format!("{out}/tradeoff.svg")).exists());
    let txt = std::fs::read_to_string(format!("{out}/tradeoff.txt")).expect("tradeoff.txt");
    assert!(txt.contains("reference: dopri5") && txt.contains("1e-2:"));
}

/// `solver.accuracy`: a relative error, positive and below one half, for beams only.
#[test]
fn bad_accuracy() {
    for (value, needle) in [("-1e-3", "must be positive"), ("0.7", "below 0.5")] {
        rejected(
            &format!("accuracy{value}"),
            &beam_scene(&[], &format!("solver:\n  accuracy: {value}\n")),
            &["solver.accuracy", needle],
        );
    }
    rejected(
        "accuracy-on-a-curve",
        &format!("duration: 1\n{PARABOLA}{GOOD_DISK}solver:\n  accuracy: 1e-3\n"),
        &["solver.accuracy", "rigid curve"],
    );
}

/// A beam for vehicles, and one vehicle whose parts `car` edits.
const VEHICLE_BEAM: &str = "track:
  beam:
    from: [0.0, 0.0]
    to: [25.0, 0.0]
    E: 2.87e9
    G: 1.0e12
    rho: 2.303
    A: 1000.0
    Av: 1000.0
    I: 2.9
    supports: {from: pinned, to: roller}
";

fn car(edit: impl Fn(String) -> String) -> String {
    let text = "vehicles:
  - name: car
    speed: 20.0
    bodies: [{name: body, mass: 1000.0, inertia: 500.0, x: 1.0}]
    axles: [{name: a1, x: 0.0}, {name: a2, x: 3.0}]
    springs:
      - {upper: body, lower: a1, x: 0.0, k: 1.0e6}
      - {upper: body, lower: a2, x: 3.0, k: 1.0e6}
"
    .to_string();
    format!("duration: 0.1\n{VEHICLE_BEAM}{}", edit(text))
}

/// Vehicles and their profile: one sentence naming the line and key for each flaw.
#[test]
fn vehicles_refused_with_one_sentence() {
    let cases: [(&str, String, &[&str]); 17] = [
        ("unknown-part", car(|t| t.replace("lower: a2", "lower: a9")), &["vehicles.springs.lower", "a9", "names no body or axle"]),
        ("duplicate-name", car(|t| t.replace("name: a2", "name: body")), &["vehicles.axles.name", "names two parts"]),
        ("negative-mass", car(|t| t.replace("mass: 1000.0", "mass: -1000.0")), &["vehicles.bodies.mass", "positive"]),
        ("negative-k", car(|t| t.replace("k: 1.0e6}\n      - {upper: body, lower: a2", "k: -1.0e6}\n      - {upper: body, lower: a2")), &["vehicles.springs.k", "positive"]),
        ("axles-decreasing", car(|t| t.replace("x: 3.0}]", "x: -3.0}]").replace("a2, x: 3.0", "a2, x: -3.0")), &["vehicles.axles.x", "increasing"]),
        ("not-resting", car(|t| t.replace("x: 1.0}]", "x: 9.0}]")), &["does not rest on its axles"]),
        ("loose-body", car(|t| t.replace("bodies: [", "bodies: [{name: cargo, mass: 10.0}, ")), &["cargo", "joined to no axle"]),
        ("spring-off-axle", car(|t| t.replace("lower: a2, x: 3.0", "lower: a2, x: 2.0")), &["vehicles.springs.x", "not where axle"]),
        ("no-axle", car(|t| t.replace("axles: [{name: a1, x: 0.0}, {name: a2, x: 3.0}]", "axles: []")), &["vehicles.axles", "no axle"]),
        ("rigid-spring", car(|t| t.replace("k: 1.0e6}\n      - {upper: body, lower: a2", "k: 1.0e22}\n      - {upper: body, lower: a2")), &["vehicles", "car", "ring on their springs", "1e6 Hz", "soften the stiffest spring"]),
        ("no-inertia", car(|t| t.replace("inertia: 500.0", "inertia: 1.0e-16")), &["vehicles", "car", "ring on their springs", "1e6 Hz"]),
        ("disk-wheel", car(|t| t.replace("speed: 20.0", "speed: 20.0\n    wheel: disk")), &["vehicles.wheel", "radius"]),
        ("profile-decreasing", car(|t| t) .replace("    supports: {from: pinned, to: roller}\n", "    supports: {from: pinned, to: roller}\n  profile:\n    points: [[0.0, 0.0], [-1.0, 0.01]]\n"), &["track.profile.points", "increasing"]),
        ("profile-nan", car(|t| t).replace("    supports: {from: pinned, to: roller}\n", "    supports: {from: pinned, to: roller}\n  profile:\n    points: [[0.0, .nan]]\n"), &["track.profile.points", "finite"]),
        ("iso-class", car(|t| t).replace("    supports: {from: pinned, to: roller}\n", "    supports: {from: pinned, to: roller}\n  profile:\n    iso8608: {class: Z}\n"), &["track.profile.iso8608.class", "A to H"]),
        ("vehicles-on-curve", format!("duration: 1\n{PARABOLA}{}", car(|t| t).split_once("    supports: {from: pinned, to: roller}\n").expect("split").1), &["vehicles", "beam tracks only"]),
        ("disk-flies-beside", car(|t| format!("disk: {{mass: 100, radius: 0.2, s0: 1.0, omega0: -10, contact_loss: fly}}\n{t}")), &["disk.contact_loss", "does not beside vehicles", "contact_loss: stop"]),
    ];
    for (name, text, needles) in cases {
        rejected(name, &text, needles);
    }
}

/// Several disks: each is checked as `disk` is and named by its place in the list; `disk` and
/// `disks` together, an empty list, the thesis coupling among several, and a list on a rigid
/// curve or beside a train are refused with the reason.
#[test]
fn bad_disk_lists() {
    let one = "{mass: 100, radius: 0.2, s0: 1.0, omega0: -10}";
    rejected(
        "disks-second-bad",
        &beam_scene(
            &[],
            &format!("disks:\n  - {one}\n  - {{mass: -1, radius: 0.2, s0: 2.0}}\n"),
        ),
        &["`disks[2].mass` must be positive"],
    );
    rejected(
        "disks-off-beam",
        &beam_scene(
            &[],
            &format!("disks:\n  - {one}\n  - {{mass: 1, radius: 0.2, s0: 9.0}}\n"),
        ),
        &["disks[2].s0", "off the beam"],
    );
    rejected(
        "disk-and-disks",
        &beam_scene(&[], &format!("disk: {one}\ndisks: [{one}]\n")),
        &["`disk`", "`disks` are both given"],
    );
    rejected(
        "disks-empty",
        &beam_scene(&[], "disks: []\n"),
        &["`disks`", "1 to 100 disks"],
    );
    rejected(
        "disks-thesis",
        &beam_scene(
            &[],
            &format!(
                "disks:\n  - {one}\n  - {{mass: 100, radius: 0.2, s0: 2.0, omega0: -10, coupling: thesis}}\n"
            ),
        ),
        &["disks[2].coupling", "one disk"],
    );
    rejected(
        "disks-on-curve",
        &format!("duration: 1\n{PARABOLA}disks: [{one}]\n"),
        &["`disks`", "beam tracks only"],
    );
}

/// A listed disk's keys are swept as `disks.<k>.<field>`, k from 1 as errors name it: a k
/// the list does not hold, or a field a disk does not have, is one sentence and exit 1; a
/// number and a name are set on that disk alone.
#[test]
fn sweep_keys_of_listed_disks() {
    let one = "{mass: 100, radius: 0.2, s0: 1.0, omega0: -10, coupling: moving-force}";
    let path = scene_path(
        "sweep-disks",
        &beam_scene(&[], &format!("disks:\n  - {one}\n  - {one}\n")),
    );
    let p = path.to_str().expect("utf-8 path");
    let out = format!("{p}.sweep");
    for (set, needles) in [
        (
            "disks.3.s0=1:2:2",
            vec!["`disks.3.s0`", "k from 1 to the 2 disks"],
        ),
        (
            "disks.0.s0=1:2:2",
            vec!["`disks.0.s0`", "k from 1 to the 2 disks"],
        ),
        (
            "disks.2.nothing=1:2:2",
            vec!["`disks.2.nothing`", "not a number"],
        ),
    ] {
        let (code, err) = rollbeam(&["sweep", p, "--set", set, "--out", &out]);
        assert_eq!(code, 1, "{set}: exit {code}, {err}");
        assert_eq!(err.trim().lines().count(), 1, "{set}: {err}");
        for n in needles {
            assert!(err.contains(n), "{set}: '{n}' missing from {err}");
        }
    }
    let (code, err) = rollbeam(&[
        "sweep",
        p,
        "--set",
        "disks.2.s0=2:3:2",
        "--set",
        "disks.2.coupling=moving-mass",
        "--out",
        &out,
    ]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(format!("{out}/sweep.csv")).expect("sweep.csv");
    assert!(
        csv.starts_with("disks.2.s0,disks.2.coupling,status"),
        "{csv}"
    );
    // Each listed disk has its columns, named as in history.csv.
    assert!(
        csv.lines().next().is_some_and(|header| header.contains(
            ",disk1.rn_min,disk1.rn_max,disk1.left_track_t,disk2.rn_min,disk2.rn_max,disk2.left_track_t"
        )),
        "{csv}"
    );
    assert_eq!(
        csv.lines().filter(|l| l.contains(",ok,")).count(),
        2,
        "{csv}"
    );
}

/// Names that read as numbers (`nan`, `inf`) at a key of names, beside a second setting (which
/// lets each case fail alone): the one-shot sweep and the planned one each run, record both
/// cases as failed with the key named, and write the values quoted, as the names they are.
/// The table's check for non-finite numbers took an unquoted `nan` for one and refused the
/// whole table; a shard stopped at the first such case and the plan could not be merged.
#[test]
fn a_sweep_over_names_that_read_as_numbers_fails_case_by_case() {
    let path = scene_path(
        "named",
        &beam_scene(&[], "disk:\n  mass: 10\n  radius: 0.1\n  s0: 1\n"),
    );
    let p = path.to_str().expect("utf-8 path");
    let (out, dir, merged) = (
        format!("{p}.out"),
        format!("{p}.plan"),
        format!("{p}.merged"),
    );
    let _ = std::fs::remove_dir_all(&dir);
    let sets = ["--set", "disk.mass=10", "--set", "disk.coupling=nan,inf"];
    let steps: [Vec<&str>; 4] = [
        [&["sweep", p][..], &sets, &["--out", &out]].concat(),
        [&["sweep", p][..], &sets, &["--plan", &dir]].concat(),
        vec!["sweep", "--plan", &dir, "--shard", "1/1"],
        vec!["sweep", "--merge", &dir, "--out", &merged],
    ];
    for args in &steps {
        let (code, err) = rollbeam(args);
        assert_eq!(code, 0, "{args:?}: {err}");
    }
    for folder in [&out, &merged] {
        let csv = std::fs::read_to_string(format!("{folder}/sweep.csv")).expect("sweep.csv");
        let rows: Vec<&str> = csv.lines().skip(1).collect();
        assert_eq!(rows.len(), 2, "{csv}");
        for (row, name) in rows.iter().zip(["nan", "inf"]) {
            assert!(
                row.starts_with(&format!("10,\"{name}\",\"failed: ")),
                "{row}"
            );
            assert!(row.contains("`disk.coupling` is"), "{row}");
        }
    }
}

//! A bounded, deterministic property test of reading, planning and `check`: scenes
//! made by mutating every study scene (a value replaced by a hostile one, a line dropped or
//! repeated, text spliced in) must each end, within a time bound, either accepted with every
//! number the model derives finite, or refused with one sentence that names where (a line or
//! a key). Never a panic. The cases are drawn from a fixed seed, so a failure reproduces.

use std::cell::Cell;
use std::time::{Duration, Instant};

use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

use rollbeam::commands::check::Described;
use rollbeam::plan::Planner;
use rollbeam::scene::{Model, SceneSpec};

/// Cases per run: about two seconds of the suite's time.
const CASES: u32 = 3000;
/// One case (read, plan, describe) taking longer than this is a hang: the slowest plan (a
/// mesh choice at the finest accuracy) takes about three seconds.
const BOUND: Duration = Duration::from_secs(8);

const SEEDS: [&str; 12] = [
    include_str!("parabola-p1.yaml"),
    include_str!("parabola-p3.yaml"),
    include_str!("beam-b1.yaml"),
    include_str!("beam-b3.yaml"),
    include_str!("cantilever-c2.yaml"),
    include_str!("bridge-d44.yaml"),
    include_str!("bridge-d50.yaml"),
    include_str!("rubber.yaml"),
    include_str!("zipline.yaml"),
    include_str!("parabola-p4.yaml"),
    include_str!("hslm-15m.yaml"),
    include_str!("jump.yaml"),
];

/// Values a hostile user types where a number or a name belongs.
const HOSTILE: [&str; 32] = [
    "0",
    "-1",
    "1e-300",
    "1e300",
    "-1e300",
    "1e308",
    "5e-324",
    ".nan",
    ".inf",
    "-.inf",
    "8.0",
    "99999999999999999999",
    "-0",
    "0.5",
    "1e-12",
    "10",
    "null",
    "~",
    "\"\"",
    "[]",
    "{}",
    "[1, 2, 3]",
    "\"../../x\"",
    "\"a\\nb\"",
    "&a 1",
    "*a",
    "!!str 1",
    "yes",
    "\"s^s^s^s\"",
    "\"((((s))))\"",
    "[[0, 0], [1, 0.1], [2, 0.1], [3, 0]]",
    "1e-3",
];

/// One mutation of a seed scene, by line.
fn mutate(seed: &str, line: usize, how: u8, pick: usize) -> String {
    let mut lines: Vec<String> = seed.lines().map(str::to_string).collect();
    let k = line % lines.len();
    let value = HOSTILE[pick % HOSTILE.len()];
    match how % 5 {
        // Replace the value after the first `key:` on the line.
        0 => {
            if let Some(i) = lines[k].find(": ") {
                lines[k] = format!("{}: {value}", &lines[k][..i]);
            }
        }
        // Replace a number inside a flow mapping or sequence.
        1 => {
            let l = &lines[k];
            if let Some(i) = l.find(|c: char| c.is_ascii_digit()) {
                let end = l[i..]
                    .find(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '-'))
                    .map_or(l.len(), |e| i + e);
                lines[k] = format!("{}{value}{}", &l[..i], &l[end..]);
            }
        }
        2 => {
            lines.remove(k);
        }
        3 => {
            let copy = lines[k].clone();
            lines.insert(k, copy);
        }
        _ => {
            let at = pick % (lines[k].len() + 1);
            if lines[k].is_char_boundary(at) {
                lines[k].insert_str(at, value);
            }
        }
    }
    lines.join("\n") + "\n"
}

/// Every number the planned model derives, for the finiteness check.
fn derived_numbers(scene: &rollbeam::scene::Scene) -> Vec<f64> {
    let mut v = vec![
        scene.duration,
        scene.interval,
        scene.solver.rtol,
        scene.solver.atol,
    ];
    match &scene.model {
        Model::Rolling(r) => {
            let d = &r.rolling.disk;
            v.extend([d.mass, d.radius, d.inertia(), d.rolling_mass()]);
        }
        Model::Beam(b) => {
            let s = &b.beam.section;
            v.extend([s.ea, s.gav, s.ei, s.rho_a, s.rho_i, b.accuracy]);
            v.extend(b.beam.from.iter().chain(&b.beam.to));
            v.extend(
                b.loads
                    .iter()
                    .flat_map(|l| [l.x, l.force[0], l.force[1], l.mz]),
            );
            if let Some(d) = b.disk() {
                v.extend([
                    d.disk.mass,
                    d.disk.radius,
                    d.disk.inertia(),
                    d.s0,
                    d.omega0,
                    d.patch,
                ]);
            }
        }
    }
    v
}

#[test]
fn mutated_scenes_are_accepted_finite_or_refused_in_one_sentence() {
    let config = Config {
        cases: CASES,
        failure_persistence: None,
        ..Config::default()
    };
    let mut runner =
        TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::ChaCha));
    let (accepted, refused) = (Cell::new(0u32), Cell::new(0u32));
    let strategy = (
        0..SEEDS.len(),
        0..64usize,
        any::<u8>(),
        0..4096usize,
        0..3usize,
    );
    let result = runner.run(&strategy, |(seed, line, how, pick, rounds)| {
        let mut text = SEEDS[seed].to_string();
        for r in 0..=rounds {
            text = mutate(
                &text,
                line + 7 * r,
                how.wrapping_add(r as u8),
                pick + 13 * r,
            );
        }
        let started = Instant::now();
        let spec = SceneSpec::parse(&text, "fuzz.yaml", "fuzz");
        let outcome = spec
            .as_ref()
            .map_err(|e| rollbeam::error::Error::Input(e.to_string()))
            .and_then(|spec| Planner::default().plan(spec));
        match outcome {
            Ok(scene) => {
                // Written back as a scene file (a planned sweep's case, a pickled Python
                // scene), it reads back to the same scene.
                let spec = spec.as_ref().expect("planned, so read");
                let written = spec.to_yaml().expect("an accepted scene writes");
                let again = SceneSpec::parse(&written, "again.yaml", "fuzz");
                prop_assert!(again.is_ok(), "{:?}\n{}", again.err(), written);
                let again = again.expect("checked above");
                prop_assert_eq!(again.to_yaml().expect("writes"), written.clone());
                let described = |s: &SceneSpec| s.check().map(|c| Described(&c.scene).to_string());
                prop_assert_eq!(described(&again).ok(), described(spec).ok(), "{}", written);
                let numbers = derived_numbers(&scene);
                prop_assert!(numbers.iter().all(|x| x.is_finite()), "{numbers:?}\n{text}");
                let printed = Described(&scene).to_string();
                let non_finite = printed
                    .split(|c: char| c.is_whitespace() || ",;:()[]".contains(c))
                    .any(|t| ["inf", "-inf", "NaN"].contains(&t));
                prop_assert!(!non_finite, "{}", printed);
                accepted.set(accepted.get() + 1);
            }
            Err(e) => {
                let m = e.to_string();
                prop_assert_eq!(m.lines().count(), 1, "not one line: {}\n{}", m, text);
                prop_assert!(
                    m.contains('`') || m.contains("line "),
                    "names no key or line: {}",
                    m
                );
                prop_assert!(m.len() < 600, "{} bytes: {}", m.len(), m);
                refused.set(refused.get() + 1);
            }
        }
        prop_assert!(
            started.elapsed() < BOUND,
            "took {:?}:\n{}",
            started.elapsed(),
            text
        );
        Ok(())
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    // The mutations must exercise both outcomes, or the property says nothing.
    let (accepted, refused) = (accepted.get(), refused.get());
    assert!(
        accepted > CASES / 20 && refused > CASES / 4,
        "{accepted} accepted, {refused} refused"
    );
}

/// The fuzzing corpus under `fuzz/corpus` (the inputs the campaign kept, each reaching code
/// no other did), replayed through the two targets' properties, so that a change to reading,
/// planning or the curve formula that breaks one of them fails here, where `cargo fuzz` does
/// not run: a scene is accepted with a finite plan and a printout free of NaN, or refused in
/// one line under 600 bytes; a formula parses to a tree that evaluates, or is refused in one
/// line. Each within [`BOUND`].
#[test]
fn the_fuzzing_corpus_keeps_the_targets_properties() {
    let corpus = |target: &str| -> Vec<(String, String)> {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("fuzz/corpus")
            .join(target);
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|entry| entry.expect("a corpus entry").path())
            .collect();
        files.sort();
        files
            .into_iter()
            .filter_map(|path| {
                let bytes = std::fs::read(&path).expect("a corpus file");
                let text = String::from_utf8(bytes).ok()?;
                Some((path.display().to_string(), text))
            })
            .collect()
    };
    let scenes = corpus("scene");
    let mut accepted = 0;
    for (file, text) in &scenes {
        let started = Instant::now();
        let planned = SceneSpec::parse(text, "fuzz.yaml", "fuzz")
            .map_err(|e| rollbeam::error::Error::Input(e.to_string()))
            .and_then(|s| Planner::default().plan(&s));
        match planned {
            Ok(scene) => {
                assert!(
                    scene.duration.is_finite() && scene.solver.rtol < 1.0,
                    "{file}"
                );
                let printed = Described(&scene).to_string();
                assert!(!printed.contains("NaN"), "{file}: {printed}");
                accepted += 1;
            }
            Err(e) => {
                let m = e.to_string();
                assert_eq!(m.lines().count(), 1, "{file}: {m}");
                assert!(m.len() < 600, "{file}: {m}");
            }
        }
        assert!(
            started.elapsed() < BOUND,
            "{file} took {:?}",
            started.elapsed()
        );
    }
    let formulas = corpus("formula");
    for (file, text) in &formulas {
        match rollbeam::curve::expr::Formula::parse(text) {
            Ok(f) => {
                for s in [-1.5, 0.0, 0.3, 2.0] {
                    let _ = f.eval(s);
                }
            }
            Err(m) => assert_eq!(m.lines().count(), 1, "{file}: {m}"),
        }
    }
    // A corpus that no longer reaches the planner, or was lost, tests nothing.
    assert!(
        accepted > 100 && scenes.len() > 1000 && formulas.len() > 100,
        "{accepted} of {} scenes accepted, {} formulas",
        scenes.len(),
        formulas.len()
    );
}

//! The documents stay true: the scene README.md's first screen shows reads, plans and runs, and
//! every figure REPORT.md shows exists.

use std::path::Path;

use rollbeam::run::{self, Overrides};
use rollbeam::scene::Scene;

fn read(file: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(file))
        .unwrap_or_else(|e| panic!("{file}: {e}"))
}

/// The first ```yaml block of README.md is a scene that runs to its end, with its train's
/// residual vibration reported (the first screen says it is), and the probe's range the
/// printout beside it shows is the run's, to the digits printed.
#[test]
fn the_readme_scene_runs() {
    let readme = read("README.md");
    let start = readme.find("```yaml\n").expect("a yaml block") + "```yaml\n".len();
    let text = &readme[start..start + readme[start..].find("```").expect("its end")];
    let scene = Scene::parse(text, "README.md", "bridge").expect("the README's scene is valid");
    let r = run::run(&scene, &Overrides::default(), false)
        .expect("it runs")
        .beam()
        .expect("a beam scene");
    assert_eq!(r.header.stop.name(), "end");
    assert!(r.amplitude_after_exit(0).is_some_and(|a| a > 0.0));
    let w = &r.extremes.probes[0][1];
    let printed = format!("w from {:.6e} to {:.6e} m", w.min, w.max);
    assert!(
        readme.contains(&printed),
        "README.md's printout does not show the run's `{printed}`"
    );
}

/// The README's vehicle, put in the first scene in place of its train as the README says,
/// crosses the deck and reports its body's largest acceleration.
#[test]
fn the_readme_vehicle_replaces_the_train() {
    let readme = read("README.md");
    let blocks: Vec<&str> = readme
        .split("```yaml\n")
        .skip(1)
        .map(|b| &b[..b.find("```").expect("its end")])
        .collect();
    let (scene, vehicle) = (blocks[0], blocks[1]);
    let train = scene
        .lines()
        .find(|l| l.starts_with("train:"))
        .expect("the first scene's train");
    let text = scene.replace(&format!("{train}\n"), vehicle);
    let scene = Scene::parse(&text, "README.md", "bridge").expect("the vehicle scene is valid");
    let r = run::run(&scene, &Overrides::default(), false)
        .expect("it runs")
        .beam()
        .expect("a beam scene");
    assert_eq!(r.header.stop.name(), "end");
    assert!(r.vehicles[0].bodies[0].1.largest_magnitude().0 > 0.0);
}

/// Every image REPORT.md and README.md link, `](path.svg)` or `](path.png)`, is in the
/// repository.
#[test]
fn every_linked_figure_exists() {
    for doc in ["REPORT.md", "README.md"] {
        let text = read(doc);
        for (i, _) in text.match_indices("](") {
            let rest = &text[i + 2..];
            let Some(end) = rest.find(')') else { continue };
            let link = &rest[..end];
            if link.ends_with(".svg") || link.ends_with(".png") {
                let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(link);
                assert!(path.exists(), "{doc} links {link}, which is not there");
            }
        }
    }
}

/// The documents stay readable at the lengths they were cut to: README.md a front door of at
/// most 3 000 words, REPORT.md the conclusions in at most 12 000, the method notes in `docs/`
/// at most 6 000 (the scene-format reference beside them not counted); and no table cell or
/// line of prose in any of them longer than 400 characters, which a reader can no longer take
/// in as one statement. Words are counted as `wc -w` counts them.
#[test]
fn the_documents_keep_their_lengths() {
    let words = |text: &str| text.split_whitespace().count();
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs");
    let mut notes: Vec<String> = std::fs::read_dir(&docs)
        .expect("docs/ is readable")
        .map(|e| e.expect("an entry of docs/").path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .map(|p| format!("docs/{}", p.file_name().unwrap().to_string_lossy()))
        .collect();
    notes.sort();
    let method_notes: usize = notes
        .iter()
        .filter(|f| !f.ends_with("scene-format.md"))
        .map(|f| words(&read(f)))
        .sum();
    for (what, count, most) in [
        ("README.md", words(&read("README.md")), 3_000),
        ("REPORT.md", words(&read("REPORT.md")), 12_000),
        ("the method notes in docs/", method_notes, 6_000),
    ] {
        assert!(count <= most, "{what} has {count} words, past {most}");
    }
    for doc in ["README.md".to_string(), "REPORT.md".to_string()]
        .into_iter()
        .chain(notes)
    {
        for (i, line) in read(&doc).lines().enumerate() {
            let longest = if line.starts_with('|') {
                line.split('|')
                    .map(|c| c.chars().count())
                    .max()
                    .unwrap_or(0)
            } else {
                line.chars().count()
            };
            assert!(
                longest <= 400,
                "{doc}:{}: {longest} characters in one {}",
                i + 1,
                if line.starts_with('|') {
                    "table cell"
                } else {
                    "line"
                }
            );
        }
    }
}

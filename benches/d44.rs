//! D44 as a user would write it, with some of its keys left out: shared by the benches that
//! measure the defaults.

use std::path::Path;

use rollbeam::scene::Scene;

/// D44 with the lines that start with `keys` left out, as a user would write it.
pub fn d44_without(keys: &[&str]) -> Scene {
    d44_text_without(keys, 1.0)
}

/// The same, with the shear modulus multiplied by `shear`.
pub fn d44_text_without(keys: &[&str], shear: f64) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("studies/bridge-d44.yaml");
    let text = std::fs::read_to_string(&path)
        .expect("D44 is readable")
        .replace("G: 81.0e9", &format!("G: {:e}", 81.0e9 * shear));
    let kept: String = text
        .lines()
        .filter(|l| !keys.iter().any(|k| l.trim_start().starts_with(k)))
        .map(|l| {
            if l == "solver:" && keys.contains(&"method:") {
                "solver: {}"
            } else {
                l
            }
        })
        .map(|l| format!("{l}\n"))
        .collect();
    Scene::parse(&kept, "D44 with defaults", "bridge-d44").expect("D44 is valid")
}

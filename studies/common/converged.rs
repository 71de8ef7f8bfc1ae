//! Converged runs too long to repeat in every test run, stored in
//! `studies/references/converged/` with the hash of the study file each was made from: a
//! study edited since is refused with the command that makes its runs again, as the
//! work–precision store refuses a stale reference.

use std::path::PathBuf;

use rollbeam::workflows::tradeoff::store::scene_hash;

/// The file of the stored converged run `name`.
pub fn path(name: &str) -> PathBuf {
    super::studies_dir()
        .join("references/converged")
        .join(format!("{name}.yaml"))
}

/// The hash of study file `study` as it is now.
pub fn study_hash(study: &str) -> String {
    scene_hash(&super::studies_dir().join(study)).expect("the study file")
}

/// What every stored run holds besides its numbers.
#[derive(serde::Deserialize)]
struct Made {
    scene_hash: String,
}

/// The stored converged run `name`, made from `study` as it is now; `remake` names the
/// command that makes it again.
pub fn read<T: serde::de::DeserializeOwned>(name: &str, study: &str, remake: &str) -> T {
    let remake =
        format!("make it with `cargo test --release --test studies -- --ignored {remake}`");
    read_keyed(name, &study_hash(study), &remake)
}

/// The stored converged run `name`, made from what hashes to `hash` (a study file, or a
/// test's scene text with the converged run's settings); `remake` says how to make it again.
pub fn read_keyed<T: serde::de::DeserializeOwned>(name: &str, hash: &str, remake: &str) -> T {
    let path = path(name);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e}; {remake}", path.display()));
    let made: Made = serde_saphyr::from_str(&text).expect("a stored converged run");
    assert_eq!(
        made.scene_hash,
        hash,
        "{}: its scene changed since it was stored; {remake}",
        path.display()
    );
    serde_saphyr::from_str(&text).expect("a stored converged run")
}

/// Whether the tests that read converged runs keyed by their own scene text make them again
/// (and store them) instead: `ROLLBEAM_REMAKE_CONVERGED=1`.
pub fn remaking() -> bool {
    std::env::var_os("ROLLBEAM_REMAKE_CONVERGED").is_some_and(|v| v == "1")
}

/// Stores `value` (which carries its study's [`study_hash`]) as the converged run `name`.
pub fn write<T: serde::Serialize>(name: &str, value: &T) {
    let path = path(name);
    std::fs::create_dir_all(path.parent().expect("a folder")).expect("the folder");
    let text = serde_saphyr::to_string(value).expect("serialised");
    std::fs::write(&path, text).expect("written");
}

/// One converged number of a study (a windowed mean, a peak), as stored.
#[derive(serde::Serialize, serde::Deserialize)]
pub struct Number {
    converged_by: String,
    scene_hash: String,
    value: f64,
}

impl Number {
    /// The stored number `name` of study file `study`; `remake` names the test that makes it.
    pub fn stored(name: &str, study: &str, remake: &str) -> f64 {
        read::<Number>(name, study, remake).value
    }

    /// Stores `value` as the number `name` of study file `study`, converged as `converged_by`
    /// says.
    pub fn store(name: &str, study: &str, converged_by: String, value: f64) {
        let stored = Number {
            converged_by,
            scene_hash: study_hash(study),
            value,
        };
        write(name, &stored);
    }
}

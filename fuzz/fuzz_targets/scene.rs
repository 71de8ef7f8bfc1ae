//! Reading and planning a scene from arbitrary bytes: every input ends accepted with finite
//! derived numbers and a printable model, or refused with one sentence; never a panic, a stack
//! overflow or a run-away allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rollbeam::commands::check::Described;
use rollbeam::plan::Planner;
use rollbeam::scene::SceneSpec;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match SceneSpec::parse(text, "fuzz.yaml", "fuzz").and_then(|s| Planner::default().plan(&s)) {
        Ok(scene) => {
            assert!(scene.duration.is_finite() && scene.solver.rtol < 1.0);
            let printed = Described(&scene).to_string();
            assert!(!printed.contains("NaN"), "{printed}");
        }
        Err(e) => {
            let m = e.to_string();
            assert_eq!(m.lines().count(), 1, "{m}");
            assert!(m.len() < 600, "{m}");
        }
    }
});

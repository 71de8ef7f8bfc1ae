//! The curve formula parser and evaluator on arbitrary text: a tree or one sentence, and an
//! evaluation that returns (whatever its value) without overflowing the stack.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rollbeam::curve::expr::Formula;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match Formula::parse(text) {
        Ok(f) => {
            for s in [-1.5, 0.0, 0.3, 2.0] {
                let _ = f.eval(s);
            }
        }
        Err(m) => assert_eq!(m.lines().count(), 1, "{m}"),
    }
});

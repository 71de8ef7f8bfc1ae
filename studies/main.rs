//! The verification suite: one module per study or property, each reading like a paper's
//! verification section (what is compared, against what, and why that tolerance), and the
//! helpers they share in `common`. Run one module with `cargo test --release --test studies
//! <module>::`, e.g. `parabola::`.

mod common;

/// The allocator the command line runs with (`src/main.rs`), so that the suite times the runs
/// users get: with glibc's, malloc and free took a tenth of the heaviest tests.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

mod accuracy;
mod bad_input;
mod beam_element;
mod beam_models;
mod beams;
mod bridge_engineering;
mod discretisation;
mod disk_on_beam;
mod documents;
mod exact_modal;
mod extremes;
mod flight;
mod hostile;
mod parabola;
mod reader_properties;
mod tradeoff;
mod vehicles;

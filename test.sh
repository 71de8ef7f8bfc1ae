#!/usr/bin/env bash
# The whole verification suite: the Rust tests, then the Python package built from this
# checkout into a fresh virtual environment and its tests (which also run examples/).
set -euo pipefail
cd "$(dirname "$0")"
# Built without the release profile's whole-program optimisation, which would give every test
# binary and the Python extension a link-time pass of the whole program, doubling the build.
export CARGO_PROFILE_RELEASE_LTO=false
# The workspace, so that the features pyo3's macros ask of shared crates are resolved here too
# and the Python package below links the library built here (python/Cargo.toml).
cargo test --release --workspace
venv=target/python-venv
rm -rf "$venv"
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet "./python[test]"
ROLLBEAM_BIN="$PWD/target/release/rollbeam" "$venv/bin/python" -m pytest -q python/tests

#!/usr/bin/env bash
# The whole verification suite: the Rust tests, then the Python package built from this
# checkout into a fresh virtual environment and its tests (which also run examples/).
set -euo pipefail
cd "$(dirname "$0")"
cargo test --release
venv=target/python-venv
rm -rf "$venv"
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet "./python[test]"
ROLLBEAM_BIN="$PWD/target/release/rollbeam" "$venv/bin/python" -m pytest -q python/tests

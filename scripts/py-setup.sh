#!/usr/bin/env bash
# Build the Python package `frontier` into a virtualenv and install what its tests need.
#
#   scripts/py-setup.sh            # target/py-venv (FRONTIER_VENV=... for another place)
#   scripts/py-setup.sh --dev      # the dev profile, beside what `cargo test` built (CI)
#   target/py-venv/bin/pytest crates/py/tests
#
# maturin and the test requirements come from PyPI (crates/py/requirements-dev.txt).
# The extension is built once: in the release profile by default (the speed is the point
# of it), or with --dev in the workspace's dev profile, into target/debug beside what
# `cargo test` compiled. That reuses every crate `cargo test` built (crates/py asks for the
# features the tests' dev-dependencies turn on, so that none is built again): only PyO3,
# numpy, ndarray and the package crate are new (crates/py has no Rust tests). The tests
# run as fast on either build.
set -euo pipefail
cd "$(dirname "$0")/.."
profile=--release
case "${1:-}" in
    # `--profile dev`, not only no `--release`: maturin would take pyproject.toml's
    # `profile = "release"` and build in target/release.
    --dev) profile="--profile dev" ;;
    "") ;;
    *) echo "usage: $0 [--dev]" >&2; exit 2 ;;
esac
venv=${FRONTIER_VENV:-target/py-venv}
python=${PYTHON:-python3}
if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    -r crates/py/requirements-dev.txt
VIRTUAL_ENV="$(cd "$venv" && pwd)" PATH="$venv/bin:$PATH" \
    "$venv/bin/maturin" develop --quiet $profile --manifest-path crates/py/Cargo.toml
"$venv/bin/python" -c 'import frontier; print("frontier", frontier.__version__, "installed in '"$venv"'")'

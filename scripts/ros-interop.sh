#!/usr/bin/env bash
# frontier-ros against another vendor's DDS: Eclipse Cyclone DDS (rmw_cyclonedds_cpp's),
# through its Python binding from PyPI (the wheel carries the C library; no ROS needed).
#
#   scripts/ros-interop.sh          # builds crates/ros in release, runs scripts/ros-interop.py
#                                   # twice: Nav2's action (Cyclone's service mapping), publish-only
#
# The binding goes into target/ros-interop-venv (FRONTIER_INTEROP_VENV=... for another place).
# The DDS domain is 150–199 (one per process), away from the default 0.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=${FRONTIER_INTEROP_VENV:-target/ros-interop-venv}
python=${PYTHON:-python3}
if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "cyclonedds==11.0.1"
cargo build --release --quiet --manifest-path crates/ros/Cargo.toml
for mode in action publish-only; do
    echo "== --mode $mode"
    "$venv/bin/python" scripts/ros-interop.py --node crates/ros/target/release/frontier-ros \
        --mode "$mode" "$@"
done

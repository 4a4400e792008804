#!/usr/bin/env bash
# frontier-ros against the two DDS vendors ROS 2 ships RMWs for: Eclipse Cyclone DDS
# (rmw_cyclonedds_cpp; its Python binding from PyPI, the C library in the wheel) and
# eProsima Fast DDS (rmw_fastrtps_cpp, the default RMW; Debian's libfastrtps and fastddsgen).
# No ROS installation is needed. See crates/ros/interop/interop.py.
#
#   scripts/ros-interop.sh          # each DDS: Nav2's action, publish-only, the pose from TF,
#                                   # the node in /robot1 with remapping rules (one run
#                                   # each); and a Humble Nav2 on Cyclone: 9 runs, ~45 s
#
# Installs what is missing: Debian's Fast DDS packages (apt-get, as root or through sudo),
# the Cyclone binding into target/ros-interop/venv; builds the node (release) and the Fast
# DDS peer into target/ros-interop. Each run uses a DDS domain of 150–199.
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/ros-interop
mkdir -p "$out"
if ! command -v fastddsgen > /dev/null || [ ! -d /usr/include/fastdds ]; then
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo=sudo
    $sudo apt-get install -y --no-install-recommends libfastrtps-dev libfastcdr-dev fastddsgen g++
fi
venv=$out/venv
[ -x "$venv/bin/python" ] || "${PYTHON:-python3}" -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "cyclonedds==11.0.1"
cargo build --release --quiet --manifest-path crates/ros/Cargo.toml
# The Fast DDS peer: ROS 2's types from ros2.idl through fastddsgen, then one g++ call.
if [ ! -x "$out/fastdds_peer" ] || [ crates/ros/interop/fastdds_peer.cpp -nt "$out/fastdds_peer" ] \
    || [ crates/ros/interop/ros2.idl -nt "$out/fastdds_peer" ]; then
    mkdir -p "$out/gen"
    fastddsgen -replace -d "$out/gen" crates/ros/interop/ros2.idl > /dev/null
    g++ -std=c++17 -O1 -I"$out/gen" crates/ros/interop/fastdds_peer.cpp "$out/gen/ros2.cxx" \
        "$out/gen/ros2PubSubTypes.cxx" -lfastrtps -lfastcdr -o "$out/fastdds_peer"
fi
for dds in cyclone fastdds; do
    for run in "--mode action" "--mode publish-only" "--mode action --pose tf"; do
        echo "== $dds, $run"
        # shellcheck disable=SC2086 # $run is two or four words
        "$venv/bin/python" crates/ros/interop/interop.py --dds "$dds" $run \
            --node crates/ros/target/release/frontier-ros --fastdds-peer "$out/fastdds_peer" "$@"
    done
done
# A launch file's namespace and remaps: Nav2's action with the pose on Cyclone, from TF on
# Fast DDS.
for run in "cyclone --mode action" "fastdds --mode action --pose tf"; do
    echo "== ${run%% *}, ${run#* } --namespaced"
    # shellcheck disable=SC2086 # $run is three or five words
    "$venv/bin/python" crates/ros/interop/interop.py --dds $run --namespaced \
        --node crates/ros/target/release/frontier-ros --fastdds-peer "$out/fastdds_peer" "$@"
done
echo "== cyclone, --mode action --nav2 humble"
"$venv/bin/python" crates/ros/interop/interop.py --dds cyclone --mode action --nav2 humble \
    --node crates/ros/target/release/frontier-ros "$@"

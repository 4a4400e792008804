#!/usr/bin/env python3
"""Time every team preset on one map and check the team goals, as docs/teams.md does.

    cargo build --release -p frontier
    scripts/teams-table.py                          # willow-full, 5 robots, 2 series
    scripts/teams-table.py --map maps/depot.yaml --runs 1 --presets cf,minpos,ha-cc

Each run is `frontier explore --json` with Holz et al.'s laser set-up (`--sensor
lidar:r=8,fov=180,res=1 --belief reflection --clearance 0.3`), seed 0, on one core
(RAYON_NUM_THREADS=1), in a process of its own. A series runs every preset once, the
single-robot `cf` yardstick first; the series follow one another, so that the machine's
drift (up to 1.5x within an hour on the development machine) touches every preset alike
and a ratio to the same series' `cf` is its least noisy figure. Prints, as Markdown, the
table of docs/teams.md (ranges over the series) and the goals: every preset within 10 s,
`greedy`, `nearest`, `minpos` and the RFE and AF presets within 3 s, a robot-decision
within 5 times a `cf` decision. Only the Python standard library is needed.
"""
import argparse
import json
import os
import subprocess
import sys

# The team presets in docs/teams.md's order.
TEAM = ["greedy", "greedy-utility", "nearest", "minpos", "nearest-af", "nearest-rfe",
        "greedy-utility-af", "greedy-utility-rfe", "minpos-af", "minpos-rfe", "ia-af",
        "ia-rfe", "ha-af", "ha-rfe", "ga-af", "ga-rfe", "sga-af", "sga-rfe", "ha-centroids",
        "ga-cc", "ia-cc", "ha-cc", "sga-cc", "ma-rfe", "ma-cc", "ma-af"]
YARDSTICK = "cf"
# The goals of the team issue: wall time of a whole run, and a robot-decision against `cf`'s.
ALL_WITHIN_S = 10.0
FAST_WITHIN_S = 3.0
PER_DECISION_TIMES = 5.0


def fast_group(preset):
    """Whether `preset` has the 3 s goal: the coordination study's `minpos`, `greedy`,
    `nearest` and every RFE and AF preset."""
    return preset in ("minpos", "greedy", "nearest") or preset.endswith(("-rfe", "-af"))


def run(binary, preset, args):
    """One whole run of `preset`: (total s, decide s, sense s, robot-decisions)."""
    robots = "1" if preset == YARDSTICK else str(args.robots)
    cmd = [binary, "explore", "--map", args.map, "--robots", robots, "--strategy", preset,
           "--sensor", args.sensor, "--belief", "reflection", "--clearance", "0.3",
           "--seed", "0", "--json"]
    if args.resolution:
        cmd += ["--resolution", args.resolution]
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    done = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if done.returncode != 0:
        sys.exit(f"{' '.join(cmd)}: exit {done.returncode}\n{done.stderr.strip()}")
    out = json.loads(done.stdout)
    t = out["timing_ms"]
    if not out.get("complete", True):
        print(f"warning: {preset} did not explore everything ({out.get('reason')})",
              file=sys.stderr)
    return t["total"] / 1e3, t["decide"] / 1e3, t["sense"] / 1e3, out["decisions"]


def span(values, fmt):
    """`lo–hi` of `values` in `fmt`, one figure when they print alike."""
    lo, hi = fmt.format(min(values)), fmt.format(max(values))
    return lo if lo == hi else f"{lo}–{hi}"


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--map", default="maps/willow-full.yaml", help="map file (any the CLI reads)")
    p.add_argument("--resolution", default=None, help="metres per cell, for maps without one")
    p.add_argument("--robots", type=int, default=5, help="team size")
    p.add_argument("--sensor", default="lidar:r=8,fov=180,res=1", help="sensor spec")
    p.add_argument("--runs", type=int, default=2, help="series (each runs every preset once)")
    p.add_argument("--presets", default=None, help="comma-separated team presets (default: all)")
    p.add_argument("--bin", default=None, help="frontier binary (default: target/release/frontier)")
    args = p.parse_args()
    if args.runs < 1 or args.robots < 1:
        p.error("--runs and --robots: expected at least 1")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    binary = args.bin or os.path.join(root, "target", "release", "frontier")
    if not os.access(binary, os.X_OK):
        p.error(f"--bin: expected an executable frontier binary, found none at {binary} "
                "(cargo build --release -p frontier)")
    presets = TEAM if args.presets is None else [s for s in args.presets.split(",") if s]
    presets = [s for s in presets if s != YARDSTICK]
    order = [YARDSTICK] + presets
    got = {s: [] for s in order}
    for series in range(args.runs):
        for s in order:
            got[s].append(run(binary, s, args))
            total = got[s][-1][0]
            print(f"series {series + 1}/{args.runs}: {s} {total:.2f} s", file=sys.stderr)
    # a robot-decision's deciding time against the same series' `cf` decision
    cf_per = [d / max(n, 1) for (_, d, _, n) in got[YARDSTICK]]
    print(f"{args.map}, {args.robots} robots, --sensor {args.sensor} --belief reflection "
          f"--clearance 0.3, seed 0, one core, {args.runs} series\n")
    print("| preset | total | ×`cf` | decide | sense | robot-decisions "
          "| decide / robot-decision (×`cf`) |")
    print("|---|---|---|---|---|---|---|")
    over_all, over_fast, over_ratio = [], [], []
    for s in order:
        rows = got[s]
        totals = [r[0] for r in rows]
        per = [r[1] / max(r[3], 1) for r in rows]
        ratio = [x / c for x, c in zip(per, cf_per)]
        times_cf = [r[0] / c[0] for r, c in zip(rows, got[YARDSTICK])]
        name = f"`{s}` (1 robot)" if s == YARDSTICK else f"`{s}`"
        print(f"| {name} | {span(totals, '{:.2f}')} s | {span(times_cf, '{:.1f}')} "
              f"| {span([r[1] for r in rows], '{:.2f}')} s | {span([r[2] for r in rows], '{:.2f}')} s "
              f"| {span([r[3] for r in rows], '{:,}')} | {span([x * 1e3 for x in per], '{:.2f}')} ms "
              f"({span(ratio, '{:.1f}')}×) |")
        if s == YARDSTICK:
            continue
        if max(totals) > ALL_WITHIN_S:
            over_all.append(f"{s} {span(totals, '{:.1f}')} s")
        if fast_group(s) and max(totals) > FAST_WITHIN_S:
            over_fast.append(f"{s} {span(totals, '{:.1f}')} s")
        if max(ratio) > PER_DECISION_TIMES:
            over_ratio.append(f"{s} {span(ratio, '{:.1f}')}×")

    def verdict(what, over):
        print(f"- {what}: " + ("met" if not over else "not met by " + ", ".join(over)))

    print()
    verdict(f"every preset within {ALL_WITHIN_S:g} s", over_all)
    verdict(f"`minpos`, `greedy`, `nearest`, RFE and AF presets within {FAST_WITHIN_S:g} s",
            over_fast)
    verdict(f"a robot-decision within {PER_DECISION_TIMES:g}× a `cf` decision", over_ratio)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Faigl & Kulich 2013, Table I beside ours, from a `frontier bench report` of faigl2013
or faigl2013-real.

    frontier bench --suite faigl2013 --trials 1 --db faigl.sqlite --report faigl-report/
    scripts/faigl2013-table.py faigl-report/report.md

Prints, as Markdown: the paper's eleven comparisons per (rho, m) with our verdicts
(`ours (paper)`, per environment: empty = the paper's em, office = jh, potholes; a real
floor plan of faigl2013-real, named after its file, is compared with jh, the paper's real
building), how many of our verdicts are the paper's and how many are the opposite (+
against -), and the mean longest path L of every method. Only the Python standard library
is needed.
"""
import re
import sys

# (row strategy, column strategy) of the paper's Table I, in its order.
PAIRS = [("ia-cc", "ia-rfe"), ("ha-cc", "ha-rfe"), ("ma-cc", "ma-rfe"), ("ha-cc", "ma-rfe"),
         ("ha-cc", "ma-cc"), ("ia-cc", "ha-rfe"), ("ia-cc", "ma-rfe"), ("ia-cc", "ha-cc"),
         ("ia-cc", "sga-af"), ("ha-cc", "sga-af"), ("ma-cc", "sga-af")]
# Table I of the paper: per (rho, m), eleven em/jh/potholes verdicts ("a vs b: +" = a better).
PAPER = """
3 3  =/+/+ +/+/= +/+/+ =/-/+ =/-/= =/+/+ -/-/+ -/=/= =/+/+ +/+/= +/+/=
3 5  +/+/= +/+/+ =/=/+ +/+/+ +/+/= +/=/+ +/-/+ =/-/= +/=/= +/+/+ +/+/+
3 7  +/+/= +/+/- =/+/+ +/+/= +/+/= =/+/- +/+/= =/=/= =/+/+ =/+/+ -/=/+
3 10 =/+/+ =/=/+ =/+/+ =/+/+ =/+/+ =/=/= =/+/+ =/=/= =/+/+ =/+/+ =/+/=
5 3  +/=/+ +/=/+ +/+/+ +/-/+ =/-/= +/=/+ +/-/+ +/=/= +/=/+ +/=/= +/+/+
5 5  =/=/+ =/+/- +/+/+ +/-/+ +/-/+ =/=/- +/-/+ -/-/= =/=/= +/=/= =/+/=
5 7  =/+/+ =/+/+ +/=/+ =/+/+ =/+/+ =/+/+ =/=/+ =/-/= =/+/+ =/+/+ =/+/+
5 10 =/=/+ =/+/+ -/+/+ =/+/+ =/+/= =/=/+ =/=/+ =/-/+ =/+/+ =/+/= =/+/=
7 3  =/=/- =/=/+ +/=/+ =/-/+ =/-/= =/=/- =/-/- =/=/= -/-/- =/-/= -/+/+
7 5  -/+/+ -/+/+ -/-/+ -/-/+ =/-/= -/=/+ -/-/+ =/-/= -/-/= -/-/+ -/+/+
7 7  -/+/+ -/+/+ -/-/+ -/+/+ =/+/+ -/+/+ -/=/+ =/-/- -/+/+ -/+/+ -/+/+
7 10 -/+/+ -/=/+ -/=/+ -/+/+ =/+/= -/=/+ -/+/+ =/=/= =/+/+ =/+/+ =/+/+
"""
ENVS = ["empty", "office", "potholes"]  # the paper's em, jh, potholes
ORDER = ["ga-af", "ia-af", "ha-af", "ga-rfe", "ia-rfe", "ha-rfe", "ma-rfe", "ga-cc", "ia-cc",
         "ha-cc", "ma-cc", "sga-af"]


def paper():
    out = {}
    for line in PAPER.strip().splitlines():
        rho, m, *cols = line.split()
        for (a, b), v in zip(PAIRS, cols):
            for env, x in zip(ENVS, v.split("/")):
                out[(env, int(rho), int(m), a, b)] = x
    return out


def parse(text):
    """Verdicts and mean L per setting from report.md."""
    verdict, mean = {}, {}
    head = re.compile(r"^### (\S+) · los:r=(\d+) · (\d+) robot")
    env = cols = None
    for line in text.splitlines():
        h = head.match(line)
        if h:
            name, rho, m = h.group(1), int(h.group(2)), int(h.group(3))
            # a generated environment is KIND-sSEED; a floor plan keeps its file's stem
            env = name.split("-")[0] if name.split("-")[0] in ENVS else name
            cols = None
            continue
        if line.startswith("#"):
            env = None
            continue
        if env is None or not line.startswith("|"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if cells[0] == "row vs column":
            cols = cells[1:]
        elif cols is None and len(cells) > 3 and cells[1].isdigit() and "±" in cells[3]:
            mean[(env, rho, m, cells[0])] = float(cells[3].split("±")[0])
        elif cols is not None:
            for c, v in zip(cols, cells[1:]):
                if v[:1] in ("+", "=", "-", "–"):
                    verdict[(env, rho, m, cells[0], c)] = "-" if v[0] == "–" else v[0]
    return verdict, mean


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    verdict, mean = parse(open(sys.argv[1], encoding="utf-8").read())
    table = paper()
    # a real floor plan is compared with jh, the paper's real building (our "office")
    ref = lambda e, *k: table.get((e if e in ENVS else "office", *k))
    envs = [e for e in ENVS if any(k[0] == e for k in mean)]
    envs += sorted({k[0] for k in mean} - set(ENVS))
    settings = sorted({(k[1], k[2]) for k in mean})
    dash = lambda v: v.replace("-", "–")
    print("| ρ (m) | m | " + " | ".join(f"{a.upper()} vs {b.upper()}" for a, b in PAIRS) + " |")
    print("|---|---|" + "---|" * len(PAIRS))
    for rho, m in settings:
        row = []
        for a, b in PAIRS:
            ours = "/".join(dash(verdict.get((e, rho, m, a, b), "·")) for e in envs)
            theirs = "/".join(dash(ref(e, rho, m, a, b) or "·") for e in envs)
            row.append(f"{ours} ({theirs})")
        print(f"| {rho} | {m} | " + " | ".join(row) + " |")
    print()
    for e in envs:
        same = opposite = n = 0
        for (env, rho, m, a, b), v in verdict.items():
            p = ref(env, rho, m, a, b)
            if env != e or p is None:
                continue
            n += 1
            same += v == p
            opposite += {v, p} == {"+", "-"}
        print(f"- `{e}`: {same} of {n} verdicts are the paper's, {opposite} the opposite.")
    for e in envs:
        strat = [s for s in ORDER if any((e, r, m, s) in mean for r, m in settings)]
        print(f"\nMean L (m), `{e}`:\n")
        print("| ρ | m | " + " | ".join(s.upper() for s in strat) + " |")
        print("|---|---|" + "---|" * len(strat))
        for r, m in settings:
            vals = [f"{mean[(e, r, m, s)]:.4g}" if (e, r, m, s) in mean else "·" for s in strat]
            print(f"| {r} | {m} | " + " | ".join(vals) + " |")


if __name__ == "__main__":
    main()

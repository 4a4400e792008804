"""A small study from Python: three strategies on ten generated offices, run in parallel
on Rust threads, into a pandas DataFrame, plotted with matplotlib.

    python crates/py/examples/study.py [out.png]      # needs pandas and matplotlib
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

import frontier  # noqa: E402

maps = [frontier.Map.generate("office", seed=s) for s in range(10)]
runs = [
    dict(map=m, strategy=strategy, seed=s, sensor="lidar:r=8,fov=180,res=1")
    for s, m in enumerate(maps)
    for strategy in ("random", "cf", "cf-rr")
]
df = pd.DataFrame(frontier.explore_many(runs))
table = df.groupby("strategy")["max_path_length_m"].agg(["mean", "std", "count"])
print(table.round(1))

fig, ax = plt.subplots(figsize=(6, 4))
df.boxplot(column="max_path_length_m", by="strategy", ax=ax)
ax.set_ylabel("path length to full coverage (m)")
ax.set_title("10 generated offices, lidar 8 m / 180°")
fig.suptitle("")
out = sys.argv[1] if len(sys.argv) > 1 else "study.png"
fig.savefig(out, dpi=120, bbox_inches="tight")
print(f"wrote {out}")

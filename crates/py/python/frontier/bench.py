"""Read a study's SQLite store (written by ``frontier bench``) into a data frame.

The rows come through the bench crate's own reader, so the columns are exactly those of
``frontier bench export`` (CSV): one row per trial, ordered by key. JSON columns
(``starts``, ``path_lengths``, ``coverage_curve``, ``idle_s``) are decoded into lists, and
``seed`` (kept as decimal text, an unsigned 64-bit number) into an int, as pandas reads the
CSV's.
"""

from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Union

from . import _native, _path, _text

__all__ = ["load", "rows"]

_JSON_COLUMNS = ("starts", "path_lengths", "coverage_curve", "idle_s")


def rows(db: Union[str, "os.PathLike[str]"]) -> List[Dict[str, Any]]:
    """Every trial of the store ``db`` as a list of dicts (no pandas needed)."""
    _path("db", db)
    out = json.loads(_native.load_rows(os.fspath(db)))
    for r in out:
        for c in _JSON_COLUMNS:
            if isinstance(r.get(c), str):
                r[c] = json.loads(r[c])
        if isinstance(r.get("seed"), str):
            r["seed"] = int(r["seed"])
    return out


def load(db: Union[str, "os.PathLike[str]"], backend: str = "pandas") -> Any:
    """Every trial of the store ``db`` as a ``pandas.DataFrame`` (``backend="polars"``:
    a ``polars.DataFrame``). Raises ``ValueError`` if ``db`` is not a study store."""
    _text("backend", backend, "'pandas' or 'polars'")
    if backend not in ("pandas", "polars"):
        raise ValueError(f"backend: expected 'pandas' or 'polars', found {backend!r}")
    data = rows(db)
    if backend == "pandas":
        import pandas as pd

        from_rows = pd.DataFrame(data)
        if not data:
            from_rows = pd.DataFrame(columns=_columns())
        # A numeric column that no trial filled (no [optimal] section, no coverage goal)
        # is all None: as floats with NaN, as the CSV export reads, it sums and averages.
        for c in _OPTIONAL_NUMBERS:
            if from_rows[c].dtype == object:
                from_rows[c] = pd.to_numeric(from_rows[c]).astype("float64")
        return from_rows
    import polars as pl

    if not data:
        return pl.DataFrame(schema=_columns())
    frame = pl.DataFrame(data)
    return frame.with_columns(
        [pl.col(c).cast(pl.Float64) for c in _OPTIONAL_NUMBERS if frame[c].dtype == pl.Null]
    )


#: The numeric columns a trial may leave empty.
_OPTIONAL_NUMBERS = (
    "env_seed", "s_max", "coverage_goal", "optimal_m", "optimal_lower_m", "ratio", "d90_m",
    "t90_s", "d99_m", "t99_s",
)


def _columns() -> List[str]:
    return [
        "key", "scenario", "env", "env_kind", "env_seed", "map_file", "resolution", "width",
        "height", "strategy", "preset", "s_max", "sensor", "belief", "sensing", "robots",
        "start_variant", "trial", "seed", "starts", "clearance", "speed", "coverage_goal",
        "max_moves", "path_lengths", "max_path", "total_path", "time_s", "coverage",
        "decisions", "moves", "reason", "reachable_cells", "coverage_curve", "version",
        "wall_s", "optimal_m", "optimal_lower_m", "optimal_proven", "ratio", "d90_m", "t90_s",
        "d99_m", "t99_s", "overlap", "idle_s",
    ]

"""Read a study's SQLite store (written by ``frontier bench``) into a data frame.

The rows come through the bench crate's own reader, so the columns are exactly those of
``frontier bench export`` (CSV): one row per trial, ordered by key. JSON columns
(``starts``, ``path_lengths``, ``coverage_curve``, ``idle_s``) are decoded into lists, and
``seed`` (kept as decimal text, an unsigned 64-bit number) into an int (a data frame's
column: uint64 in every store, whatever its seeds' values).
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
            seed = int(r["seed"])
            if not 0 <= seed < 2**64:
                raise ValueError(
                    f"{os.fspath(db)}: trial {r.get('key')}: seed: expected an integer in "
                    f"0..2^64, found {r['seed']}"
                )
            r["seed"] = seed
    return out


def load(db: Union[str, "os.PathLike[str]"], backend: str = "pandas") -> Any:
    """Every trial of the store ``db`` as a ``pandas.DataFrame`` (``backend="polars"``:
    a ``polars.DataFrame``). Raises ``ValueError`` if ``db`` is not a study store.

    Every store gives the same column types, whatever its trials filled, so that frames
    of several stores (a study's shards) concatenate: a numeric column no trial filled is
    float64 of NaN (polars: the column's type, all null), ``seed`` is uint64 (polars:
    ``UInt64``), ``optimal_proven`` is pandas' nullable ``boolean`` (polars: ``Boolean``),
    and an empty store's frame has every
    column's type (pandas: the one it reads a filled column as)."""
    _text("backend", backend, "'pandas' or 'polars'")
    if backend not in ("pandas", "polars"):
        raise ValueError(f"backend: expected 'pandas' or 'polars', found {backend!r}")
    data = rows(db)
    if backend == "pandas":
        import pandas as pd

        if not data:
            return pd.DataFrame({c: pd.Series(dtype=_PANDAS[k]) for c, k in _SCHEMA})
        from_rows = pd.DataFrame(data)
        # A numeric column that no trial filled (no [optimal] section, no coverage goal)
        # is all None: as floats with NaN, as the CSV export reads, it sums and averages.
        for c in _OPTIONAL_NUMBERS:
            if from_rows[c].dtype == object:
                from_rows[c] = pd.to_numeric(from_rows[c]).astype("float64")
        from_rows["optimal_proven"] = from_rows["optimal_proven"].astype("boolean")
        # pandas makes seeds int64 when all are below 2^63 and uint64 otherwise, and frames
        # of the two concatenate into float64, which changes seeds of 2^53 and more: seeds
        # are uint64 in every store, as an empty store's are and polars' are.
        from_rows["seed"] = from_rows["seed"].astype("uint64")
        return from_rows
    import polars as pl

    types = {c: _polars(pl, k) for c, k in _SCHEMA}
    if not data:
        return pl.DataFrame(schema=types)
    frame = pl.DataFrame(data)
    # A column no trial filled is Null-typed, and seeds beyond 2^63 made the seeds Int128:
    # each gets its own type, the same in every store.
    return frame.with_columns(
        [pl.col(c).cast(t) for c, t in types.items() if frame[c].dtype != t]
    )


#: Every column of a store's frame, in order, with its kind of values.
_SCHEMA = (
    ("key", "str"), ("scenario", "str"), ("env", "str"), ("env_kind", "str"),
    ("env_seed", "optional int"), ("map_file", "str"), ("resolution", "float"),
    ("width", "int"), ("height", "int"), ("strategy", "str"), ("preset", "str"),
    ("s_max", "optional int"), ("sensor", "str"), ("belief", "str"), ("sensing", "str"),
    ("robots", "int"), ("start_variant", "int"), ("trial", "int"), ("seed", "seed"),
    ("starts", "cells"), ("clearance", "float"), ("speed", "float"),
    ("coverage_goal", "float"), ("max_moves", "int"), ("path_lengths", "floats"),
    ("max_path", "float"), ("total_path", "float"), ("time_s", "float"),
    ("coverage", "float"), ("decisions", "int"), ("moves", "int"), ("reason", "str"),
    ("reachable_cells", "int"), ("coverage_curve", "pairs"), ("version", "str"),
    ("wall_s", "float"), ("optimal_m", "float"), ("optimal_lower_m", "float"),
    ("optimal_proven", "bool"), ("ratio", "float"), ("d90_m", "float"), ("t90_s", "float"),
    ("d99_m", "float"), ("t99_s", "float"), ("overlap", "float"), ("idle_s", "floats"),
)

#: The pandas dtype of each kind in an empty store's frame: what pandas makes of a filled
#: column ("str": pandas' own string type; an optional int is float64, NaN where empty).
_PANDAS = {
    "str": "str", "int": "int64", "optional int": "float64", "float": "float64",
    "seed": "uint64", "bool": "boolean", "cells": "object", "floats": "object",
    "pairs": "object",
}


def _polars(pl: Any, kind: str) -> Any:
    """The polars type of a column of ``kind``."""
    return {
        "str": pl.String, "int": pl.Int64, "optional int": pl.Int64, "float": pl.Float64,
        "seed": pl.UInt64, "bool": pl.Boolean, "cells": pl.List(pl.List(pl.Int64)),
        "floats": pl.List(pl.Float64), "pairs": pl.List(pl.List(pl.Float64)),
    }[kind]


#: The numeric columns a trial may leave empty.
_OPTIONAL_NUMBERS = tuple(
    c for c, k in _SCHEMA
    if k == "optional int" or c in (
        "coverage_goal", "optimal_m", "optimal_lower_m", "ratio", "d90_m", "t90_s", "d99_m",
        "t99_s",
    )
)


def _columns() -> List[str]:
    return [c for c, _ in _SCHEMA]

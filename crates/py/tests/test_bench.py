"""frontier.bench.load: a study store written by `frontier bench` read into a data frame."""

import os
import shutil
import subprocess

import pytest

import frontier
import frontier.bench

SCENARIO = """
name = "tiny"
seed = 1
robots = [1, 2]
sensors = ["los:r=4c"]
strategies = ["cf", "cf-rr"]
trials = 2

[[env]]
kind = "office"
seeds = [0]
size = [15, 12]
resolution = 0.25
"""


@pytest.fixture(scope="module")
def store(cli, tmp_path_factory):
    d = tmp_path_factory.mktemp("study")
    (d / "tiny.toml").write_text(SCENARIO)
    subprocess.run(
        [cli, "bench", str(d / "tiny.toml"), "--db", str(d / "tiny.sqlite"), "--no-progress"],
        check=True, capture_output=True,
    )
    subprocess.run(
        [cli, "bench", "export", str(d / "tiny.sqlite"), "--csv", str(d / "tiny.csv")],
        check=True, capture_output=True,
    )
    return d


def test_load_into_pandas_matches_the_csv_export(store):
    pd = pytest.importorskip("pandas")
    df = frontier.bench.load(store / "tiny.sqlite")
    csv = pd.read_csv(store / "tiny.csv")
    assert list(df.columns) == list(csv.columns)
    # The columns an empty store's frame gets are the same.
    assert frontier.bench._columns() == list(csv.columns)
    assert all(isinstance(v, list) for v in df["idle_s"])
    assert len(df) == 8
    assert list(df["key"]) == list(csv["key"])
    assert df["total_path"].tolist() == pytest.approx(csv["total_path"].tolist())
    assert set(df["strategy"]) == {"cf", "cf-rr"}
    assert all(isinstance(p, list) and len(p) == m for p, m in zip(df["path_lengths"], df["robots"]))
    means = df.groupby(["strategy", "robots"])["max_path"].mean()
    assert len(means) == 4


def test_load_into_polars_matches_pandas(store):
    pl = pytest.importorskip("polars")
    df = frontier.bench.load(store / "tiny.sqlite", backend="polars")
    assert isinstance(df, pl.DataFrame)
    pdf = frontier.bench.load(store / "tiny.sqlite")
    assert df.columns == list(pdf.columns)
    assert df["key"].to_list() == list(pdf["key"])
    assert df["total_path"].to_list() == pytest.approx(pdf["total_path"].tolist())
    assert df["path_lengths"].to_list() == list(pdf["path_lengths"])
    means = df.group_by(["strategy", "robots"]).agg(pl.col("max_path").mean())
    assert means.height == 4


def test_rows_equal_explore(store):
    row = next(r for r in frontier.bench.rows(store / "tiny.sqlite") if r["robots"] == 1)
    m = frontier.Map.generate("office", seed=0, size=(15, 12), resolution=0.25)
    got = frontier.explore(
        m, strategy=row["preset"], sensor=row["sensor"], seed=int(row["seed"]),
        start=tuple(row["starts"][0]),
    )
    assert got.total_path_length_m == pytest.approx(row["total_path"], abs=1e-4)


def _make_read_only(paths):
    """Make files and folders read-only, also to root (the immutable attribute); returns
    how to undo it. Skips the test where neither way is open."""
    if os.geteuid() != 0:
        modes = [(p, p.stat().st_mode) for p in paths]
        for p in paths:
            p.chmod(0o555 if p.is_dir() else 0o444)
        return lambda: [p.chmod(m) for p, m in modes]
    if shutil.which("chattr") is None:
        pytest.skip("root without chattr: no way to make a read-only folder")
    done = subprocess.run(["chattr", "+i", *map(str, paths)], capture_output=True)
    if done.returncode != 0:
        pytest.skip(f"chattr +i refused: {done.stderr.decode().strip()}")
    return lambda: subprocess.run(["chattr", "-i", *map(str, paths)], check=True)


def test_load_reads_a_read_only_store(store, tmp_path):
    """Regression: ``load`` opened the store for writing, so a store on a read-only file
    system (a cluster's results mounted read-only) was "attempt to write a readonly
    database", where ``frontier bench export`` reads it."""
    d = tmp_path / "ro"
    d.mkdir()
    shutil.copy(store / "tiny.sqlite", d / "tiny.sqlite")
    undo = _make_read_only([d / "tiny.sqlite", d])
    try:
        df = frontier.bench.load(d / "tiny.sqlite")
    finally:
        undo()
    assert list(df["key"]) == list(frontier.bench.load(store / "tiny.sqlite")["key"])
    assert sorted(p.name for p in d.iterdir()) == ["tiny.sqlite"]


def test_not_a_store(tmp_path):
    with pytest.raises(ValueError, match="no such study store"):
        frontier.bench.load(tmp_path / "missing.sqlite")
    with pytest.raises(ValueError, match="is a folder; expected a study store"):
        frontier.bench.load(tmp_path)
    bad = tmp_path / "bad.sqlite"
    bad.write_text("not a database at all, just text" * 100)
    with pytest.raises(ValueError):
        frontier.bench.load(bad)
    with pytest.raises(ValueError, match="backend: expected 'pandas' or 'polars'"):
        frontier.bench.load(bad, backend="excel")


def test_regression_load_refuses_a_foreign_database_unchanged(tmp_path):
    """Regression: ``load`` of another program's SQLite database in WAL mode left ``-wal``
    and ``-shm`` files beside it, and said only that it had "no results tables". It names
    the tables it found, and the folder is left as it was."""
    import sqlite3

    db = tmp_path / "notes.db"
    conn = sqlite3.connect(db)
    conn.execute("PRAGMA journal_mode=WAL")
    conn.executescript(
        "CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);"
        "CREATE TABLE notes (body TEXT); INSERT INTO notes VALUES ('buy milk');"
    )
    conn.close()
    before = db.read_bytes()
    assert before[18:20] == b"\x02\x02", "the database is in WAL mode"
    with pytest.raises(
        ValueError,
        match=r"notes\.db: is not a frontier results database \(it has the tables meta, notes, "
        r"not frontier's \(meta, envs, trials, optimal\)\)",
    ):
        frontier.bench.load(db)
    assert db.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["notes.db"]

def test_regression_load_gives_integer_seeds_as_the_csv_does(store):
    pd = pytest.importorskip("pandas")
    df = frontier.bench.load(store / "tiny.sqlite")
    csv = pd.read_csv(store / "tiny.csv")
    assert df["seed"].dtype == csv["seed"].dtype and df["seed"].tolist() == csv["seed"].tolist()
    seed = int(csv["seed"][0])
    assert len(df[df["seed"] == seed]) == len(csv[csv["seed"] == seed]) >= 1
    assert all(isinstance(r["seed"], int) for r in frontier.bench.rows(store / "tiny.sqlite"))


def test_regression_numeric_columns_no_trial_filled_are_floats(store):
    """Regression: a numeric column that no trial filled (no [optimal] section, no
    coverage goal) came back as objects, all None, where the CSV export reads NaN floats,
    so that its mean failed. It is float64 (polars: Float64) of NaN (null)."""
    pd = pytest.importorskip("pandas")
    df = frontier.bench.load(store / "tiny.sqlite")
    csv = pd.read_csv(store / "tiny.csv")
    for c in ("s_max", "coverage_goal", "optimal_m", "optimal_lower_m", "ratio"):
        assert df[c].dtype == csv[c].dtype == "float64", c
        assert df[c].isna().all(), c
    assert pd.isna(df.groupby("strategy")["ratio"].mean()).all()
    pl = pytest.importorskip("polars")
    frame = frontier.bench.load(store / "tiny.sqlite", backend="polars")
    assert frame["ratio"].dtype == pl.Float64 and frame["ratio"].null_count() == len(frame)


def test_regression_arguments_of_a_wrong_type_name_the_argument():
    """Regression: a store that is no path gave os.fspath's message, which names no
    argument, and a backend that is no str was a ValueError."""
    for call, message in [
        (lambda: frontier.bench.load(3), r"db: expected a path \(a str or os.PathLike\), found int"),
        (lambda: frontier.bench.rows(None),
         r"db: expected a path \(a str or os.PathLike\), found NoneType"),
        (lambda: frontier.bench.load("study.sqlite", backend=1),
         "backend: expected 'pandas' or 'polars', found int"),
        (lambda: frontier._native.load_rows(2.5),
         r"path: expected a path \(a str or os.PathLike\), found float"),
    ]:
        with pytest.raises(TypeError, match=f"^{message}"):
            call()


def test_regression_every_store_gives_the_same_column_types(cli, store, tmp_path):
    """Regression: an empty store's frame had 36 object columns (polars: all Null), and a
    column no trial filled took another type than a filled one, so that frames of a study's
    shards concatenated into object columns; optimal_proven was an object column of None."""
    pd = pytest.importorskip("pandas")
    (tmp_path / "tiny.toml").write_text(SCENARIO)
    empty = tmp_path / "empty.sqlite"
    subprocess.run(
        [cli, "bench", str(tmp_path / "tiny.toml"), "--db", str(empty), "--limit", "0",
         "--no-progress"],
        check=True, capture_output=True,
    )
    full = frontier.bench.load(store / "tiny.sqlite")
    none = frontier.bench.load(empty)
    assert len(none) == 0 and list(none.columns) == list(full.columns)
    both = pd.concat([full, none])
    for c in full.columns:
        if c not in ("env_seed", "map_file"):  # int64 / object when filled, float64 / str empty
            assert none[c].dtype == full[c].dtype, c
        assert both[c].dtype == full[c].dtype or c in ("env_seed", "map_file"), c
    assert full["optimal_proven"].dtype == "boolean"
    assert ([c for c in both.columns if both[c].dtype == object]
            == ["map_file", "starts", "path_lengths", "coverage_curve", "idle_s"])
    pl = pytest.importorskip("polars")
    full = frontier.bench.load(store / "tiny.sqlite", backend="polars")
    none = frontier.bench.load(empty, backend="polars")
    assert full.schema == none.schema
    assert full["seed"].dtype == pl.UInt64 and full["map_file"].dtype == pl.String
    assert pl.concat([full, none]).height == full.height


def test_regression_seeds_are_uint64_in_every_store(store, tmp_path):
    """Regression: pandas made a store's seeds int64 when all were below 2^63 and uint64
    otherwise, so that the frames of two shards concatenated into float64 seeds, and a seed
    of 2^53 + 1 came back as 2^53. Seeds are uint64 in every store; a seed outside
    0..2^64 is refused, not wrapped."""
    pd = pytest.importorskip("pandas")
    import sqlite3

    small = tmp_path / "small.sqlite"
    shutil.copy(store / "tiny.sqlite", small)
    conn = sqlite3.connect(small)
    conn.execute("UPDATE trials SET seed = '9007199254740993'")  # 2^53 + 1
    conn.commit()
    conn.close()
    full = frontier.bench.load(store / "tiny.sqlite")
    low = frontier.bench.load(small)
    assert full["seed"].dtype == low["seed"].dtype == "uint64"
    assert max(full["seed"]) >= 2**63 and set(low["seed"]) == {2**53 + 1}
    both = pd.concat([full, low])
    assert both["seed"].dtype == "uint64"
    assert both["seed"].tolist() == full["seed"].tolist() + [2**53 + 1] * len(low)
    assert len(both[both["seed"] == 2**53 + 1]) == len(low)
    pl = pytest.importorskip("polars")
    assert frontier.bench.load(small, backend="polars")["seed"].dtype == pl.UInt64
    conn = sqlite3.connect(small)
    conn.execute("UPDATE trials SET seed = '-1'")
    conn.commit()
    conn.close()
    with pytest.raises(ValueError, match=r"small\.sqlite: trial .*: seed: expected an integer "
                       r"in 0\.\.2\^64, found -1"):
        frontier.bench.load(small)

"""frontier.explore and explore_many: the CLI's numbers, parallel batches, clear errors."""

import json
import os
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import frontier
import frontier.gym


def cli_json(cli, *args):
    out = subprocess.run(
        [cli, "explore", *args, "--json", "--no-timing"], capture_output=True, text=True, check=True
    )
    return json.loads(out.stdout)


@pytest.mark.parametrize(
    "strategy,sensor,robots",
    [("cf-rr", "los:r=5", 1), ("yamauchi", "lidar:r=4,fov=180,res=2", 1), ("ha-cc", "los:r=3", 3)],
)
def test_equals_cli_json(cli, office, tmp_path, strategy, sensor, robots):
    yaml = tmp_path / "office.yaml"
    office.save(yaml)
    want = cli_json(
        cli, "--map", str(yaml), "--strategy", strategy, "--sensor", sensor,
        "--robots", str(robots), "--seed", "4",
    )
    got = frontier.explore(
        frontier.Map.load(yaml), strategy=strategy, sensor=sensor, robots=robots, seed=4
    )
    assert got.summary == want
    assert got.path_length_m == want["path_length_m"]


@pytest.mark.parametrize("strategy,robots", [("cf-rr", 1), ("ha-cc", 3)])
def test_sensing_every_third_cell_equals_cli_json(cli, office, tmp_path, strategy, robots):
    # Explore-Bench's grid simulator senses at every third cell of a path and at its end.
    yaml = tmp_path / "office.yaml"
    office.save(yaml)
    want = cli_json(
        cli, "--map", str(yaml), "--strategy", strategy, "--sensor", "square:r=3",
        "--robots", str(robots), "--seed", "4", "--sensing", "every-3",
    )
    assert want["sensing"] == "every-3" and want["reason"] == "complete"
    got = frontier.explore(
        frontier.Map.load(yaml), strategy=strategy, sensor="square:r=3", robots=robots, seed=4,
        sensing="every-3",
    )
    assert got.summary == want
    every = frontier.explore(office, strategy=strategy, robots=robots, seed=4, sensing="every-1")
    assert every.summary == frontier.explore(office, strategy=strategy, robots=robots, seed=4).summary


def test_motion_and_coverage_equal_cli_json(cli, office, tmp_path):
    """Regression: explore() had no `motion` (TypeError) or `coverage`, and explore_many
    took both for tags, silently running with the defaults."""
    yaml = tmp_path / "office.yaml"
    office.save(yaml)
    want = cli_json(cli, "--map", str(yaml), "--motion", "any-angle", "--coverage", "known",
                    "--sensor", "square:r=3")
    assert (want["motion"], want["coverage_kind"]) == ("any-angle", "known")
    m = frontier.Map.load(yaml)
    got = frontier.explore(m, motion="any-angle", coverage="known", sensor="square:r=3")
    assert got.summary == want
    [row] = frontier.explore_many([dict(map=m, motion="any-angle", coverage="known", sensor="square:r=3")])
    assert (row["motion"], row["coverage_kind"], row["path_length_m"]) == (
        "any-angle", "known", want["path_length_m"])
    with pytest.raises(ValueError, match="--coverage: "):
        frontier.explore(m, coverage="all")


def test_generated_map_equals_cli_env(cli, office):
    want = cli_json(cli, "--env", "office", "--seed", "3", "--size", "15x12", "--resolution", "0.25")
    assert frontier.explore(office, seed=3).summary == want


def test_clutter_equals_cli_clutter_map(cli, office, tmp_path):
    # Tables off the laser plane: every free cell of a few 3 x 3 blocks.
    cells = office.to_numpy()
    furniture = np.zeros(cells.shape, dtype=bool)
    for y, x in [(10, 12), (20, 30), (30, 45), (12, 40)]:
        furniture[y:y + 3, x:x + 3] = cells[y:y + 3, x:x + 3] == 1
    assert furniture.any()
    layer = frontier.Map.from_numpy(furniture, 0.25)
    office.save(tmp_path / "office.yaml")
    layer.save(tmp_path / "clutter.yaml")
    want = cli_json(
        cli, "--map", str(tmp_path / "office.yaml"), "--clutter-map",
        str(tmp_path / "clutter.yaml"), "--sensor", "lidar:r=4,fov=180,res=2", "--seed", "2",
    )
    loaded = frontier.Map.load(tmp_path / "office.yaml")
    got = frontier.explore(loaded, sensor="lidar:r=4,fov=180,res=2", seed=2, clutter=layer)
    assert got.summary == want
    plain = frontier.explore(loaded, sensor="lidar:r=4,fov=180,res=2", seed=2)
    assert plain.summary != want  # the body met the furniture the laser did not see
    rows = frontier.explore_many(
        [{"map": loaded, "sensor": "lidar:r=4,fov=180,res=2", "seed": 2, "clutter": layer}]
    )
    assert rows[0]["path_length_m"] == want["path_length_m"]
    with pytest.raises(ValueError, match="clutter: expected the map's size 60x48 cells, found 2x2"):
        frontier.explore(office, clutter=frontier.Map.from_numpy(np.zeros((2, 2), bool), 0.25))
    with pytest.raises(TypeError, match="clutter: expected a frontier.Map"):
        frontier.explore(office, clutter="tables")


def test_trajectories_that_outgrow_their_memory_end_the_run():
    # Regression: random crossing a maze for every goal takes 1.4 times the moves its
    # estimate expects here, and its trajectories grew past the memory checked.
    maze = frontier.Map.generate("maze", seed=3, size=(14, 10), resolution=0.05)
    kw = dict(strategy="random", sensor="los:r=2c", memory_mb=100)
    with pytest.warns(RuntimeWarning, match="the run stopped after .* moves, before it"):
        r = frontier.explore(maze, **kw)
    assert r.reason == "trace limit" and r.coverage < 1.0
    assert sum(len(t) for t in r.trajectories) > 1_000_000


def test_arrays(office):
    r = frontier.explore(office, robots=2, seed=1)
    assert r.belief.shape == office.shape and r.belief.dtype == np.uint8
    assert len(r.trajectories) == 2
    for t, start in zip(r.trajectories, r.starts):
        assert t.dtype == np.int32 and t.shape[1] == 2
        assert list(t[0]) == start
        steps = np.abs(np.diff(t, axis=0)).max(axis=1)
        assert (steps <= 1).all()
    assert r.decide_ms is None
    assert frontier.explore(office, timing=True).decide_ms >= 0
    assert frontier.explore(office, trajectories=False).trajectories is None


def test_same_seed_same_result(office):
    a = frontier.explore(office, strategy="random", seed=9)
    b = frontier.explore(office, strategy="random", seed=9)
    assert a.summary == b.summary and np.array_equal(a.belief, b.belief)


def test_explore_many_matches_explore_in_order(office):
    runs = [
        dict(map=office, strategy=s, seed=seed, tag=f"{s}/{seed}")
        for s in ("cf", "cf-rr", "random")
        for seed in range(3)
    ]
    rows = frontier.explore_many(runs, threads=2)
    assert [r["tag"] for r in rows] == [r["tag"] for r in runs]
    for run, row in zip(runs, rows):
        one = frontier.explore(office, strategy=run["strategy"], seed=run["seed"]).row()
        assert {k: row[k] for k in one} == one
    pd = pytest.importorskip("pandas")
    df = pd.DataFrame(rows)
    assert len(df) == 9 and "map_accuracy" in df and "max_path_length_m" in df
    assert (df.groupby("strategy").size() == 3).all()


def test_explore_many_on_one_map_shares_its_line_of_sight_with_the_same_rows():
    # Runs of a batch on one map share what the line-of-sight sensor sees from each cell
    # (made at the second scan from a cell, read at later ones): every row equals the run
    # made alone, for one robot and teams, with the ray template (3 m = 15 cells) and
    # shadow casting (5 m = 25 cells).
    holes = frontier.Map.generate("potholes", seed=2, size=(12, 10), resolution=0.2)
    runs = [
        dict(map=holes, strategy=s, robots=m, sensor=f"los:r={r}", seed=seed)
        for s, m in (("cf-rr", 1), ("ha-cc", 3), ("ma-rfe", 3))
        for r in (3, 5)
        for seed in range(3)
    ]
    rows = frontier.explore_many(runs, threads=2)
    for run, row in zip(runs, rows):
        kw = {k: v for k, v in run.items() if k != "map"}
        one = frontier.explore(holes, **kw).row()
        assert {k: row[k] for k in one} == one, run


@pytest.mark.parametrize(
    "kwargs,error,message",
    [
        (dict(strategy="fastest"), ValueError, "--strategy: unknown strategy 'fastest'"),
        (dict(sensor="radar:r=3"), ValueError, "--sensor: sensor 'radar:r=3': unknown kind 'radar'"),
        (dict(start=(500, 2)), ValueError, "--start 500,2: outside the 60x48 map"),
        (dict(start=(0, 0)), ValueError, r"--start 0,0: the cell is occupied"),
        (dict(robots=0), ValueError, "--robots: expected at least 1, found 0"),
        (dict(speed=-1.0), ValueError, "--speed: expected a positive number of metres per second"),
        (dict(goal=2.0), ValueError, r"--goal: expected a coverage share in \(0, 1\]"),
        (dict(s_max=0), ValueError, "--s-max: expected a positive number of cell moves or -1"),
        (dict(belief="fuzzy"), ValueError, "--belief: "),
        (dict(sensing="every-0"), ValueError, "--sensing: sensing mode: expected 'continuous', "
         "'on-arrival' or 'every-N'"),
        (dict(seed=-1), ValueError, "--seed: expected an integer in 0..2"),
        (dict(strategy=3), TypeError, "strategy: expected a str, found int"),
        (dict(start="1,2"), TypeError, r"start: expected a cell \(x, y\)"),
    ],
)
def test_bad_input_raises_with_cli_message(office, kwargs, error, message):
    with pytest.raises(error, match=message):
        frontier.explore(office, **kwargs)


def test_messages_equal_the_cli(cli, office, tmp_path):
    yaml = tmp_path / "office.yaml"
    office.save(yaml)
    for flags, kwargs in [
        (["--strategy", "fastest"], dict(strategy="fastest")),
        (["--sensor", "los:r=-2"], dict(sensor="los:r=-2")),
        (["--start", "500,2"], dict(start=(500, 2))),
        (["--start", "0,0"], dict(start=(0, 0))),
        (["--memory-mb", "1"], dict(memory_mb=1)),
    ]:
        out = subprocess.run([cli, "explore", "--map", str(yaml), *flags], capture_output=True, text=True)
        assert out.returncode == 1
        with pytest.raises(ValueError) as e:
            frontier.explore(frontier.Map.load(yaml), **kwargs)
        assert out.stderr.strip() == f"error: {e.value}"


def test_explore_many_checks_every_run_first(office):
    with pytest.raises(ValueError, match="run 1: --strategy: unknown strategy 'nope'"):
        frontier.explore_many([dict(map=office), dict(map=office, strategy="nope")])
    with pytest.raises(TypeError, match="run 0: missing 'map'"):
        frontier.explore_many([dict(seed=1)])
    with pytest.raises(TypeError, match="unexpected keyword argument 'colour'"):
        frontier.explore(office, **{"colour": "red"}) if False else frontier._native.explore(office, {"colour": "red"})


def test_explore_many_checks_memory_first(office):
    """Regression: the Python package estimated no run's memory, so a batch of large runs
    could be killed half-way for lack of memory; now it is refused before any starts."""
    # each run (about 17 MiB: 16.2 of base and arrays, 0.4 of the los:r=5 sensor's ray
    # template) fits in 20 MiB, two at once do not
    with pytest.raises(ValueError, match=r"running 4 runs on 2 threads \(the largest, run 0, "
                       r"about 17 MiB\) needs about 34 MiB, more than --memory-mb 20; "
                       r"use fewer threads"):
        frontier.explore_many([dict(map=office)] * 4, threads=2, memory_mb=20)
    with pytest.raises(ValueError, match=r"run 0: exploring this 60x48 map with 1 robot \(cf-rr\) "
                       r"needs about 17 MiB, more than --memory-mb 1"):
        frontier.explore_many([dict(map=office)] * 4, threads=2, memory_mb=1)
    with pytest.raises(ValueError, match="memory_mb: expected a positive number of MiB, found 0"):
        frontier.explore(office, memory_mb=0)
    with pytest.raises(TypeError, match="memory_mb: expected an int, found float"):
        frontier.explore_many([dict(map=office)], memory_mb=2.5)
    assert len(frontier.explore_many([dict(map=office)] * 2, threads=2, memory_mb=4096)) == 2


def test_explore_many_arguments(office):
    with pytest.raises(TypeError, match=r"runs: expected a list of runs \(mappings with a 'map'\), found int"):
        frontier.explore_many(5)
    with pytest.raises(ValueError, match="threads: expected at least 1, found -1"):
        frontier.explore_many([dict(map=office)], threads=-1)
    assert len(frontier.explore_many(dict(map=office, seed=k) for k in range(2))) == 2


def test_explore_many_warns_of_a_misspelt_option(office):
    with pytest.warns(UserWarning, match=r"run 1: 'stratgy' is not an option of explore .* "
                      r"did you mean 'strategy'\?"):
        rows = frontier.explore_many([dict(map=office), dict(map=office, stratgy="cf")])
    assert rows[1]["stratgy"] == "cf" and rows[1]["strategy"] == "cf-rr"
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        frontier.explore_many([dict(map=office, tag="baseline", trial=3)])


def test_strategies_lists_the_presets(office):
    names = [n for n, _ in frontier.strategies()]
    assert {"cf-rr", "yamauchi", "dt500", "random", "ha-rfe", "ma-cc"} <= set(names)
    # Regression: the list held the summary line "ga-af, ia-cc, ...", which no run takes.
    for name in names:
        frontier.gym.ExploreEnv(office, strategy=name)


def test_explore_many_reports_progress_and_gives_the_same_rows(office):
    runs = [dict(map=office, strategy=s, seed=k) for s in ("cf", "cf-rr") for k in range(4)]
    calls = []
    rows = frontier.explore_many(runs, threads=2, progress=lambda done, n: calls.append((done, n)))
    assert rows == frontier.explore_many(runs, threads=2)
    assert calls and calls[-1] == (len(runs), len(runs))
    assert all(n == len(runs) for _, n in calls)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)
    # the bar (tqdm's, or a line on stderr without tqdm) changes nothing either
    assert frontier.explore_many(runs, progress=True) == rows
    with pytest.raises(TypeError, match="progress: expected True, False, None or a callable"):
        frontier.explore_many(runs, progress="yes")


def _slow_batch():
    """Runs that take minutes each in any build (a 100 x 60 m hospital at 0.05 m, a team
    deciding every 7 moves), so that a batch which does not stop shows."""
    big = frontier.Map.generate("hospital", seed=1, size=(100, 60), resolution=0.05)
    return [dict(map=big, strategy="ha-cc", robots=3, seed=k) for k in range(4)]


def test_an_exception_from_progress_stops_the_batch():
    runs = _slow_batch()

    def stop(done, n):
        raise RuntimeError("enough")

    started = time.monotonic()
    with pytest.raises(RuntimeError, match="enough"):
        frontier.explore_many(runs, threads=2, progress=stop)
    # the runs stopped at the first report (0.1 s), not after minutes
    assert time.monotonic() - started < 60


def test_ctrl_c_stops_explore_and_explore_many():
    runs = _slow_batch()
    # Python raises KeyboardInterrupt on SIGINT only if it did not start with SIGINT
    # ignored, as a background job without job control does (`nohup pytest &`): then the
    # signal would do nothing and the runs go to their end. Ctrl-C's usual handler, here.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        for call in (
            lambda: frontier.explore(runs[0]["map"], strategy="ha-cc", robots=3),
            lambda: frontier.explore_many(runs, threads=2),
        ):
            timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
            started = time.monotonic()
            timer.start()
            try:
                with pytest.raises(KeyboardInterrupt):
                    call()
            finally:
                timer.cancel()
            # raised within a tick of the signal, not when the runs would have ended
            assert time.monotonic() - started < 60
    finally:
        signal.signal(signal.SIGINT, previous)


def test_submodules_after_a_bare_import():
    """`frontier.bench.load(db)` as pandas users write it, without `import frontier.bench`:
    the submodules load on first use (a fresh interpreter, as no other test imported them)."""
    code = (
        "import sys, frontier\n"
        "assert 'frontier.bench' not in sys.modules and 'frontier.gym' not in sys.modules\n"
        "assert callable(frontier.bench.load)\n"
        "assert frontier.gym.ExploreEnv and frontier.pettingzoo.ExploreParallelEnv\n"
        "assert {'bench', 'gym', 'pettingzoo'} <= set(dir(frontier))\n"
        "try:\n"
        "    frontier.nope\n"
        "except AttributeError as e:\n"
        "    assert \"'nope'\" in str(e)\n"
        "else:\n"
        "    raise SystemExit('no AttributeError')\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_regression_explore_result_copies_and_pickles(office):
    import copy
    import pickle

    r = frontier.explore(office, seed=2)
    for other in (copy.copy(r), copy.deepcopy(r), pickle.loads(pickle.dumps(r))):
        assert other.summary == r.summary and other.coverage == r.coverage
        assert np.array_equal(other.belief, r.belief)
        assert all(np.array_equal(a, b) for a, b in zip(other.trajectories, r.trajectories))
    assert copy.deepcopy(r).summary is not r.summary
    with pytest.raises(AttributeError):
        r.no_such_field
    empty = frontier.ExploreResult.__new__(frontier.ExploreResult)
    with pytest.raises(AttributeError):
        empty.summary
    with pytest.raises(AttributeError):
        empty.coverage


def test_regression_explore_many_starts_no_more_threads_than_runs():
    a = np.zeros((8, 8), bool)
    m = frontier.Map.from_numpy(a, 0.1)
    one = frontier.explore_many([dict(map=m)])
    t0 = time.perf_counter()
    assert frontier.explore_many([dict(map=m)], threads=4096) == one
    # A pool of 4,096 OS threads took seconds; one thread per run takes milliseconds.
    assert time.perf_counter() - t0 < 1.0
    assert frontier.explore_many([], threads=8) == []
    with pytest.raises(ValueError, match="threads: expected at most 4096, found 1000000"):
        frontier.explore_many([dict(map=m)], threads=10**6)
    with pytest.raises(ValueError, match="threads: expected at most 4096, found 4097"):
        frontier._native.explore_many([(m, None)], threads=4097)


def test_regression_explore_many_refuses_batch_arguments_and_clashing_tags(office):
    for key, value, what in [
        ("timing", True, r"explore_many\(runs, timing=\.\.\.\)"),
        ("memory_mb", 100, r"explore_many\(runs, memory_mb=\.\.\.\)"),
        ("trajectories", False, "explore_many returns summaries only"),
    ]:
        with pytest.raises(TypeError, match=rf"run 1: '{key}': .*{what}"):
            frontier.explore_many([dict(map=office), dict(map=office, **{key: value})])
    for tag in ("env", "reason", "map_accuracy", "timing_ms_total"):
        with pytest.raises(ValueError, match=rf"run 0: the tag '{tag}' is also a column"):
            frontier.explore_many([dict(map=office, **{tag: "mine"})])
    rows = frontier.explore_many([dict(map=office, trial=2, label="a")])
    assert (rows[0]["trial"], rows[0]["label"]) == (2, "a")


def test_regression_start_beyond_32_bits_is_reported_as_given(office):
    with pytest.raises(ValueError, match=r"start: expected a cell \(x, y\) of 32-bit integers, "
                       r"found \(8589934592, 1\)"):
        frontier.explore(office, start=(2**33, 1))


def test_regression_memory_mb_takes_numpy_integers(office):
    rows = frontier.explore_many([dict(map=office)], memory_mb=np.int64(100))
    assert rows == frontier.explore_many([dict(map=office)], memory_mb=100)
    assert frontier.explore(office, memory_mb=np.int32(100)).summary == \
        frontier.explore(office).summary


def test_regression_run_options_of_a_wrong_type_name_the_argument(office):
    """Regression: a bool was taken as a number (robots=True ran one robot), an integer
    beyond 64 bits was "expected an int, found int", and None was "not allowed" without
    saying what was."""
    for kwargs, error, message in [
        (dict(robots=True), TypeError, "robots: expected an int, found bool"),
        (dict(seed=False), TypeError, "seed: expected an int, found bool"),
        (dict(s_max=True), TypeError, "s_max: expected an int, found bool"),
        (dict(max_moves=np.float32(5)), TypeError, "max_moves: expected an int, found float32"),
        (dict(clearance=True), TypeError, "clearance: expected a number of metres, found bool"),
        (dict(speed="fast"), TypeError,
         "speed: expected a number of metres per second, found str"),
        (dict(goal="all"), TypeError, "goal: expected a number or None, found str"),
        (dict(sensor=None), TypeError, "sensor: expected a str, found NoneType"),
        (dict(belief=1), TypeError, "belief: expected a str or None, found int"),
        (dict(motion=b"grid"), TypeError, "motion: expected a str or None, found bytes"),
        (dict(seed=2**64), ValueError,
         r"--seed: expected an integer in 0\.\.2\^64, found 18446744073709551616"),
        (dict(seed=2**200), ValueError, r"--seed: expected an integer in 0\.\.2\^64, found 1606"),
        (dict(robots=2**70), ValueError,
         "--robots: expected at most 18446744073709551615, found 1180591620717411303424"),
        (dict(robots=-2**70), ValueError,
         "--robots: expected at least 1, found -1180591620717411303424"),
        (dict(s_max=2**70), ValueError, "--s-max: expected a positive number of cell moves or "
         r"-1 \(on arrival\), found 1180591620717411303424"),
        (dict(max_moves=2**70), ValueError,
         r"--max-moves: expected an integer in 0\.\.2\^64, found 1180591620717411303424"),
    ]:
        with pytest.raises(error, match=f"^{message}"):
            frontier.explore(office, **kwargs)
        with pytest.raises(error, match=f"^run 0: {message}"):
            frontier.explore_many([dict(map=office, **kwargs)])
    with pytest.raises(TypeError, match="^trajectories: expected a bool, found str"):
        frontier._native.explore(office, {"trajectories": "yes"})
    with pytest.raises(TypeError, match="^kwargs: expected str keys, found int"):
        frontier._native.explore(office, {1: 2})
    # None is an unset option, and no clutter (as explore's clutter=None).
    assert frontier.explore_many([dict(map=office, seed=2, clutter=None, goal=None)]) == \
        frontier.explore_many([dict(map=office, seed=2)])
    assert frontier.explore(office, robots=np.int64(2), seed=np.uint64(2**63)).robots == 2


def test_numpy_bool_as_a_number_refused(office):
    """Regression: a numpy bool converts to a float, so ``goal=np.True_`` ran to the goal 1.0,
    ``clearance=np.True_`` kept 1 m clear and ``Map.from_numpy(a, np.True_)`` made 1 m
    cells, where Python's True was a TypeError."""
    for kwargs, message in [
        (dict(goal=np.True_), "goal: expected a number or None, found bool"),
        (dict(clearance=np.True_), "clearance: expected a number of metres, found bool"),
        (dict(speed=np.False_), "speed: expected a number of metres per second, found bool"),
    ]:
        with pytest.raises(TypeError, match=f"^{message}$"):
            frontier.explore(office, **kwargs)
        with pytest.raises(TypeError, match=f"^run 0: {message}$"):
            frontier.explore_many([dict(map=office, **kwargs)])
    a = np.zeros((4, 4), bool)
    with pytest.raises(TypeError, match="^resolution: expected a number of metres per cell, "
                       "found bool$"):
        frontier.Map.from_numpy(a, np.True_)
    with pytest.raises(TypeError, match="^resolution: expected a number of metres per cell, "
                       "found bool$"):
        frontier.Map.generate("empty", resolution=np.True_)
    with pytest.raises(TypeError, match=r"^size: expected \(width, height\) in metres, found "
                       r"np.True_ \(bool\) among its values$"):
        frontier.Map.generate("empty", size=(np.True_, 5))
    with pytest.raises(TypeError, match=r"^resolution: expected a number of metres per cell or "
                       r"a pair \(x, y\), found np.True_ \(bool\) among its values$"):
        frontier.Map.load("office.txt", resolution=(np.True_, 0.1))
    # numpy numbers are numbers
    assert frontier.Map.from_numpy(a, np.float32(0.5)).resolution == 0.5
    assert frontier.explore(office, goal=np.float64(0.5)).summary == \
        frontier.explore(office, goal=0.5).summary


def test_number_beyond_float_range_refused_by_its_range_check(cli, office, tmp_path):
    """Regression: an int beyond a float's range (10**400) was "clearance: expected a number
    of metres, found int" (a TypeError, though an int is a number) in the native arguments,
    and an OverflowError ("int too large to convert to float") in the environments'. It is
    infinite now, as the CLI's 1e400 is, and refused by the argument's range check with the
    CLI's message."""
    big = 10**400
    for kwargs, message in [
        (dict(clearance=big), "--clearance: expected a non-negative number of metres, found inf"),
        (dict(speed=-big), "--speed: expected a positive number of metres per second, from "
         "0.001 to 1000, found -inf"),
        (dict(goal=big), r"--goal: expected a coverage share in \(0, 1\], found inf"),
    ]:
        with pytest.raises(ValueError, match=f"^{message}$"):
            frontier.explore(office, **kwargs)
        with pytest.raises(ValueError, match=f"^run 0: {message}$"):
            frontier.explore_many([dict(map=office, **kwargs)])
    yaml = tmp_path / "office.yaml"
    office.save(yaml)
    out = subprocess.run([cli, "explore", "--map", str(yaml), "--clearance", "1e400"],
                         capture_output=True, text=True)
    with pytest.raises(ValueError) as e:
        frontier.explore(office, clearance=big)
    assert out.stderr.strip() == f"error: {e.value}"
    resolution = r"^--resolution: expected a positive number of metres per cell, at most 1000, " \
        r"found 'inf'$"
    with pytest.raises(ValueError, match=resolution):
        frontier.Map.from_numpy(np.zeros((4, 4), bool), big)
    with pytest.raises(ValueError, match=resolution):
        frontier.Map.load(yaml, resolution=(0.1, big))
    with pytest.raises(ValueError, match=r"^--size: expected WxH in metres \(e.g. 25x20\), "
                       r"found 'infx5'$"):
        frontier.Map.generate("empty", size=(big, 5))
    from frontier.gym import ExploreEnv

    for call, message in [
        (lambda: ExploreEnv(office, lam=big), "lam: expected a finite number, found inf"),
        # Regression: a negative price, which rewards travelling, was taken without a word.
        (lambda: ExploreEnv(office, lam=-1), "lam: expected a price per metre travelled of at least 0, found -1"),
        (lambda: ExploreEnv("empty", size=(5, -big)), "--size: expected WxH in metres"),
        (lambda: ExploreEnv("empty", resolution=big), "--resolution: expected a positive"),
    ]:
        with pytest.raises(ValueError, match=f"^{message}"):
            call()


def test_start_beyond_64_bits_is_a_value_error(office):
    """Regression: a start coordinate beyond 64 bits was "start: expected a cell (x, y), found
    1180591620717411303424 (int) among its values", a TypeError, though it is an int, and so
    was np.uint64(2**63); beyond 32 bits (2**33) it was the ValueError it is now for all."""
    for start, shown in [((2**70, 1), "1180591620717411303424, 1"),
                         ((3, -(2**64)), "3, -18446744073709551616"),
                         ((np.uint64(2**63), 2), "9223372036854775808, 2"),
                         ((2**33, 1), "8589934592, 1")]:
        message = rf"^start: expected a cell \(x, y\) of 32-bit integers, found \({shown}\)$"
        with pytest.raises(ValueError, match=message):
            frontier.explore(office, start=start)
        with pytest.raises(ValueError, match=f"^run 0: {message[1:]}"):
            frontier.explore_many([dict(map=office, start=start)])
    with pytest.raises(TypeError, match=r"^start: expected a cell \(x, y\), found np.True_ "
                       r"\(bool\) among its values$"):
        frontier.explore(office, start=(np.True_, 3))
    assert frontier.explore(office, start=(np.uint64(3), np.int8(3))).summary == \
        frontier.explore(office, start=(3, 3)).summary


def test_explore_many_threads_beyond_64_bits_names_the_limit(office):
    """Regression: threads=2**70 was "threads: expected at most 9223372036854775807", a limit
    explore_many does not have (it takes at most 4096, which 5000 was told)."""
    for threads in (5000, 2**63, 2**70, np.uint64(2**64 - 1)):
        with pytest.raises(ValueError, match=f"^threads: expected at most 4096, found {threads}$"):
            frontier.explore_many([dict(map=office)], threads=threads)
    assert len(frontier.explore_many([dict(map=office)], threads=4096)) == 1


def test_explore_many_run_giving_threads_or_progress_refused(office):
    """Regression: a run giving ``threads`` or ``progress``, arguments of the whole batch as
    ``timing`` and ``memory_mb`` are, was copied into its row as a tag and did nothing (no
    warning either: neither is close to an option's name)."""
    for key, value in [("threads", 2), ("progress", True)]:
        with pytest.raises(TypeError, match=rf"^run 1: '{key}': an argument of the whole batch: "
                           rf"explore_many\(runs, {key}=\.\.\.\)$"):
            frontier.explore_many([dict(map=office), dict(map=office, **{key: value})])


def test_native_explore_arguments_name_the_argument(office):
    """Regression: the native ``explore`` and ``explore_many`` (which the .pyi stubs list)
    raised OverflowError for memory_mb=-1 or threads=2**70 ("can't convert negative int to
    unsigned"), took memory_mb=True as a budget of 1 MiB, memory_mb=0 as a budget of none
    and threads=True as one thread, called a progress that is no callable only once the
    runs had ended, and gave PyO3's messages naming no argument ("'int' object is not an
    instance of 'bool'")."""
    native = frontier._native
    one = [(office, None)]
    for call, error, message in [
        (lambda: native.explore(office, None, False, -1), ValueError,
         "memory_mb: expected a positive number of MiB, found -1"),
        (lambda: native.explore(office, None, False, 2**64), ValueError,
         r"memory_mb: expected less than 2\^64 MiB, found 18446744073709551616"),
        (lambda: native.explore(office, None, False, 0), ValueError,
         "memory_mb: expected a positive number of MiB, found 0"),
        (lambda: native.explore(office, None, False, True), TypeError,
         "memory_mb: expected an int, found bool"),
        (lambda: native.explore(office, None, 1), TypeError, "timing: expected a bool, found int"),
        (lambda: native.explore(None), TypeError, "map: expected a frontier.Map, found NoneType"),
        (lambda: native.explore(office, [1]), TypeError,
         "kwargs: expected a dict or None, found list"),
        (lambda: native.explore_many(one, -1), ValueError,
         "threads: expected at least 1, found -1"),
        (lambda: native.explore_many(one, 0), ValueError,
         "threads: expected at least 1, found 0"),
        (lambda: native.explore_many(one, 2**70), ValueError,
         "threads: expected at most 4096, found 1180591620717411303424"),
        (lambda: native.explore_many(one, -(2**200)), ValueError,
         "threads: expected at least 1, found -1606938044258990275541962092341162602522202993782"),
        (lambda: native.explore_many(one, True), TypeError, "threads: expected an int, found bool"),
        (lambda: native.explore_many(one, 1.0), TypeError,
         "threads: expected an int, found float"),
        (lambda: native.explore_many(one, None, 1), TypeError,
         "timing: expected a bool, found int"),
        (lambda: native.explore_many(one, None, False, -1), ValueError,
         "memory_mb: expected a positive number of MiB, found -1"),
        (lambda: native.explore_many(one, None, False, True), TypeError,
         "memory_mb: expected an int, found bool"),
        (lambda: native.explore_many(one, None, False, None, 5), TypeError,
         "progress: expected a callable or None, found int"),
        (lambda: native.explore_many([office]), TypeError,
         r"runs: expected a list of \(frontier.Map, dict or None\) pairs, found list"),
        (lambda: native.explore_many("ab"), TypeError,
         r"runs: expected a list of \(frontier.Map, dict or None\) pairs, found str"),
    ]:
        with pytest.raises(error, match=f"^{message}"):
            call()
    text, _, _ = native.explore(office, {"seed": 1}, np.False_, np.int64(4096))
    assert native.explore_many([(office, {"seed": 1})], np.int32(2), False, 4096) == [text]


def test_explore_many_progress_takes_numpy_bools(office, capsys):
    """Regression: ``progress=np.True_`` was "progress: expected True, False, None or a
    callable, found bool", though ``timing`` takes numpy's bools as Python's."""
    rows = frontier.explore_many([dict(map=office)], progress=np.True_)
    assert "explore_many" in capsys.readouterr().err  # tqdm's bar or the plain line
    assert frontier.explore_many([dict(map=office)], progress=np.False_) == rows
    assert capsys.readouterr().err == ""


def test_regression_explore_many_checks_every_run_before_any_starts(office):
    """Regression: a run whose sensor its map's cells cannot carry (sonar on 0.25 m cells),
    or whose start is on a wall, was refused only when it started, after the runs before
    it had run (and their results were lost)."""
    # A run of seconds first: had it started, progress would have been told of it.
    slow = dict(map=frontier.Map.generate("office", seed=0, size=(40, 30), resolution=0.1),
                strategy="ma-cc", robots=4, seed=1)
    for bad, message in [
        (dict(map=office, sensor="sonar"), "^run 1: .*sonar"),
        (dict(map=office, start=(0, 0)), r"^run 1: --start 0,0: the cell is occupied"),
    ]:
        calls = []
        with pytest.raises(ValueError, match=message):
            frontier.explore_many(
                [slow, bad], threads=1, progress=lambda done, n: calls.append(done)
            )
        assert calls == [], "no run started"
    # A good start is still taken, and the sensor checked once serves every run.
    rows = frontier.explore_many([dict(map=office, seed=k, start=(5, 5)) for k in range(3)])
    assert len(rows) == 3


def test_regression_numpy_complex_numbers_are_no_real_numbers(office):
    """Regression: a numpy complex number was taken for its real part (with only a
    ComplexWarning) wherever a real number is taken, where Python's complex was refused:
    Map.from_numpy(a, np.complex128(0.1+5j)) made a map of 0.1 m cells."""
    import warnings

    a = office.to_numpy()
    c = np.complex128(0.25 + 5j)
    for call, message in [
        (lambda: frontier.Map.from_numpy(a, c),
         "resolution: expected a number of metres per cell, found complex128"),
        (lambda: frontier.Map.from_numpy(a, np.complex64(0.25)),
         "resolution: expected a number of metres per cell, found complex64"),
        (lambda: frontier.Map.from_numpy(a, np.array(0.25 + 0j)),
         "resolution: expected a number of metres per cell, found ndarray"),
        (lambda: frontier.explore(office, clearance=np.complex128(0.1 + 3j)),
         "clearance: expected a number of metres, found complex128"),
        (lambda: frontier.explore(office, speed=np.clongdouble(1)),
         "speed: expected a number of metres per second, found clongdouble"),
        (lambda: frontier.explore(office, goal=np.complex128(0.9)),
         "goal: expected a number or None, found complex128"),
        (lambda: frontier.explore_many([dict(map=office, clearance=c)]),
         "run 0: clearance: expected a number of metres, found complex128"),
        (lambda: frontier.Map.generate("office", size=(np.complex128(20 + 1j), 20)),
         r"size: expected \(width, height\) in metres, found np.complex128\(20\+1j\) "
         r"\(complex128\) among its values"),
        (lambda: frontier.Map.generate("office", resolution=c),
         "resolution: expected a number of metres per cell, found complex128"),
        (lambda: frontier.Map.load("plan.png", resolution=c),
         r"resolution: expected a number of metres per cell or a pair \(x, y\), "
         "found complex128"),
        (lambda: frontier.Map.load("plan.png", resolution=(0.25, np.complex64(0.25))),
         "resolution: expected a number of metres per cell or a pair"),
        (lambda: frontier.gym.ExploreEnv(office, clearance=np.complex128(0.1 + 1j)),
         "clearance: expected a number of metres, found complex128"),
        (lambda: frontier.explore(office, clearance=0.1 + 0j),
         "clearance: expected a number of metres, found complex"),
    ]:
        # Warnings recorded, not raised: a ComplexWarning raised as an error would make
        # the conversion fail, which is what the test is about.
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            with pytest.raises(TypeError, match=f"^{message}"):
                call()
        assert [str(w.message) for w in seen] == [], message
    # Real numpy numbers, and 0-d arrays of them, are still numbers.
    assert frontier.Map.from_numpy(a, np.array(0.25)).resolution == 0.25
    assert frontier.Map.from_numpy(a, np.float32(0.25)).resolution == 0.25

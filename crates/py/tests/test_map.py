"""frontier.Map: loading, generating, numpy in and out, saving, and refusing bad input."""

import numpy as np
import pytest

import frontier


def test_generate_is_deterministic(office):
    again = frontier.Map.generate("office", seed=3, size=(15, 12), resolution=0.25)
    assert office.shape == (48, 60)
    assert office.resolution == 0.25
    assert office.name == "office-s3-15x12m-r0.25"
    assert np.array_equal(office.to_numpy(), again.to_numpy())


def test_numpy_round_trip(office):
    a = office.to_numpy()
    assert a.dtype == np.uint8 and set(np.unique(a)) <= {0, 1, 2}
    b = frontier.Map.from_numpy(a, 0.25)
    assert np.array_equal(b.to_numpy(), a)
    occ = frontier.Map.from_numpy(a == 2, 0.25)
    assert np.array_equal(occ.to_numpy() == 2, a == 2)
    assert occ.free_cells == int((a != 2).sum())


def test_save_and_load_every_format(office, tmp_path):
    yaml = tmp_path / "office.yaml"
    office.save(yaml)
    loaded = frontier.Map.load(yaml)
    assert loaded.name == "office" and loaded.resolution == 0.25
    assert np.array_equal(loaded.to_numpy(), office.to_numpy())
    png = tmp_path / "plan.png"
    office.save(png)
    bare = frontier.Map.load(png, resolution=0.25)
    assert np.array_equal(bare.to_numpy() == 2, office.to_numpy() == 2)
    text = tmp_path / "tiny.map"
    text.write_text("type octile\nheight 3\nwidth 4\nmap\n@@@@\n@..@\n@@@@\n")
    assert frontier.Map.load(text).shape == (3, 4)


def test_wrong_dtype_and_shape_raise_type_error():
    with pytest.raises(TypeError, match="2-D numpy array of bool .* found a 2-D array of dtype float64"):
        frontier.Map.from_numpy(np.zeros((4, 4)), 0.1)
    with pytest.raises(TypeError, match="found a 3-D array"):
        frontier.Map.from_numpy(np.zeros((2, 4, 4), dtype=np.uint8), 0.1)
    with pytest.raises(TypeError):
        frontier.Map.from_numpy([[0, 1]], 0.1)


def test_bad_values_raise_value_error(tmp_path):
    with pytest.raises(ValueError, match=r"expected cell values 0 \(unknown\), 1 \(free\) or 2 \(occupied\), found 7 at row 1, column 2"):
        a = np.ones((3, 4), dtype=np.uint8)
        a[1, 2] = 7
        frontier.Map.from_numpy(a, 0.1)
    with pytest.raises(ValueError, match="--resolution: expected a positive number"):
        frontier.Map.from_numpy(np.ones((3, 3), dtype=np.uint8), -1.0)
    # Regression: 1e308 m per cell was accepted and every length came out infinite.
    with pytest.raises(ValueError, match="--resolution: expected a positive number of metres per cell, at most 1000"):
        frontier.Map.from_numpy(np.ones((3, 3), dtype=np.uint8), 1e308)
    with pytest.raises(ValueError, match="--env: "):
        frontier.Map.generate("castle")
    with pytest.raises(ValueError, match="--resolution is required for a bare bitmap"):
        png = tmp_path / "x.png"
        frontier.Map.from_numpy(np.ones((3, 3), dtype=np.uint8), 0.1).save(png)
        frontier.Map.load(png)
    with pytest.raises(ValueError, match="cannot read"):
        frontier.Map.load(tmp_path / "missing.yaml")


def test_load_reads_what_the_cli_reads(cli, office, tmp_path, write_png):
    """Regression: Map.load read neither MCAP recordings nor dungeon PNGs, which the CLI
    reads (`--map run.mcap`, `--dungeon`)."""
    import json
    import subprocess

    yaml = tmp_path / "office.yaml"
    office.save(yaml)
    rec = tmp_path / "run.mcap"
    subprocess.run([cli, "explore", "--map", str(yaml), "--max-moves", "5", "--mcap", str(rec)],
                   check=True, capture_output=True)
    loaded = frontier.Map.load(rec, topic="/map")
    assert np.array_equal(loaded.to_numpy(), office.to_numpy())
    assert loaded.resolution == office.resolution and loaded.start is None
    with pytest.raises(ValueError, match="an MCAP recording's map carries its own resolution"):
        frontier.Map.load(rec, resolution=0.1)
    with pytest.raises(ValueError, match="topic: chooses the map topic of an MCAP recording"):
        frontier.Map.load(yaml, topic="/map")

    # A 12 x 8 dungeon room: walls (0) around free space (255), a start (208) at (4, 3).
    pixels = np.full((8, 12), 255, np.uint8)
    pixels[[0, -1], :] = 0
    pixels[:, [0, -1]] = 0
    pixels[3, 4] = 208
    png = tmp_path / "dungeon.png"
    write_png(png, pixels)
    d = frontier.Map.load(png, resolution=0.1, dungeon=True)
    assert d.start == (4, 3) and d.shape == (8, 12)
    out = subprocess.run([cli, "explore", "--map", str(png), "--resolution", "0.1", "--dungeon",
                          "--json", "--no-timing"], check=True, capture_output=True, text=True)
    assert frontier.explore(d).summary == json.loads(out.stdout)
    with pytest.raises(ValueError, match="dungeon: expected one resolution"):
        frontier.Map.load(png, dungeon=True)


def test_dungeon_border_reads_what_the_cli_reads(cli, tmp_path, write_png):
    """Regression: border was ignored for dungeon PNGs (Map.load read the picture as it
    was, as did the CLI's --dungeon --border); it adds a wall around the map as for a bare
    bitmap, the start moving with the cells, the same in Python and the CLI."""
    import json
    import subprocess

    # A 12 x 8 dungeon of free space (255) to its edges, a start (208) at (4, 3).
    pixels = np.full((8, 12), 255, np.uint8)
    pixels[3, 4] = 208
    png = tmp_path / "dungeon.png"
    write_png(png, pixels)
    d = frontier.Map.load(png, resolution=0.1, border=True, dungeon=True)
    assert d.shape == (10, 14) and d.start == (5, 4)
    assert d.origin == pytest.approx((-0.1, -0.1, 0.0))
    cells = d.to_numpy()
    assert (cells[[0, -1], :] == 2).all() and (cells[:, [0, -1]] == 2).all()
    assert (cells[1:-1, 1:-1] == 1).all()
    info = json.loads(subprocess.run(
        [cli, "map", "info", str(png), "--resolution", "0.1", "--dungeon", "--border", "--json"],
        check=True, capture_output=True, text=True).stdout)
    assert (info["height"], info["width"]) == d.shape
    assert tuple(info["start"]) == d.start
    assert (info["free"], info["occupied"]) == (d.free_cells, 14 * 10 - d.free_cells)
    out = subprocess.run([cli, "explore", "--map", str(png), "--resolution", "0.1", "--dungeon",
                          "--border", "--json", "--no-timing"],
                         check=True, capture_output=True, text=True)
    assert frontier.explore(d).summary == json.loads(out.stdout)


def test_memory_mb_applies_to_map_loading(tmp_path):
    """Regression: Map.load checked a map's loading against the machine's memory only, with
    no budget of the user's (explore's memory_mb came after the map was loaded); it takes
    memory_mb and refuses a map whose loading would not fit before decoding it."""
    # A header claiming 16384 x 16384 pixels and no pixels: the estimate refuses it, not
    # the missing pixels.
    pgm = tmp_path / "claimed.pgm"
    pgm.write_bytes(b"P5\n16384 16384\n255\n")
    with pytest.raises(ValueError, match=r"claimed\.pgm: loading this 16384x16384 PGM image "
                       r"needs about 1281 MiB, more than --memory-mb 64; "):
        frontier.Map.load(pgm, resolution=0.1, memory_mb=64)
    with pytest.raises(ValueError, match="truncated"):
        frontier.Map.load(pgm, resolution=0.1)
    small = tmp_path / "small.pgm"
    small.write_bytes(b"P5\n4 3\n255\n" + bytes([254] * 11 + [0]))
    assert frontier.Map.load(small, resolution=0.1, memory_mb=np.int64(1)).shape == (3, 4)
    with pytest.raises(ValueError, match="memory_mb: expected a positive number of MiB, found 0"):
        frontier.Map.load(small, resolution=0.1, memory_mb=0)
    with pytest.raises(ValueError, match="memory_mb: expected a positive number of MiB, found -1"):
        frontier.Map.load(small, resolution=0.1, memory_mb=-1)
    with pytest.raises(ValueError, match=r"memory_mb: expected less than 2\^64 MiB, found 18446744073709551616"):
        frontier.Map.load(small, resolution=0.1, memory_mb=2**64)
    for bad in (2.5, True, "64"):
        with pytest.raises(TypeError, match=f"memory_mb: expected an int, found {type(bad).__name__}"):
            frontier.Map.load(small, resolution=0.1, memory_mb=bad)


def test_mcap_map_larger_than_the_budget_is_refused_before_loading(cli, tmp_path):
    """Regression: a recording's map was loaded whatever the memory; it is refused from its
    message's header, naming the file, the topic, the size, the bytes needed and the
    budget."""
    import subprocess

    yaml = tmp_path / "open.yaml"
    frontier.Map.from_numpy(np.ones((1000, 1000), dtype=np.uint8), 0.05).save(yaml)
    rec = tmp_path / "run.mcap"
    subprocess.run([cli, "explore", "--map", str(yaml), "--max-moves", "1", "--mcap", str(rec)],
                   check=True, capture_output=True)
    with pytest.raises(ValueError, match=r"run\.mcap: topic /map, message at 0 ns: loading this "
                       r"1000x1000 OccupancyGrid needs about 3 MiB, more than --memory-mb 2; "):
        frontier.Map.load(rec, memory_mb=2)
    assert frontier.Map.load(rec, memory_mb=4).shape == (1000, 1000)


def test_from_numpy_refuses_more_cells_than_a_map_file_may_hold():
    # Regression: from_numpy copied any array, 2^31 cells and more, where every map file
    # is refused above 2^28 cells (cells are numbered in 32 bits). Broadcast views: no
    # memory behind them.
    for dtype in (np.uint8, np.bool_):
        big = np.broadcast_to(np.zeros(1, dtype=dtype), (2, 2**27 + 1))
        with pytest.raises(ValueError, match=r"map too large: 134217729x2 cells is more than the limit of 268435456 cells"):
            frontier.Map.from_numpy(big, 0.1)
    ok = np.broadcast_to(np.ones(1, dtype=np.uint8), (2, 2**27))
    assert frontier.Map.from_numpy(ok, 0.1).shape == (2, 2**27)


def _same_map(a, b):
    assert np.array_equal(a.to_numpy(), b.to_numpy())
    assert (a.resolution, a.name, a.origin, a.start) == (b.resolution, b.name, b.origin, b.start)


def test_regression_maps_pickle_and_copy(office, tmp_path, write_png):
    import copy
    import pickle
    from concurrent.futures import ProcessPoolExecutor
    from multiprocessing import get_context

    # A ROS map with an origin, a dungeon map with a marked start, and a generated one.
    (tmp_path / "o.pgm").write_bytes(b"P5\n4 3\n255\n" + bytes([254] * 11 + [0]))
    (tmp_path / "o.yaml").write_text(
        "image: o.pgm\nresolution: 0.5\norigin: [-1.5, 2.25, 0.5]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    pixels = np.full((8, 12), 255, np.uint8)
    pixels[[0, -1], :] = 0
    pixels[:, [0, -1]] = 0
    pixels[5, 4] = 208
    write_png(tmp_path / "d.png", pixels)
    ros = frontier.Map.load(tmp_path / "o.yaml")
    dungeon = frontier.Map.load(tmp_path / "d.png", resolution=0.1, dungeon=True)
    assert ros.origin == (-1.5, 2.25, 0.5) and dungeon.start == (4, 5)
    for m in (office, ros, dungeon):
        for other in (pickle.loads(pickle.dumps(m)), copy.copy(m), copy.deepcopy(m)):
            _same_map(m, other)
    again = pickle.loads(pickle.dumps(dungeon))
    assert frontier.explore(again, seed=1).summary == frontier.explore(dungeon, seed=1).summary
    # What Gymnasium's async vector env and a spawned process pool need.
    with ProcessPoolExecutor(1, mp_context=get_context("spawn")) as pool:
        got = pool.submit(frontier.explore, office, seed=4).result()
    assert got.summary == frontier.explore(office, seed=4).summary
    with pytest.raises(ValueError, match=r"cells: expected 2 x 2 cells, found 3"):
        frontier._native._restore_map(b"\x01\x01\x01", 2, 2, 0.1, (0.0, 0.0, 0.0), "m", None)


def test_regression_conversion_errors_name_the_argument(tmp_path):
    from frontier.gym import ExploreEnv

    a = np.zeros((6, 6), bool)
    m = frontier.Map.from_numpy(a, 0.1)
    (tmp_path / "m.txt").write_text("....\n....\n")
    cases = [
        (lambda: frontier.Map.from_numpy(a, "0.1"), TypeError,
         "resolution: expected a number of metres per cell, found str"),
        (lambda: frontier.Map.from_numpy(a, True), TypeError, "resolution: expected a number"),
        (lambda: frontier.Map.load(tmp_path / "m.txt", border="x"), TypeError,
         "border: expected a bool, found str"),
        (lambda: frontier.Map.load(tmp_path / "m.txt", dungeon=1), TypeError,
         "dungeon: expected a bool, found int"),
        (lambda: frontier.Map.generate("office", seed=-1), ValueError,
         r"seed: expected an integer in 0\.\.2\^64, found -1"),
        (lambda: frontier.Map.generate("office", seed=2**64), ValueError,
         r"seed: expected an integer in 0\.\.2\^64, found 18446744073709551616"),
        (lambda: frontier.Map.generate("office", seed=1.5), TypeError,
         "seed: expected an int, found float"),
        (lambda: frontier.Map.generate("office", resolution="x"), TypeError,
         "resolution: expected a number of metres per cell, found str"),
        (lambda: ExploreEnv(m, lam="x"), TypeError, "lam: expected a number"),
        (lambda: ExploreEnv(m, gain="yes"), TypeError, "gain: expected a bool, found str"),
        (lambda: ExploreEnv(m, max_path_m="far"), TypeError, "max_path_m: expected a number"),
        (lambda: ExploreEnv(m, k=2**70), ValueError, "k: expected at most"),
        (lambda: ExploreEnv(m, candidates=3), TypeError, "candidates: expected a str"),
        (lambda: frontier.explore(m, timing="no"), TypeError, "timing: expected a bool"),
        (lambda: frontier.explore(m, trajectories=0), TypeError, "trajectories: expected a bool"),
        (lambda: frontier.explore_many([dict(map=m)], timing="no"), TypeError,
         "timing: expected a bool"),
    ]
    for call, kind, message in cases:
        with pytest.raises(kind, match=message):
            call()
    assert frontier.Map.generate("cave", seed=np.uint64(2**63), size=(8, 8)).shape == (80, 80)
    assert frontier.Map.from_numpy(a, np.float32(0.5)).resolution == 0.5
    assert ExploreEnv(m, lam=np.float64(0.5), gain=np.True_) is not None


def test_regression_pairs_may_be_any_sequence_of_two(office, tmp_path):
    from frontier.gym import ExploreEnv

    tuple_made = frontier.Map.generate("office", seed=1, size=(12, 10))
    for size in ([12, 10], np.array([12, 10]), np.array([12.0, 10.0])):
        assert np.array_equal(frontier.Map.generate("office", seed=1, size=size).to_numpy(),
                              tuple_made.to_numpy())
    assert ExploreEnv("office", size=[12, 10]).observation_space["belief"].shape == \
        ExploreEnv("office", size=(12, 10)).observation_space["belief"].shape
    r = frontier.explore(office, start=(3, 3))
    for start in ([3, 3], np.array([3, 3]), (np.int32(3), 3)):
        assert frontier.explore(office, start=start).summary == r.summary
    office.save(tmp_path / "o.pgm")
    by_tuple = frontier.Map.load(tmp_path / "o.pgm", resolution=(0.05, 0.05))
    for res in ([0.05, 0.05], np.array([0.05, 0.05])):
        assert frontier.Map.load(tmp_path / "o.pgm", resolution=res).resolution == \
            by_tuple.resolution
    for call, kind, message in [
        (lambda: frontier.Map.generate("office", size=[10]), ValueError,
         r"size: expected \(width, height\) in metres, found 1 values"),
        (lambda: frontier.Map.generate("office", size="10x8"), TypeError,
         r"size: expected \(width, height\) in metres, found str"),
        (lambda: ExploreEnv("office", size=[12, "8"]), TypeError,
         r"size: expected \(width, height\) in metres, found '8' \(str\)"),
        (lambda: ExploreEnv("office", size=5), TypeError, "size: expected"),
        (lambda: frontier.explore(office, start=[3.5, 3]), TypeError,
         r"start: expected a cell \(x, y\), found 3.5 \(float\)"),
        (lambda: frontier.explore(office, start=[1, 2, 3]), ValueError,
         r"start: expected a cell \(x, y\), found 3 values"),
        (lambda: frontier.Map.load(tmp_path / "o.pgm", resolution=[0.05]), ValueError,
         "resolution: expected a number of metres per cell or a pair"),
    ]:
        with pytest.raises(kind, match=message):
            call()


def test_regression_str_and_path_arguments_name_the_argument(tmp_path):
    """Regression: a str or path argument of another type gave PyO3's "'int' object is not an
    instance of 'str'" or os.fspath's message, which name no argument."""
    a = np.zeros((6, 6), bool)
    m = frontier.Map.from_numpy(a, 0.1)
    (tmp_path / "m.txt").write_text("....\n....\n")
    for call, message in [
        (lambda: frontier.Map.generate(3), "kind: expected a str, found int"),
        (lambda: frontier.Map.generate(None, seed=1), "kind: expected a str, found NoneType"),
        (lambda: frontier.Map.from_numpy(a, 0.1, name=7), "name: expected a str, found int"),
        (lambda: frontier.Map.from_numpy(a, 0.1, b"m"), "name: expected a str, found bytes"),
        (lambda: frontier.Map.load(3), r"path: expected a path \(a str or os.PathLike\), found int"),
        (lambda: frontier.Map.load(tmp_path / "m.txt", topic=5),
         "topic: expected a str or None, found int"),
        (lambda: m.save(None), r"path: expected a path \(a str or os.PathLike\), found NoneType"),
    ]:
        with pytest.raises(TypeError, match=f"^{message}"):
            call()
    # What they take: str subclasses (numpy's), paths, None for an optional str.
    assert frontier.Map.generate(np.str_("empty"), size=(4, 4)).name.startswith("empty")
    assert frontier.Map.from_numpy(a, 0.1, name=np.str_("six")).name == "six"
    assert frontier.Map.load(str(tmp_path / "m.txt"), topic=None).shape == (2, 4)
    # The signature still shows the default name.
    assert 'name="array"' in frontier.Map.from_numpy.__text_signature__


def test_restore_map_arguments_checked(office):
    """Regression: ``_restore_map`` (what unpickling a map calls) raised OverflowError for a
    negative width ("can't convert negative int to unsigned") or a start beyond 32 bits,
    took a bool as the resolution 1 m, and made a map with a NaN origin or a start outside
    it (a run on it then failed with "--start 50,50: outside the 2x2 map")."""
    restore = frontier._native._restore_map
    cells, origin = b"\x01" * 4, (0.0, 0.0, 0.0)
    for args, error, message in [
        ((cells, -1, 2, 0.1, origin, "m", None), ValueError,
         r"width: expected a number of cells in 1\.\.2\^64, found -1"),
        ((cells, 2, 0, 0.1, origin, "m", None), ValueError,
         r"height: expected a number of cells in 1\.\.2\^64, found 0"),
        ((cells, 2.0, 2, 0.1, origin, "m", None), TypeError, "width: expected an int, found float"),
        ((cells, 2, 2, True, origin, "m", None), TypeError,
         "resolution: expected a number of metres per cell, found bool"),
        ((cells, 2, 2, 0.1, (float("nan"), 0.0, 0.0), "m", None), ValueError,
         r"origin: expected finite numbers \(x, y, yaw\), found \(NaN, 0, 0\)"),
        ((cells, 2, 2, 0.1, origin, 5, None), TypeError, "name: expected a str, found int"),
        ((cells, 2, 2, 0.1, origin, "m", (50, 50)), ValueError,
         r"start: expected a cell of the 2x2 map, found \(50, 50\)"),
        ((cells, 2, 2, 0.1, origin, "m", (0, -1)), ValueError,
         r"start: expected a cell of the 2x2 map, found \(0, -1\)"),
        ((cells, 2, 2, 0.1, origin, "m", (2**40, 0)), ValueError,
         r"start: expected a cell \(x, y\) of 32-bit integers, found \(1099511627776, 0\)"),
    ]:
        with pytest.raises(error, match=f"^{message}"):
            restore(*args)
    m = restore(cells, np.int64(2), 2, np.float32(0.5), origin, "m", (np.int32(1), 1))
    assert (m.shape, m.resolution, m.start) == ((2, 2), 0.5, (1, 1))


def test_pair_given_as_a_set_or_a_mapping_refused(office):
    """Regression: a pair may be any sequence of two, but a set or a mapping has a length of
    two without a first and a second item: the environments took ``size={30, 12}`` as
    12 x 30 m (a set's own order) and ``size={12: 'a', 30: 'b'}`` as its keys, and the native
    arguments took ``size={0: 30, 1: 12}`` by its keys 0 and 1."""
    from frontier.gym import ExploreEnv

    for pair in ({30, 12}, frozenset((30, 12)), {12: "a", 30: "b"}, {0: 30, 1: 12}):
        found = type(pair).__name__
        for call in (lambda: frontier.Map.generate("office", size=pair),
                     lambda: ExploreEnv("office", size=pair)):
            with pytest.raises(TypeError, match=rf"^size: expected \(width, height\) in metres, "
                               rf"found {found}$"):
                call()
        with pytest.raises(TypeError, match=rf"^start: expected a cell \(x, y\), found {found}$"):
            frontier.explore(office, start=pair)
    with pytest.raises(TypeError, match=r"^resolution: expected a number of metres per cell or "
                       r"a pair \(x, y\), found dict$"):
        frontier.Map.load("office.pgm", resolution={0: 0.1, 1: 0.1})


def test_regression_a_map_repr_prints_its_resolution_short():
    """Regression: a map at 1e-300 m per cell printed its resolution in 300 digits."""
    tiny = frontier.Map.from_numpy(np.zeros((2, 3), bool), 1e-300)
    assert repr(tiny) == f"Map('{tiny.name}', 3x2 cells at 1e-300 m)"
    assert "at 0.05 m" in repr(frontier.Map.from_numpy(np.zeros((2, 3), bool), 0.05))


def test_regression_an_empty_path_and_a_huge_resolution_are_named_plainly():
    """Regression: Map.load('') said ': unknown map format ""…', and a resolution of
    1e308 was echoed in 309 digits."""
    with pytest.raises(ValueError, match="^path: expected a path, found an empty one$"):
        frontier.Map.load("")
    with pytest.raises(ValueError, match=r"at most 1000, found '1e308'$"):
        frontier.Map.from_numpy(np.zeros((2, 2), bool), 1e308)


def test_regression_an_unpickled_map_equals_the_map(office):
    """Regression: Map had no __eq__, so pickle.loads(pickle.dumps(m)) == m was False."""
    import pickle

    again = pickle.loads(pickle.dumps(office))
    assert again == office and hash(again) == hash(office)
    assert len({office, again}) == 1
    other = frontier.Map.generate("office", seed=4, size=(15, 12), resolution=0.25)
    assert other != office
    array = office.to_numpy()
    # Equality is of the contents: the same cells, resolution, origin and name.
    assert frontier.Map.from_numpy(array, 0.25, name=office.name) == office
    assert frontier.Map.from_numpy(array, 0.5, name=office.name) != office
    renamed = frontier.Map.from_numpy(array, 0.25, name="other")
    assert renamed != office
    assert office != "office"


def test_regression_bool_array_with_other_bytes():
    # A bool view of bytes other than 0 and 1: numpy takes every nonzero byte for True, and
    # the map read them as Rust bools (undefined behaviour): 5 became a cell of value 6, and
    # 255 a cell of value 0.
    raw = np.array([[0, 5, 1, 0], [0, 0, 0, 255], [2, 0, 128, 0]], np.uint8)
    b = raw.view(bool)
    m = frontier.Map.from_numpy(b, 1.0)
    expected = np.where(raw != 0, 2, 1).astype(np.uint8)
    assert np.array_equal(m.to_numpy(), expected)
    assert m == frontier.Map.from_numpy(raw != 0, 1.0)
    assert m.free_cells == int((raw == 0).sum())
    # Not contiguous, and Fortran-ordered, read the same.
    wide = np.zeros((3, 8), np.uint8)
    wide[:, ::2] = raw
    assert np.array_equal(frontier.Map.from_numpy(wide.view(bool)[:, ::2], 1.0).to_numpy(), expected)
    assert np.array_equal(frontier.Map.from_numpy(np.asfortranarray(b), 1.0).to_numpy(), expected)
    # The array is left as it was.
    assert b.dtype == np.bool_ and np.array_equal(b.view(np.uint8), raw)


def test_regression_ctrl_c_interrupts_generating_a_large_map():
    """Regression: ``Map.generate`` of a large map ran to its end before Python saw Ctrl-C
    (a 200 x 200 m cave at 0.05 m took tens of seconds, 2 s now); ``Map.load`` held the
    GIL as it read. Both now wake every 0.1 s to let Python handle signals."""
    import _thread
    import signal
    import threading
    import time

    # About 1.3 s in a release build: long beside the 0.05 s before the interrupt and the
    # 0.1 s between looks.
    args = dict(kind="cave", seed=0, size=(160, 160), resolution=0.05)
    t = time.perf_counter()
    frontier.Map.generate(**args)
    whole = time.perf_counter() - t
    # Python's own Ctrl-C handler, which a process started in the background (SIGINT
    # ignored) does not get, and without which interrupt_main does nothing.
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        t = time.perf_counter()
        threading.Timer(0.05, _thread.interrupt_main).start()
        with pytest.raises(KeyboardInterrupt):
            frontier.Map.generate(**args)
        interrupted = time.perf_counter() - t
    finally:
        signal.signal(signal.SIGINT, before)
    # Without the checks the interrupt was raised only once the map was made.
    assert interrupted < whole / 2, (interrupted, whole)

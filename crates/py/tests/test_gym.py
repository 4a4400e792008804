"""frontier.gym: Gymnasium's checker, determinism, baselines equal to explore, vector env."""

import gc
import os
import time

import gymnasium
import numpy as np
import pytest
from gymnasium.utils import seeding
from gymnasium.utils.env_checker import check_env

import frontier
from frontier.gym import Baseline, ExploreEnv, ExploreVectorEnv, RandomPolicy


def episode(env, policy, seed):
    """Observations' digests, rewards and infos of one whole episode."""
    obs, info = env.reset(seed=seed)
    trace = [(obs["belief"].tobytes(), obs["candidates"].tobytes(), info["seed"])]
    while True:
        a = policy(env) if isinstance(policy, Baseline) else policy(obs)
        obs, reward, terminated, truncated, info = env.step(a)
        trace.append((obs["belief"].tobytes(), obs["candidates"].tobytes(), reward))
        if terminated or truncated:
            return trace, info, terminated


def test_check_env_passes(office):
    for kwargs in (dict(), dict(view=21, gain=True, k=4), dict(candidates="centroids")):
        check_env(ExploreEnv(office, **kwargs), skip_render_check=True)


def test_observation_space_bounds_the_pose_and_candidates_by_the_map(office):
    """A pose and a candidate lie on the map's cells (any cell, with a view, whose maps may
    differ in size), and a heading within [-pi, pi]; every observation of an episode is in
    the space."""
    env = ExploreEnv(office, k=16)
    h, w = env.observation_space["belief"].shape
    pose = env.observation_space["pose"]
    assert pose.low.tolist() == pytest.approx([0, 0, -np.pi])
    assert pose.high.tolist() == pytest.approx([w - 1, h - 1, np.pi])
    cand = env.observation_space["candidates"]
    assert cand.high[:, :2].tolist() == [[w - 1, h - 1]] * 16
    assert np.isinf(cand.high[:, 2:]).all() and (cand.low == 0).all()
    assert np.isinf(ExploreEnv(office, view=21).observation_space["pose"].high[:2]).all()
    policy = RandomPolicy(3)
    obs, _ = env.reset(seed=2)
    while True:
        assert env.observation_space.contains(obs), obs["pose"]
        obs, _, terminated, truncated, _ = env.step(policy(obs))
        if terminated or truncated:
            break
    assert env.observation_space.contains(obs)


def test_registered():
    env = gymnasium.make("frontier/Explore-v0", maps="cave", size=(8, 8), resolution=0.25, k=8)
    obs, _ = env.reset(seed=1)
    assert obs["belief"].shape == (32, 32) and obs["candidates"].shape == (8, 4)


def test_same_seed_identical_episodes(office):
    env = ExploreEnv([office], k=8, lam=0.1)
    a = episode(env, RandomPolicy(5), 11)
    b = episode(env, RandomPolicy(5), 11)
    assert a == b
    c = episode(env, RandomPolicy(5), 12)
    assert c[0][0][2] != a[0][0][2]


@pytest.mark.parametrize("preset", ["cf-rr", "cf", "random", "yamauchi"])
def test_baseline_episode_equals_explore(office, preset):
    env = ExploreEnv(office, strategy=preset, k=4096)
    _, info, terminated = episode(env, Baseline(preset), 3)
    assert terminated
    ref = frontier.explore(office, strategy=preset, seed=info["seed"])
    assert info["path_length_m"] == pytest.approx(ref.path_length_m[0], abs=1e-4)
    assert (info["decisions"], info["moves"]) == (ref.decisions, ref.moves)
    assert info["coverage"] == pytest.approx(ref.coverage, abs=1e-6)


def test_reward_and_budget(office):
    env = ExploreEnv(office, lam=0.5, max_steps=3, render_mode="rgb_array")
    obs, info = env.reset(seed=0)
    cov0 = info["coverage"]
    total, steps = 0.0, 0
    while True:
        obs, r, terminated, truncated, info = env.step(0)
        total += r
        steps += 1
        if terminated or truncated:
            break
    assert truncated and not terminated and steps == 3
    reachable = frontier.explore(office, seed=info["seed"]).reachable_cells
    area = (info["coverage"] - cov0) * reachable * office.resolution**2
    assert total == pytest.approx(area - 0.5 * info["path_length_m"], abs=1e-6)
    assert env.render().shape == office.shape + (3,)
    with pytest.raises(ValueError, match="after the episode ended"):
        env.step(0)


def test_step_before_reset_is_reset_needed(office):
    """Regression: stepping (or asking a baseline) before the first reset raised ValueError
    "after the episode ended"; Gymnasium's own wrapper (``gym.make``) raises ResetNeeded,
    and so do the environments now, each of the three."""
    from frontier.pettingzoo import ExploreParallelEnv

    env = ExploreEnv(office)
    with pytest.raises(gymnasium.error.ResetNeeded, match="call reset"):
        env.step(0)
    with pytest.raises(gymnasium.error.ResetNeeded, match="call reset"):
        Baseline("cf-rr")(env)
    venv = ExploreVectorEnv(2, office)
    with pytest.raises(gymnasium.error.ResetNeeded, match="call reset"):
        venv.step(np.zeros(2, dtype=np.int64))
    with pytest.raises(gymnasium.error.ResetNeeded, match="call reset"):
        Baseline("cf-rr")(venv)
    team = ExploreParallelEnv(office, robots=2)
    with pytest.raises(gymnasium.error.ResetNeeded, match="call reset"):
        team.step({"robot_0": 0})
    with pytest.raises(gymnasium.error.ResetNeeded, match="call reset"):
        team.baseline_actions("cf-rr")
    # after a reset they step
    env.reset(seed=0)
    env.step(Baseline("cf-rr")(env))
    venv.reset(seed=0)
    venv.step(Baseline("cf-rr")(venv))
    team.reset(seed=0)
    team.step(team.baseline_actions("cf-rr"))


def test_random_policy_seed_is_checked():
    """Regression: ``RandomPolicy(-1)`` raised numpy's "expected non-negative integer",
    naming no argument."""
    with pytest.raises(ValueError, match="seed: expected a non-negative int, found -1"):
        RandomPolicy(-1)
    with pytest.raises(TypeError, match="seed: expected an int or None, found str"):
        RandomPolicy("x")
    with pytest.raises(TypeError, match="found bool"):
        RandomPolicy(True)
    RandomPolicy(np.int64(3))
    RandomPolicy(None)


def test_invalid_actions(office):
    env = ExploreEnv(office, k=8, invalid_action="raise")
    obs, _ = env.reset(seed=0)
    n = int(obs["action_mask"].sum())
    with pytest.raises(ValueError, match=f"action 99: expected the index of one of the {n} candidates"):
        env.step(99)
    with pytest.raises(ValueError, match="action -1"):
        env.step(-1)
    with pytest.raises(ValueError, match="--strategy: unknown strategy"):
        ExploreEnv(office, strategy="nope")
    with pytest.raises(ValueError, match="candidates: expected af, centroids, rfe or cc"):
        ExploreEnv(office, candidates="all")
    with pytest.raises(ValueError, match="maps of different sizes need a robot-centred view"):
        ExploreEnv([office, frontier.Map.generate("cave", size=(8, 8), resolution=0.25)])


def test_action_masks_follow_the_observation(office):
    """action_masks() (sb3-contrib's MaskablePPO asks for it) is the observation's mask as
    bools, step after step, and needs a reset first."""
    env = ExploreEnv(office, k=8)
    with pytest.raises(gymnasium.error.ResetNeeded, match="call reset"):
        env.action_masks()
    obs, _ = env.reset(seed=1)
    for _ in range(6):
        mask = env.action_masks()
        assert mask.dtype == bool and mask.shape == (8,)
        assert mask.tolist() == [bool(v) for v in obs["action_mask"]]
        assert mask.any()
        obs, _, terminated, truncated, _ = env.step(int(np.flatnonzero(mask)[-1]))
        if terminated or truncated:
            break


def test_wrapped_actions_take_the_candidate_modulo_the_offer(office):
    """The default invalid_action="wrap": an index beyond the candidates offered (or
    negative) is taken modulo their number, a valid one as it is."""
    wrapping, plain = ExploreEnv(office, k=8), ExploreEnv(office, k=8)
    obs, _ = wrapping.reset(seed=3)
    plain.reset(seed=3)
    for step in range(12):
        n = int(obs["action_mask"].sum())
        given = [n + 2, -1, 0, n - 1][step % 4]
        obs, _, terminated, truncated, _ = wrapping.step(given)
        want, _, _, _, _ = plain.step(given % n)
        assert obs["belief"].tobytes() == want["belief"].tobytes()
        assert obs["candidates"].tobytes() == want["candidates"].tobytes()
        if terminated or truncated:
            break


@pytest.mark.skipif(not os.path.exists("/proc/meminfo"), reason="available memory unknown")
def test_memory_is_estimated_before_it_is_spent():
    """Regression: ExploreEnv(k=10**9) was killed by the kernel for lack of memory (and a
    huge view or number of environments would have been); now the environment refuses."""
    limit = r"(this machine has available|the cgroup memory limit leaves|ulimit -v leaves)"
    fits = r"needs about \d+ MiB, more than the \d+ MiB " + limit + "; use a smaller k"
    with pytest.raises(ValueError, match=r"running this environment \(.*k = 1000000000000\) " + fits):
        ExploreEnv("office", k=10**12)
    with pytest.raises(ValueError, match=r"1099511627776x1099511627776-cell observations"):
        ExploreEnv("office", view=2**40)
    with pytest.raises(ValueError, match=r"running these 1000000000 environments .* " + fits):
        ExploreVectorEnv(10**9, maps="office")


def test_explore_env_memory_mb_bounds_the_environments(office):
    """Regression: the environments took no memory_mb, so a training script could not bound
    them (explore and Map.load could be). A budget too small for the environments is
    refused when they are made, naming it; one that holds them changes no episode."""
    fix = "; use a smaller k or view"
    with pytest.raises(ValueError, match=r"running this environment \(60x48-cell maps, "
                       r"60x48-cell observations, k = 16\) needs about 17 MiB, more than "
                       r"--memory-mb 16" + fix):
        ExploreEnv(office, memory_mb=16)
    # Four environments are bounded together: 18 MiB, though one fits in 17.
    with pytest.raises(ValueError, match=r"running these 4 environments \(.*\) needs about "
                       r"18 MiB, more than --memory-mb 17" + fix):
        ExploreVectorEnv(4, office, memory_mb=17)
    # Regression: each environment was counted with the whole program (16 MiB) and its
    # sensor's ray template, which the process holds once: 64 of these were "about 1090
    # MiB", and 200 small ones with a view, which peak at 64 MiB, "about 3250 MiB".
    assert ExploreVectorEnv(64, office, memory_mb=40).num_envs == 64
    bounded = ExploreEnv(office, k=8, lam=0.1, memory_mb=np.int64(64))
    free = ExploreEnv(office, k=8, lam=0.1)
    assert episode(bounded, RandomPolicy(5), 11) == episode(free, RandomPolicy(5), 11)
    venvs = [ExploreVectorEnv(4, office, memory_mb=mb) for mb in (70, None)]
    obs = [v.reset(seed=3)[0] for v in venvs]
    for _ in range(5):
        assert all(obs[0][key].tobytes() == obs[1][key].tobytes() for key in obs[0])
        acts = Baseline("cf-rr")(venvs[1])
        obs = [v.step(acts)[0] for v in venvs]
    # Checked as explore's memory_mb.
    for bad, error, found in [(0, ValueError, "a positive number of MiB, found 0"),
                              (-1, ValueError, "a positive number of MiB, found -1"),
                              (2**64, ValueError, "less than 2\\^64 MiB, found 18446744073709551616"),
                              (True, TypeError, "an int, found bool"),
                              (2.5, TypeError, "an int, found float")]:
        with pytest.raises(error, match="memory_mb: expected " + found):
            ExploreEnv(office, memory_mb=bad)
        with pytest.raises(error, match="memory_mb: expected " + found):
            ExploreVectorEnv(2, office, memory_mb=bad)


def test_memory_mb_bounds_the_environments_maps(tmp_path, write_png):
    """The environments' budget bounds what they load and generate too: a map file or a
    folder's map whose loading would need more is refused before it is decoded, a generated
    map before it is generated, and an episode on a folder's map larger than the one the
    environment was sized on before its run starts."""
    claimed = tmp_path / "claimed"
    claimed.mkdir()
    # A header claiming 16384 x 16384 pixels and no pixels: refused by its estimate.
    (claimed / "huge.pgm").write_bytes(b"P5\n16384 16384\n255\n")
    refusal = r"huge.pgm: loading this 16384x16384 PGM image needs about 1281 MiB, more than --memory-mb 64"
    for maps in (claimed, claimed / "huge.pgm", [claimed / "huge.pgm"]):
        with pytest.raises(ValueError, match=refusal):
            ExploreEnv(maps, resolution=0.1, memory_mb=64)
    with pytest.raises(ValueError, match=r"generating this cave of 64000000 cells needs about "
                       r"\d+ MiB, more than --memory-mb 64"):
        ExploreEnv("cave", size=(400, 400), resolution=0.05, memory_mb=64)
    folder = tmp_path / "plans"
    folder.mkdir()
    for name, side in (("a_large", 400), ("b_small", 20)):
        pixels = np.full((side, side), 255, np.uint8)
        pixels[[0, -1], :] = pixels[:, [0, -1]] = 0
        write_png(folder / f"{name}.png", pixels)
    # The environment is sized on the map seed 0 picks, b_small (index 1 of 2): 16 MiB and
    # a run on a_large needs 24 MiB.
    env = ExploreEnv(folder, resolution=0.25, view=16, memory_mb=20)
    assert env.map_names == ["a_large", "b_small"]
    env.reset(seed=0, options={"map": 1})
    with pytest.raises(ValueError, match=r"an episode on map a_large \(400x400 cells\) needs "
                       r"about 24 MiB, more than --memory-mb 20; leave the largest maps out"):
        env.reset(seed=0, options={"map": 0})
    ExploreEnv(folder, resolution=0.25, view=16, memory_mb=64).reset(seed=0, options={"map": 0})


@pytest.mark.parametrize(
    "kwargs,error,message",
    [
        (dict(k=-1), ValueError, "k: expected at least 1 candidate, found -1"),
        (dict(k=2.5), TypeError, "k: expected an int, found float"),
        (dict(view=0), ValueError, "view: expected at least 1 cell, found 0"),
        (dict(max_steps=0), ValueError, "max_steps: expected at least 1 decision, found 0"),
        (dict(max_path_m=-1.0), ValueError, "max_path_m: expected a positive number of metres"),
        (dict(max_path_m=float("nan")), ValueError, "max_path_m: expected a positive number"),
        (dict(maps=42), TypeError, "maps: expected a frontier.Map, a list of maps, a generator kind"),
        (dict(maps="no/such/folder"), ValueError, "maps: no/such/folder: no such folder or map file"),
    ],
)
def test_bad_arguments_name_the_argument(office, kwargs, error, message):
    """Regression: these gave pyo3's OverflowError, numpy's messages, a silent episode of no
    steps, or "'int' object is not iterable"."""
    kwargs = dict(dict(maps=office), **kwargs)
    with pytest.raises(error, match=message):
        ExploreEnv(**kwargs)


def test_run_options_are_checked(office):
    """Regression: a misspelt run option was refused as an argument of "explore()", and
    seed, trajectories or clutter were taken and ignored."""
    with pytest.raises(TypeError, match=r"ExploreEnv\(\) got an unexpected keyword argument "
                       r"'clearence' .*did you mean 'clearance'\?"):
        ExploreEnv(office, clearence=0.3)
    with pytest.raises(TypeError, match=r"ExploreVectorEnv\(\) .* 'seed' .*reset\(seed=...\)'s"):
        ExploreVectorEnv(2, office, seed=3)
    with pytest.raises(TypeError, match="'trajectories'"):
        ExploreEnv(office, trajectories=True)
    ExploreEnv(office, clearance=0.25, motion="grid", sensing="every-3", coverage="known")


def test_regression_any_angle_motion_is_refused(office):
    """Regression: motion="any-angle" was taken, but rewards, max_path_m and
    info["path_length_m"] stayed grid metres (42.19 against explore's 41.58): an any-angle
    length is measured once a run ends."""
    for make in (lambda: ExploreEnv(office, motion="any-angle"),
                 lambda: ExploreVectorEnv(2, office, motion="ANY-ANGLE")):
        with pytest.raises(ValueError, match=r"motion: an environment moves on the grid .*"
                           r"frontier.explore\(\.\.\., motion="):
            make()
    with pytest.raises(ValueError, match="unknown motion 'diagonal'"):
        ExploreEnv(office, motion="diagonal")


def test_regression_move_budget_truncates(office):
    """Regression: running out of max_moves ended the episode as terminated, though a budget
    is a truncation (Gymnasium's contract: the task did not end, bootstrap past it)."""
    env = ExploreEnv(office, max_moves=10)
    env.reset(seed=0)
    terminated = truncated = False
    steps = 0
    while not (terminated or truncated):
        _, _, terminated, truncated, info = env.step(0)
        steps += 1
    assert truncated and not terminated, (steps, info)
    assert info["coverage"] < 0.9
    # Without the budget the same episode ends terminated, everything explored.
    env = ExploreEnv(office)
    env.reset(seed=0)
    terminated = truncated = False
    while not (terminated or truncated):
        _, _, terminated, truncated, info = env.step(0)
    assert terminated and not truncated and info["coverage"] == 1.0


def test_regression_required_counts_refuse_none(office):
    """Regression: k=None and num_envs=None gave "'NoneType' object cannot be interpreted
    as an integer", naming no argument."""
    with pytest.raises(TypeError, match="k: expected an int, found NoneType"):
        ExploreEnv(office, k=None)
    with pytest.raises(TypeError, match="num_envs: expected an int, found NoneType"):
        ExploreVectorEnv(None, office)


def test_regression_start_is_checked_on_every_map_of_a_list(office):
    """Regression: a fixed start was checked on the first map of a list only; another map
    refused it at the episode that drew it (a vector environment's, inside step())."""
    walled = office.to_numpy().copy()
    walled[2, 2] = 2
    other = frontier.Map.from_numpy(walled, office.resolution)
    free = office.to_numpy()[2, 2] == 1
    assert free
    ExploreEnv([office, office], start=(2, 2))
    with pytest.raises(ValueError, match=r"--start 2,2: the cell is occupied"):
        ExploreEnv([office, other], start=(2, 2))


def test_bad_actions_name_the_argument(office):
    env = ExploreEnv(office)
    env.reset(seed=0)
    with pytest.raises(TypeError, match="action: expected an int, found float"):
        env.step(1.5)
    env.step(np.int64(0))
    venv = ExploreVectorEnv(3, office)
    venv.reset(seed=0)
    with pytest.raises(ValueError, match=r"actions: expected one action per environment, shape \(3,\), "
                       r"found shape \(2,\)"):
        venv.step([0, 0])
    with pytest.raises(TypeError, match="actions: expected integers, found dtype float64"):
        venv.step(np.zeros(3))
    with pytest.raises(ValueError, match="num_envs: expected at least 1, found -2"):
        ExploreVectorEnv(-2, office)
    with pytest.raises(ValueError, match="threads: expected at least 1, found -1"):
        ExploreVectorEnv(2, office, threads=-1)


def test_a_map_file_is_a_map_list(office, tmp_path):
    office.save(tmp_path / "office.yaml")
    obs, info = ExploreEnv(str(tmp_path / "office.yaml")).reset(seed=0)
    assert info["map"] == "office"
    same, _ = ExploreEnv([office]).reset(seed=0)
    assert obs["belief"].tobytes() == same["belief"].tobytes()
    assert obs["candidates"].tobytes() == same["candidates"].tobytes()


def test_vector_env_matches_single_envs(office):
    n = 3
    venv = ExploreVectorEnv(n, [office], k=8, threads=2)
    obs, _ = venv.reset(seed=7)
    singles = [ExploreEnv([office], k=8) for _ in range(n)]
    for i, e in enumerate(singles):
        e.reset(seed=7 + i)
    for i, e in enumerate(singles):
        assert np.array_equal(obs["belief"][i], e._obs["belief"])
    done = np.zeros(n, bool)
    for _ in range(15):
        acts = venv.baseline_actions("cf-rr")
        obs, rew, term, trunc, infos = venv.step(acts)
        for i, e in enumerate(singles):
            if done[i]:
                continue
            o, r, t, tr, info = e.step(int(acts[i]))
            assert r == rew[i] and t == term[i]
            assert np.array_equal(o["candidates"], obs["candidates"][i])
            done[i] = t or tr
    assert venv.observation_space.contains(obs)


def data_address(a):
    """Where a numpy array's data starts."""
    return a.__array_interface__["data"][0]


@pytest.mark.parametrize("vector", [False, True])
def test_kept_observations_never_change_and_dropped_ones_are_reused(office, vector):
    # Observation arrays are written again only once Python holds none of them: a kept
    # dict, a kept view, copies made by the caller all stay as they were.
    env = ExploreVectorEnv(2, [office], k=8, threads=2) if vector else ExploreEnv([office], k=8)
    act = (lambda: env.baseline_actions("cf-rr")) if vector else (lambda: Baseline("cf-rr")(env))
    obs, _ = env.reset(seed=3)
    kept = obs
    frozen = {key: a.copy() for key, a in kept.items()}
    view = obs["frontier"][..., 1:]
    frozen_view = view.copy()
    addresses = set()
    for _ in range(12):
        obs, *_ = env.step(act())
        addresses.add(data_address(obs["belief"]))
        del obs
    for key, a in kept.items():
        assert np.array_equal(a, frozen[key]), key
    assert np.array_equal(view, frozen_view)
    if vector:
        # Dropped observations' arrays are written again, not allocated afresh at every
        # step. (One environment's arrays are small enough for the allocator to hand the
        # same memory back anyway, so only the vector environment's show it.)
        assert len(addresses) <= 2


@pytest.mark.parametrize("vector", [False, True])
def test_observations_brought_up_to_date_equal_ones_written_whole(office, vector):
    """A kept set of observation arrays is brought up to date with the cells changed since
    it was last written. The same episodes with every observation held (so that each is a
    new set, written whole) give the same layers at every step, whichever observations the
    caller holds on to and for how long, across resets."""

    def make():
        if vector:
            return ExploreVectorEnv(3, [office], k=8, threads=2, max_steps=30)
        return ExploreEnv([office], k=8, max_steps=30)

    part, whole = make(), make()
    rng = np.random.default_rng(11)
    seed = 3
    got, _ = part.reset(seed=seed)
    want, _ = whole.reset(seed=seed)
    every = [want]
    held = []
    for _ in range(120):
        for key in ("belief", "frontier"):
            assert np.array_equal(got[key], want[key]), key
        if vector:
            act = whole.baseline_actions("cf-rr")
        else:
            act = Baseline("cf-rr")(whole)
        got, _, term, trunc, _ = part.step(act)
        want, _, term_w, trunc_w, _ = whole.step(act)
        every.append(want)
        if not vector and (term or trunc):
            seed += 1
            got, _ = part.reset(seed=seed)
            want, _ = whole.reset(seed=seed)
            every.append(want)
        # hold some observations for a while, so that sets fall behind by different steps
        if rng.random() < 0.4:
            held.append(got)
        if held and rng.random() < 0.4:
            held.pop(int(rng.integers(len(held))))


@pytest.mark.parametrize("vector", [False, True])
def test_belief_and_frontier_layers_are_read_only(office, vector):
    """They are brought up to date in place of being written whole, so a change made in
    place would stay in them: numpy refuses it; a copy is the caller's to change."""
    env = ExploreVectorEnv(2, [office], k=8) if vector else ExploreEnv([office], k=8)
    obs, _ = env.reset(seed=0)
    for key in ("belief", "frontier"):
        assert not obs[key].flags.writeable
        with pytest.raises(ValueError, match="read-only"):
            obs[key][..., 0, 0] = 1
        mine = obs[key].copy()
        mine[..., 0, 0] = 1
    obs["candidates"][..., 0, 0] = 1.0


def test_vector_env_wraps_actions_as_the_single_env_does(office):
    """Each environment of the vector env takes an action outside its n offered candidates
    modulo n, as ExploreEnv does; with invalid_action="raise" it names the environment."""
    venv = ExploreVectorEnv(2, [office], k=8, threads=2)
    obs, _ = venv.reset(seed=3)
    singles = [ExploreEnv([office], k=8) for _ in range(2)]
    for i, e in enumerate(singles):
        e.reset(seed=3 + i)
    for step in range(10):
        n = obs["action_mask"].sum(axis=1)
        given = np.array([[n[0] + 2, -1], [-3, 0], [0, n[1] + 5], [n[0] - 1, 40]][step % 4])
        obs, rew, term, trunc, _ = venv.step(given)
        for i, e in enumerate(singles):
            o, r, t, tr, _ = e.step(int(given[i]))
            assert r == rew[i] and t == term[i] and tr == trunc[i]
            assert o["candidates"].tobytes() == obs["candidates"][i].tobytes()
        if (term | trunc).any():
            break
    strict = ExploreVectorEnv(2, [office], k=8, invalid_action="raise")
    obs, _ = strict.reset(seed=3)
    n = int(obs["action_mask"][1].sum())
    with pytest.raises(ValueError, match=f"environment 1: action 99: expected the index of one of the {n}"):
        strict.step(np.array([0, 99]))
    # Regression: a negative action was named as 18446744073709551615.
    with pytest.raises(ValueError, match=f"environment 1: action -1: expected the index of one of the {n}"):
        strict.step(np.array([0, -1]))


@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="no per-thread list")
def test_vector_env_starts_no_more_helpers_than_environments(office):
    """A helper thread with no environment to take would only spin between calls: two
    environments get one helper whatever `threads` asks, and it ends with the env."""

    def helpers():
        # Environments of earlier tests caught in reference cycles end (with their
        # helpers) when collected; a joined thread leaves the list a moment later.
        gc.collect()
        names = []
        for tid in os.listdir("/proc/self/task"):
            try:
                with open(f"/proc/self/task/{tid}/comm") as f:
                    names.append(f.read())
            except OSError:
                pass  # ended meanwhile
        return sum(n.startswith("frontier-helpe") for n in names)

    def settled(want=None):
        # the count once it stops changing (or reaches `want`), within a second
        n = helpers()
        for _ in range(100):
            if n == want:
                break
            time.sleep(0.01)
            n, last = helpers(), n
            if want is None and n == last:
                break
        return n

    before = settled()
    venv = ExploreVectorEnv(2, [office], k=8, threads=8)
    venv.reset(seed=0)
    venv.step(np.zeros(2, dtype=np.int64))
    assert helpers() - before == 1
    del venv
    assert settled(before) == before


def test_vector_env_autoresets(office):
    venv = ExploreVectorEnv(2, [office], k=8, max_steps=2)
    venv.reset(seed=0)
    _, _, _, trunc, _ = venv.step([0, 0])
    _, _, _, trunc, _ = venv.step([0, 0])
    assert trunc.all()
    _, rew, term, trunc, infos = venv.step([0, 0])
    assert not trunc.any() and (rew == 0).all() and (infos["path_length_m"] == 0).all()


def test_maps_from_a_folder(office, tmp_path):
    office.save(tmp_path / "a.yaml")
    office.save(tmp_path / "b.yaml")
    (tmp_path / "notes.md").write_text("not a map")
    env = ExploreEnv(str(tmp_path), k=4)
    names = {env.reset(seed=s)[1]["map"] for s in range(8)}
    assert names == {"a", "b"}
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(ValueError, match="no map files"):
        ExploreEnv(str(empty))


def _house(path, w, h):
    """A HouseExpo plan: an L of two rooms in a w x h metre box."""
    path.write_text(
        '{"id": "%s", "verts": [[0,0],[%g,0],[%g,%g],[%g,%g],[%g,%g],[0,%g]], '
        '"room_category": {"a": [[0,0,%g,%g]], "b": [[0,%g,%g,%g]]}}'
        % (path.stem, w, w, h / 2, w / 2, h / 2, w / 2, h, h, w, h / 2, h / 2, w / 2, h)
    )


def test_a_folder_of_houseexpo_plans_is_read_episode_by_episode(tmp_path):
    # HouseExpo's folder holds 35,000 plans: the environment lists the files and reads the
    # one an episode picks when it starts, never all of them.
    _house(tmp_path / "a.json", 6, 6)
    _house(tmp_path / "b.json", 8, 5)
    kw = dict(resolution=0.1, view=32, k=4, sensor="los:r=2")
    env = ExploreEnv(str(tmp_path), **kw)
    names = {}
    for s in range(12):
        obs, info = env.reset(seed=s)
        names[info["map"]] = s
    assert set(names) == {"a", "b"}
    # The same episodes as with the plans loaded first (same order, same pick by seed).
    eager = ExploreEnv(frontier.gym.load_folder(tmp_path, resolution=0.1), **kw)
    for s in range(4):
        assert episode(env, Baseline("cf-rr"), s) == episode(eager, Baseline("cf-rr"), s)
    # Read at reset, not at construction: a plan removed since is named when picked.
    (tmp_path / "b.json").unlink()
    with pytest.raises(ValueError, match=r"b\.json"):
        env.reset(seed=names["b"])
    assert env.reset(seed=names["a"])[1]["map"] == "a"


def test_a_folder_of_maps_of_different_sizes_needs_a_view(tmp_path):
    _house(tmp_path / "a.json", 6, 6)
    _house(tmp_path / "b.json", 8, 5)
    with pytest.raises(ValueError, match=r"[ab] is \d+x\d+ cells but [ab] is \d+x\d+; maps of "
                       "different sizes need a robot-centred view"):
        ExploreEnv(str(tmp_path), resolution=0.1, k=4)
    with pytest.raises(ValueError, match=r"[ab]\.json: --resolution is required for a HouseExpo"):
        ExploreEnv(str(tmp_path))


def test_a_folder_without_a_view_is_checked_whole_when_made(tmp_path):
    # Regression: without a view, an odd-sized or unreadable file of a folder was refused
    # only at the reset that drew it (perhaps hours into training), not when the
    # environment was made.
    for name in "abc":
        _house(tmp_path / f"{name}.json", 6, 6)
    env = ExploreEnv(str(tmp_path), resolution=0.1, k=4)
    assert {env.reset(seed=s)[1]["map"] for s in range(16)} == {"a", "b", "c"}
    _house(tmp_path / "d.json", 8, 5)
    odd = r"(d is 82x52 cells but [abc] is 62x62|[abc] is 62x62 cells but d is 82x52)"
    with pytest.raises(ValueError, match=odd):
        ExploreEnv(str(tmp_path), resolution=0.1, k=4)
    (tmp_path / "d.json").write_text("{not json")
    with pytest.raises(ValueError, match=r"d\.json"):
        ExploreEnv(str(tmp_path), resolution=0.1, k=4)
    # With a view every size is observed alike, and files are read when drawn.
    _house(tmp_path / "d.json", 8, 5)
    env = ExploreEnv(str(tmp_path), resolution=0.1, k=4, view=32)
    assert {env.reset(seed=s)[1]["map"] for s in range(16)} == {"a", "b", "c", "d"}


def test_a_folder_of_dungeon_maps_starts_where_each_marks(tmp_path, write_png):
    # Dungeon maps of learned-exploration work mark their start with pixels of value 208.
    starts = {"d0": (4, 3), "d1": (9, 5)}
    for name, (x, y) in starts.items():
        pixels = np.full((8, 12), 255, np.uint8)
        pixels[[0, -1], :] = 0
        pixels[:, [0, -1]] = 0
        pixels[y, x] = 208
        write_png(tmp_path / f"{name}.png", pixels)
    (tmp_path / "notes.txt").write_text("not a map")
    env = ExploreEnv(str(tmp_path), resolution=0.1, dungeon=True, k=4, sensor="los:r=0.3")
    seen = set()
    for s in range(10):
        obs, info = env.reset(seed=s)
        assert tuple(obs["pose"][:2].astype(int)) == starts[info["map"]]
        seen.add(info["map"])
    assert seen == set(starts)
    eager = ExploreEnv(frontier.gym.load_folder(tmp_path, 0.1, dungeon=True), k=4,
                       sensor="los:r=0.3")
    for s in range(3):
        assert episode(env, Baseline("cf-rr"), s) == episode(eager, Baseline("cf-rr"), s)
    with pytest.raises(ValueError, match="dungeon: expected one resolution"):
        ExploreEnv(str(tmp_path), dungeon=True)
    # Regression: load_folder(dungeon=True) ignored border; it walls each map as Map.load
    # does, the start moving with the cells.
    walled = frontier.gym.load_folder(tmp_path, 0.1, border=True, dungeon=True)
    assert [m.start for m in walled] == [(x + 1, y + 1) for x, y in starts.values()]
    assert [m.shape for m in walled] == [(10, 14)] * 2
    for m in walled:
        want = frontier.Map.load(tmp_path / f"{m.name}.png", 0.1, True, dungeon=True)
        assert np.array_equal(m.to_numpy(), want.to_numpy())
    # Regression: load_folder(dungeon=True) on a folder without PNGs returned no maps.
    (tmp_path / "none").mkdir()
    (tmp_path / "none" / "a.txt").write_text("#")
    with pytest.raises(ValueError, match=r"none: no \.png files \(dungeon=True\)"):
        frontier.gym.load_folder(tmp_path / "none", 0.1, dungeon=True)
    with pytest.raises(ValueError, match=r"none: no \.png files \(dungeon=True\)"):
        ExploreEnv(str(tmp_path / "none"), resolution=0.1, dungeon=True)
    with pytest.raises(ValueError, match="dungeon: reads PNG files"):
        ExploreEnv("office", dungeon=True)
    with pytest.raises(TypeError, match="dungeon: expected a bool"):
        ExploreEnv(str(tmp_path), resolution=0.1, dungeon="yes")


def test_reset_options_choose_the_map(tmp_path):
    # Evaluating on every test map once: reset(options={"map": i}) instead of the seed's
    # pick, on a list, a folder, the vector and the team environment.
    for w, h, name in [(6, 6, "a"), (12, 4, "b"), (5, 10, "c")]:
        _house(tmp_path / f"{name}.json", w, h)
    # A view and range that see each plan's walls, so that first observations tell them apart.
    kw = dict(resolution=0.1, view=64, k=4, sensor="los:r=5")
    env = ExploreEnv(str(tmp_path), **kw)
    assert env.map_names == ["a", "b", "c"]
    for i, name in enumerate(env.map_names):
        for s in range(3):
            assert env.reset(seed=s, options={"map": i})[1]["map"] == name
    listed = ExploreEnv(frontier.gym.load_folder(tmp_path, resolution=0.1), **kw)
    assert listed.map_names == ["a", "b", "c"]
    pick = lambda e, s: episode_on(e, s, 2)
    assert pick(env, 5) == pick(listed, 5) == pick(env, 5)
    with pytest.raises(ValueError, match=r"expected the index of one of the 3 maps, 0 to 2, found 3"):
        env.reset(seed=0, options={"map": 3})
    with pytest.raises(ValueError, match=r"0 or more\), found -1"):
        env.reset(seed=0, options={"map": -1})
    with pytest.raises(TypeError, match=r"options\['map'\]: expected the index of a map \(an int\), found bool"):
        env.reset(seed=0, options={"map": True})
    with pytest.warns(UserWarning, match="unknown key 'mapp' ignored"):
        env.reset(seed=0, options={"mapp": 1})
    generated = ExploreEnv("office", k=4)
    assert generated.map_names is None
    with pytest.raises(ValueError, match="the maps are generated .* no list to pick from"):
        generated.reset(seed=0, options={"map": 0})

    venv = ExploreVectorEnv(3, str(tmp_path), **kw)
    assert venv.map_names == ["a", "b", "c"]
    obs, _ = venv.reset(seed=0, options={"map": [2, None, 0]})
    # Environment i of reset(seed=0) starts the episode ExploreEnv.reset(seed=i) starts.
    for i, index in enumerate([2, None, 0]):
        one, _ = env.reset(seed=i, options={"map": index} if index is not None else None)
        assert (obs["belief"][i] == one["belief"]).all()
        assert (obs["candidates"][i] == one["candidates"]).all()
        if index is not None:
            other, _ = env.reset(seed=i, options={"map": (index + 1) % 3})
            assert (obs["belief"][i] != other["belief"]).any()
    obs, _ = venv.reset(seed=4, options={"map": 1})
    one, _ = env.reset(seed=6, options={"map": 1})
    assert (obs["belief"][2] == one["belief"]).all()
    with pytest.raises(ValueError, match="one map index \\(or None\\) per environment, 3, found 2"):
        venv.reset(seed=0, options={"map": [0, 1]})
    with pytest.raises(ValueError, match=r"environment 2: options\['map'\]: expected the index of one of the 3 maps"):
        venv.reset(seed=0, options={"map": [0, 1, 3]})

    from frontier.pettingzoo import ExploreParallelEnv

    team = ExploreParallelEnv(str(tmp_path), robots=2, **kw)
    assert team.map_names == ["a", "b", "c"]
    _, infos = team.reset(seed=1, options={"map": 1})
    assert infos["robot_0"]["map"] == "b"


def episode_on(env, seed, index):
    """One cf-rr episode on map `index` (observation digests, rewards)."""
    obs, info = env.reset(seed=seed, options={"map": index})
    trace = [(obs["belief"].tobytes(), info["map"])]
    while True:
        obs, reward, terminated, truncated, info = env.step(Baseline("cf-rr")(env))
        trace.append((obs["belief"].tobytes(), reward))
        if terminated or truncated:
            return trace


def test_a_list_of_map_files_is_read_episode_by_episode(tmp_path):
    # A dataset's train or test split as a list of paths: read as a folder's files are.
    for w, h, name in [(6, 6, "a"), (12, 4, "b"), (5, 10, "c")]:
        _house(tmp_path / f"{name}.json", w, h)
    kw = dict(resolution=0.1, view=64, k=4, sensor="los:r=5")
    split = [tmp_path / "c.json", str(tmp_path / "a.json")]
    env = ExploreEnv(split, **kw)
    assert env.map_names == ["c", "a"]
    assert {env.reset(seed=s)[1]["map"] for s in range(10)} == {"a", "c"}
    loaded = ExploreEnv([frontier.Map.load(p, resolution=0.1) for p in split], **kw)
    for s in range(3):
        assert episode(env, Baseline("cf-rr"), s) == episode(loaded, Baseline("cf-rr"), s)
    with pytest.raises(ValueError, match=r"maps\[1\]: .*nope\.json: no such map file"):
        ExploreEnv([split[0], tmp_path / "nope.json"], **kw)
    with pytest.raises(TypeError, match=r"maps\[1\]: expected a frontier.Map or a map file's path"):
        ExploreEnv([frontier.Map.load(split[0], resolution=0.1), split[1]], **kw)


def _room():
    """A 3 x 3 room the first scan sees whole: its episodes end at reset."""
    a = np.ones((12, 12), bool)
    a[4:7, 4:7] = False
    return frontier.Map.from_numpy(a, 0.1)


def test_regression_episode_ended_at_reset_terminates_at_first_step():
    env = ExploreEnv(_room())
    obs, info = env.reset(seed=1)
    assert not obs["action_mask"].any() and info["coverage"] == 1.0
    assert env.baseline_action("cf-rr") == 0
    obs, reward, terminated, truncated, info = env.step(0)
    assert (reward, terminated, truncated) == (0.0, True, False)
    assert info["coverage"] == 1.0
    with pytest.raises(ValueError, match="after the episode ended"):
        env.step(0)
    env.reset(seed=2)
    assert env.step(0)[2]


def test_regression_vector_env_autoresets_an_episode_ended_at_reset():
    venv = ExploreVectorEnv(2, _room())
    venv.reset(seed=0)
    for i in range(6):
        # Next-step autoreset: the step that ends it, then the step that resets it.
        _, rewards, terminated, truncated, infos = venv.step(np.zeros(2, int))
        assert list(terminated) == [i % 2 == 0] * 2 and not truncated.any()
        assert list(rewards) == [0.0, 0.0]
        assert list(infos["coverage"]) == [1.0, 1.0]
    assert list(Baseline("cf-rr")(venv)) == [0, 0]


def test_regression_render_draws_the_robot_at_the_centre_of_a_view(office):
    blue = np.array([30, 60, 220], np.uint8)
    for view in (21, 20):
        env = ExploreEnv(office, view=view, render_mode="rgb_array")
        obs, _ = env.reset(seed=0)
        for _ in range(3):
            img = env.render()
            assert img.shape == (view, view, 3)
            c = view // 2
            assert (img[c, c] == blue).all()
            ys, xs = np.nonzero((img == blue).all(axis=2))
            assert (ys.min(), ys.max(), xs.min(), xs.max()) == (c - 1, c + 1, c - 1, c + 1)
            env.step(0)
    # The whole map: at the robot's pose.
    env = ExploreEnv(office, render_mode="rgb_array")
    obs, _ = env.reset(seed=0)
    x, y = int(obs["pose"][0]), int(obs["pose"][1])
    assert (env.render()[y, x] == blue).all()


def _first_observations(office):
    """Observations of a reset and a step of each environment type (a 4-candidate office)."""
    from frontier.pettingzoo import ExploreParallelEnv

    env = ExploreEnv(office, k=4)
    venv = ExploreVectorEnv(2, office, k=4)
    team = ExploreParallelEnv(office, robots=2, k=4)
    observations = [env.reset(seed=0)[0], venv.reset(seed=0)[0],
                    *team.reset(seed=0)[0].values()]
    return observations + [env.step(0)[0], venv.step(np.zeros(2, int))[0]]


def test_regression_observation_layers_cannot_be_made_writeable(office):
    for obs in _first_observations(office):
        for key in ("belief", "frontier"):
            before = obs[key].copy()
            with pytest.raises(ValueError):
                obs[key].flags.writeable = True
            with pytest.raises(ValueError, match="read-only"):
                obs[key][...] = 2
            assert np.array_equal(obs[key], before)
    # Still written only when no one holds them: held observations never change.
    env = ExploreEnv(office, k=4)
    first, _ = env.reset(seed=3)
    kept = first["belief"].copy()
    for _ in range(5):
        env.step(0)
    assert np.array_equal(first["belief"], kept)



def test_regression_observation_layers_bases_cannot_be_made_writeable(office):
    """Regression: a layer was a read-only view of the kept array that owned its data, and
    numpy lets an owner be made writeable again: obs["belief"].base.flags.writeable = True
    and a write into it succeeded, and the episode's later observations, which copy only
    the cells that changed, kept the write. No array of a layer's base chain can be."""
    def chain(a):
        while isinstance(a, np.ndarray):
            yield a
            a = a.base

    for obs in _first_observations(office):
        for key in ("belief", "frontier"):
            arrays = list(chain(obs[key]))
            assert len(arrays) >= 2
            for a in arrays:
                with pytest.raises(ValueError, match="cannot set WRITEABLE flag"):
                    a.flags.writeable = True
                assert not a.flags.writeable
    # An episode whose observations are tampered with where it can be equals a fresh one.
    def episode(tamper):
        e = ExploreEnv(office, k=4)
        obs, _ = e.reset(seed=5)
        trace = []
        for t in range(20):
            for a in (a for key in ("belief", "frontier") if tamper for a in chain(obs[key])):
                try:
                    a.flags.writeable = True
                    a[...] = 2
                except ValueError:
                    pass
            obs, reward, terminated, truncated, _ = e.step(t % 3)
            trace.append((obs["belief"].tobytes(), obs["frontier"].tobytes(), reward))
            if terminated or truncated:
                break
        return trace

    assert episode(True) == episode(False)


def test_regression_vector_reset_infos_hold_what_step_infos_hold(office):
    venv = ExploreVectorEnv(2, office, k=4)
    obs, infos = venv.reset(seed=0)
    _, _, _, _, stepped = venv.step(np.zeros(2, int))
    # Each key with Gymnasium's mask of the environments that set it (every one).
    assert set(infos) == set(stepped) == {"coverage", "_coverage", "path_length_m",
                                          "_path_length_m"}
    assert all(d[f"_{k}"].dtype == bool and d[f"_{k}"].all()
               for d in (infos, stepped) for k in ("coverage", "path_length_m"))
    assert infos["coverage"].shape == (2,) and (infos["coverage"] > 0).all()
    assert list(infos["path_length_m"]) == [0.0, 0.0]


def test_regression_vector_reset_refuses_seeds_that_are_not_ints(office):
    venv = ExploreVectorEnv(2, office, k=4)
    with pytest.raises(TypeError, match=r"seed\[0\]: expected an int or None, found float"):
        venv.reset(seed=[1.5, 0])
    with pytest.raises(ValueError, match=r"seed\[1\]: expected a non-negative int, found -1"):
        venv.reset(seed=[1, -1])
    assert venv.reset(seed=[np.int64(3), None])[0]["belief"].shape[0] == 2


def test_regression_str_and_path_arguments_name_the_argument(office, tmp_path):
    """Regression: a preset of another type gave PyO3's "'int' object is not an instance of
    'str'", load_folder(3) listed file descriptor 3 and `invalid_action` or `render_mode`
    of another type was a ValueError."""
    env = ExploreEnv(office)
    env.reset(seed=0)
    venv = ExploreVectorEnv(2, office)
    venv.reset(seed=0)
    for call, message in [
        (lambda: env.baseline_action(3), "preset: expected a str, found int"),
        (lambda: venv.baseline_actions(None), "preset: expected a str, found NoneType"),
        (lambda: Baseline(b"cf-rr"), "preset: expected a str, found bytes"),
        (lambda: ExploreEnv(office, invalid_action=1), "invalid_action: expected 'wrap' or "
         "'raise', found int"),
        (lambda: ExploreVectorEnv(2, office, invalid_action=None), "invalid_action: expected "
         "'wrap' or 'raise', found NoneType"),
        (lambda: ExploreEnv(office, render_mode=1), "render_mode: expected 'rgb_array' or None, "
         "found int"),
        (lambda: ExploreEnv(office, strategy=3), "strategy: expected a str, found int"),
        (lambda: ExploreEnv(office, sensing=3), "sensing: expected a str or None, found int"),
        (lambda: ExploreEnv(office, s_max=True), "s_max: expected an int, found bool"),
        (lambda: frontier.gym.load_folder(3),
         r"folder: expected a path \(a str or os.PathLike\), found int"),
    ]:
        with pytest.raises(TypeError, match=f"^{message}"):
            call()
    assert env.baseline_action(np.str_("cf-rr")) == env.baseline_action("cf-rr")
    office.save(tmp_path / "o.pgm")
    assert len(frontier.gym.load_folder(tmp_path, resolution=0.25)) == 1


@pytest.mark.parametrize(
    "seed,error,message",
    [
        ("x", TypeError, "seed: expected an int or None, found str"),
        (1.0, TypeError, "seed: expected an int or None, found float"),
        (True, TypeError, "seed: expected an int or None, found bool"),
        (np.bool_(True), TypeError, "seed: expected an int or None, found bool"),
        (-1, ValueError, "seed: expected a non-negative int, found -1"),
        (np.int32(-2), ValueError, "seed: expected a non-negative int, found -2"),
    ],
)
def test_regression_reset_with_a_seed_that_is_not_a_non_negative_int_names_seed(
    office, seed, error, message
):
    """Regression: Gymnasium's seeding raised its own ``gymnasium.error.Error`` ("Seed must
    be a python integer, actual type: <class 'str'>"), neither a TypeError nor a ValueError,
    and took a bool as the seed 0 or 1."""
    env = ExploreEnv(office, k=4)
    with pytest.raises(error, match=f"^{message}"):
        env.reset(seed=seed)


def test_regression_reset_takes_numpy_integer_seeds(office):
    """Regression: ``reset(seed=np.int64(3))`` was refused by Gymnasium's seeding ("Seed must
    be a python integer"); a numpy integer seed now gives the int's episode."""
    env = ExploreEnv(office, k=4)
    plain = episode(env, RandomPolicy(0), 3)
    assert episode(env, RandomPolicy(0), np.int64(3)) == plain
    assert episode(env, RandomPolicy(0), np.uint8(3)) == plain
    assert env.reset(seed=2**64)[1]["seed"] != env.reset(seed=0)[1]["seed"]


@pytest.mark.parametrize(
    "seed,error,message",
    [
        ("x", TypeError, "seed: expected an int, None or a list of one per environment, found str"),
        (1.5, TypeError, "seed: expected an int, None or a list of one per environment, found float"),
        ({1, 2}, TypeError, "seed: expected an int, None or a list of one per environment, found set"),
        (np.zeros((2, 1), np.int64), TypeError, r"seed: expected an int, None or a list of one per "
         r"environment, found ndarray of shape \(2, 1\)"),
        (True, TypeError, "seed: expected an int or None, found bool"),
        (-1, ValueError, "seed: expected a non-negative int, found -1"),
    ],
)
def test_regression_vector_reset_with_a_bad_seed_names_seed(office, seed, error, message):
    """Regression: a str seed was read as a list of characters ("seed: expected 2 seeds,
    found 1"), a float gave "'float' object is not iterable", -1 Gymnasium's own ``Error``,
    and a set or True were taken."""
    venv = ExploreVectorEnv(2, office, k=4)
    with pytest.raises(error, match=f"^{message}"):
        venv.reset(seed=seed)
    obs, _ = venv.reset(seed=np.int64(3))
    assert (obs["belief"] == venv.reset(seed=3)[0]["belief"]).all()


def test_regression_actions_beyond_64_bits_are_a_value_error_naming_the_action(office):
    """Regression: ``step(2**64)`` raised OverflowError ("Python int too large to convert to
    C long"), and the vector environment took np.uint64(2**63) as -2**63, wrapped."""
    env = ExploreEnv(office, k=4)
    env.reset(seed=0)
    for action in (2**63, -(2**63) - 1, np.uint64(2**64 - 1)):
        with pytest.raises(ValueError, match=rf"^action: expected an integer in -2\^63..2\^63, "
                           rf"found {int(action)}$"):
            env.step(action)
    env.step(np.array(2, dtype=np.uint64))
    venv = ExploreVectorEnv(2, office, k=4)
    venv.reset(seed=0)
    with pytest.raises(ValueError, match=r"^actions\[1\]: expected an integer in -2\^63..2\^63, "
                       r"found 9223372036854775808$"):
        venv.step(np.array([0, 2**63], dtype=np.uint64))
    with pytest.raises(ValueError, match=r"^actions\[0\]: expected an integer in -2\^63..2\^63, "
                       r"found 18446744073709551616$"):
        venv.step([2**64, 0])
    with pytest.raises(TypeError, match=r"^actions\[1\]: expected an int, found NoneType$"):
        venv.step([0, None])
    venv.step(np.array([1, 2], dtype=np.uint64))


def test_regression_a_map_index_beyond_64_bits_is_a_value_error_naming_it(office):
    """Regression: ``reset(options={"map": 2**70})`` raised OverflowError ("int too big to
    convert"), naming no argument."""
    env = ExploreEnv([office, office], k=4)
    with pytest.raises(ValueError, match=r"^options\['map'\]: expected the index of a map of the "
                       r"list or folder \(see map_names\), found 1180591620717411303424$"):
        env.reset(seed=0, options={"map": 2**70})
    venv = ExploreVectorEnv(2, [office, office], k=4)
    with pytest.raises(ValueError, match=r"^options\['map'\]\[1\]: expected the index of a map of "
                       r"the list or folder \(see map_names\), found 18446744073709551616$"):
        venv.reset(seed=0, options={"map": [0, 2**64]})
    with pytest.raises(TypeError, match=r"^options\['map'\]\[0\]: expected the index of a map "
                       r"\(an int\), found str$"):
        venv.reset(seed=0, options={"map": ["0", 1]})
    assert env.reset(seed=0, options={"map": np.uint64(1)})[1]["map"] == office.name


def test_regression_a_size_or_resolution_that_would_change_nothing_is_refused(office, tmp_path):
    """Regression: ``size`` with maps that are not generated, and a ``resolution`` other
    than frontier.Map maps' own, were taken and ignored: the episodes ran on the maps as they
    were."""
    office.save(tmp_path / "o.yaml")
    for call, message in [
        (lambda: ExploreEnv(office, size=(10, 10)), r"size: expected None, as only generated "
         r"maps take a size and maps is a frontier.Map, found \(10.0, 10.0\)"),
        (lambda: ExploreVectorEnv(2, [office], size=(10, 10)), "size: .* maps is a list of maps"),
        (lambda: ExploreEnv(str(tmp_path), size=(10, 10)), "size: .* maps is a folder,"),
        (lambda: ExploreEnv(tmp_path / "o.yaml", size=(10, 10)), "size: .* maps is a map file,"),
        (lambda: ExploreEnv([tmp_path / "o.yaml"], size=(1, 1)), "size: .* a list of map files,"),
        (lambda: ExploreEnv(office, resolution=0.1), r"resolution: expected None or the maps' "
         r"own, as a frontier.Map keeps its resolution \(maps is a frontier.Map; "
         r"office-s3-15x12m-r0.25 has 0.25 m per cell\), found 0.1"),
        (lambda: ExploreEnv([office, office], resolution=0.5), "resolution: .* found 0.5"),
    ]:
        with pytest.raises(ValueError, match=f"^{message}"):
            call()
    # The maps' own resolution changes nothing, and is taken.
    ExploreEnv([office], resolution=0.25)
    # A map file's resolution is read as its cells' size (the cells stay as they are).
    for maps in (str(tmp_path), tmp_path / "o.yaml", [tmp_path / "o.yaml"]):
        assert ExploreEnv(maps, resolution=0.5).reset(seed=0)[0]["belief"].shape == (48, 60)


def test_regression_bytes_as_maps_is_a_type_error_naming_maps(office):
    """Regression: ``maps=b"office"`` was read as a list of ints ("maps[0]: expected a
    frontier.Map or a map file's path ..., found int"), and a too large k said "at most …
    candidate"."""
    with pytest.raises(TypeError, match="^maps: expected a frontier.Map, a list of maps, a "
                       "generator kind, a map file or a folder, found bytes$"):
        ExploreEnv(b"office")
    with pytest.raises(ValueError, match=r"^k: expected at most \d+ candidates, found \d+$"):
        ExploreEnv(office, k=2**70)


@pytest.mark.parametrize(
    "kwargs,message",
    [
        (dict(speed=0), "--speed: expected a positive number of metres per second, from 0.001 "
         "to 1000, found 0"),
        (dict(speed=float("nan")), "--speed: .*found NaN"),
        (dict(clearance=-1.0), "--clearance: expected a non-negative number of metres, found -1"),
        (dict(goal=2.0), r"--goal: expected a coverage share in \(0, 1\], found 2"),
        (dict(start=(0, 0)), r"map office-s3-15x12m-r0.25: --start 0,0: the cell is occupied"),
        (dict(maps="office", size=(0, 0)), r"--size: expected WxH in metres \(e.g. 25x20\), "
         "found '0x0'"),
        (dict(maps="office", resolution=0), "--resolution: expected a positive number of "
         "metres per cell, at most 1000, found '0'"),
    ],
)
def test_regression_run_options_out_of_range_are_refused_at_construction(office, kwargs, message):
    """Regression: a speed, clearance or goal out of range, or an occupied start, built the
    environment, and every reset then failed with the message under the map's name; a
    generator size of 0 said "invalid width_m = 0"."""
    kwargs = dict(dict(maps=office), **kwargs)
    maps = kwargs.pop("maps")
    for make in (
        lambda: ExploreEnv(maps, **kwargs),
        lambda: ExploreVectorEnv(2, maps, **kwargs),
        lambda: gymnasium.make("frontier/Explore-v0", maps=maps, **kwargs),
    ):
        with pytest.raises(ValueError, match=f"^{message}"):
            make()


def test_vector_env_step_bool_among_actions_refused(office):
    """Regression: numpy reads ``[True, 0, 0]`` as the int array ``[1, 0, 0]``, so the vector
    environment took a bool among ints as the action 1, where ``ExploreEnv.step(True)`` is a
    TypeError; an all-bool array was refused already (its dtype is bool). A list of numpy
    integers of mixed signedness, which numpy makes a float64 array, was refused as floats."""
    env = ExploreEnv(office)
    env.reset(seed=0)
    with pytest.raises(TypeError, match=r"^action: expected an int, found bool$"):
        env.step(True)
    venv = ExploreVectorEnv(3, office)
    venv.reset(seed=0)
    for actions, i in [([True, 0, 0], 0), ((0, False, 0), 1), ([0, 0, np.True_], 2),
                       ([0, np.array(True), 1], 1), ([True, True, False], 0)]:
        with pytest.raises(TypeError, match=rf"^actions\[{i}\]: expected an int, found "):
            venv.step(actions)
    with pytest.raises(TypeError, match="^actions: expected integers, found dtype bool$"):
        venv.step(np.array([True, False, True]))
    # numpy integers of mixed types (an int array of float64 dtype to numpy) are ints.
    venv.step([np.int8(1), 0, np.uint64(2)])


def _splitmix(x):
    """SplitMix64 (Steele, Lea & Flood 2014), as the environments draw episode seeds and
    maps."""
    m = (1 << 64) - 1
    z = (x + 0x9E3779B97F4A7C15) & m
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & m
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & m
    return z ^ (z >> 31)


def test_regression_failed_automatic_reset_loses_no_step(office, tmp_path):
    """Regression: once an automatic reset failed (a folder's unreadable file), every later
    step() raised for ever, retrying the same seed, and the other environments' steps made
    in the failing call were thrown away. Now the failed reset moves its seed on, and the
    others' steps are returned by the next call: environment 1 plays exactly the episode a
    lone ExploreEnv plays."""
    room = np.full((7, 7), 2, np.uint8)
    room[1:6, 1:6] = 1
    frontier.Map.from_numpy(room, 0.25).save(tmp_path / "a.pgm")  # seen whole at once
    office.save(tmp_path / "b.pgm")
    (tmp_path / "c.pgm").write_bytes(b"P5 not a picture")
    names = ["a", "b", "c"]
    pick = lambda seed: names[_splitmix(seed) % 3]
    episode = lambda s: frontier.gym._episode_seed(seeding.np_random(s)[0])
    # Environment 0 plays the room, which ends at its first step, then draws the bad file
    # at its automatic reset, then (on the retry) a good map; environment 1 the office.
    s = next(s for s in range(10_000)
             if pick(_splitmix(episode(s))) == "c"
             and pick(_splitmix(_splitmix(episode(s)))) != "c")
    kw = dict(resolution=0.25, view=16, k=4, invalid_action="wrap")
    venv = ExploreVectorEnv(2, str(tmp_path), **kw)
    venv.reset(seed=s, options={"map": [0, 1]})
    rewards, errors = [], []
    for _ in range(200):
        try:
            _, r, term, trunc, _ = venv.step(np.zeros(2, np.int64))
        except ValueError as e:
            errors.append(str(e))
            continue
        rewards.append(r[1])
        if term[1] or trunc[1]:
            break
    assert len(errors) == 1, errors
    assert "environment 0: " in errors[0] and "c.pgm" in errors[0], errors[0]
    assert "the next step draws the next one" in errors[0], errors[0]
    assert "the other environments' steps are kept" in errors[0], errors[0]
    lone = ExploreEnv(str(tmp_path), **kw)
    lone.reset(seed=s + 1, options={"map": 1})
    want = []
    while True:
        _, r, term, trunc, _ = lone.step(0)
        want.append(r)
        if term or trunc:
            break
    assert rewards == want


def test_regression_rechecking_watches_only_frontier_goals():
    """Regression: cf-rr re-decides when its goal stops being a frontier cell, and a coverage
    cell (candidates="cc") is almost never one, so it decided again at nearly every move
    (513 decisions in 689 moves here). A goal that was no frontier cell when chosen is now
    kept to arrival, as cf keeps it."""
    kw = dict(maps="office", size=(25, 20), resolution=0.25, sensor="los:r=5", k=256,
              candidates="cc")
    counts = {}
    for strategy in ("cf-rr", "cf"):
        env = ExploreEnv(strategy=strategy, **kw)
        env.reset(seed=1)
        baseline = Baseline(strategy)
        while True:
            _, _, term, trunc, info = env.step(baseline(env))
            if term or trunc:
                break
        assert term and info["coverage"] == 1.0
        counts[strategy] = (info["decisions"], info["moves"])
    decisions, moves = counts["cf-rr"]
    assert decisions < moves / 3, counts
    assert decisions <= 1.2 * counts["cf"][0], counts


def _folder_with_a_bad_file(office, tmp_path):
    """A folder of two good maps and an unreadable one, by name: a.pgm, b.pgm, c.pgm."""
    office.save(tmp_path / "a.pgm")
    office.save(tmp_path / "b.pgm")
    (tmp_path / "c.pgm").write_bytes(b"P5 not a picture")
    return str(tmp_path)


def test_regression_a_failed_reset_leaves_no_episode(office, tmp_path):
    """Regression: a reset that raised (a folder's unreadable file) left the previous episode
    running: step() went on with it while info["seed"] named the seed of the failed reset,
    and a vector environment stepped a mix of new and old episodes."""
    folder = _folder_with_a_bad_file(office, tmp_path)
    env = ExploreEnv(folder, resolution=0.25, view=16, k=4)
    _, info = env.reset(seed=0, options={"map": 0})
    env.step(0)
    with pytest.raises(ValueError, match="c.pgm"):
        env.reset(seed=5, options={"map": 2})
    with pytest.raises(gymnasium.error.ResetNeeded):
        env.step(0)
    _, again = env.reset(seed=0, options={"map": 0})
    assert again["seed"] == info["seed"]
    venv = ExploreVectorEnv(2, folder, resolution=0.25, view=16, k=4)
    venv.reset(seed=0, options={"map": [0, 1]})
    venv.step(np.zeros(2, np.int64))
    with pytest.raises(ValueError, match="c.pgm"):
        venv.reset(seed=7, options={"map": [1, 2]})
    with pytest.raises(gymnasium.error.ResetNeeded):
        venv.step(np.zeros(2, np.int64))
    venv.reset(seed=7, options={"map": [1, 0]})
    venv.step(np.zeros(2, np.int64))


def test_regression_a_list_of_seeds_seeds_the_later_resets(office):
    """Regression: after reset(seed=[...]) the later unseeded resets drew from a generator
    nobody had seeded, so a run seeded by a list could not be repeated; an int could."""
    def episodes(first):
        venv = ExploreVectorEnv(2, office, k=4)
        _, info = venv.reset(seed=first)
        paths = [info["path_length_m"].tolist()]
        for _ in range(2):
            for _ in range(3):
                venv.step(np.zeros(2, np.int64))
            obs, _ = venv.reset()
            paths.append([obs["pose"].tolist()])
        return paths
    assert episodes([3, 11]) == episodes([3, 11])
    assert episodes([3, 11]) != episodes([3, 12])


def test_regression_a_closed_vector_env_stops_its_threads(office):
    """Regression: close() did nothing: the helper threads stayed until garbage collection
    and the environment went on stepping."""
    import threading
    before = threading.active_count()
    venv = ExploreVectorEnv(2, office, k=4, threads=2)
    venv.reset(seed=0)
    venv.step(np.zeros(2, np.int64))
    venv.close()
    venv.close()
    with pytest.raises(gymnasium.error.ClosedEnvironmentError, match="step: the environment is closed"):
        venv.step(np.zeros(2, np.int64))
    with pytest.raises(gymnasium.error.ClosedEnvironmentError, match="reset"):
        venv.reset(seed=0)
    assert threading.active_count() == before


def test_regression_messages_have_no_runs_of_spaces(office):
    """Regression: a string continued over lines without its backslash put 14 spaces in the
    middle of the any-angle message."""
    with pytest.raises(ValueError) as e:
        ExploreEnv(office, motion="any-angle")
    assert "  " not in str(e.value), str(e.value)


def test_regression_a_second_thread_is_told_the_environment_is_busy():
    """Regression: a thread calling an environment while another thread's call was under
    way (the native core steps with the GIL released) got PyO3's bare "Already borrowed"."""
    import threading

    env = ExploreEnv("office", size=(12, 10), resolution=0.1, k=8)
    venv = ExploreVectorEnv(2, "office", size=(12, 10), resolution=0.1, k=8)
    errors = []

    def hammer(step, reset):
        started = False
        for _ in range(300):
            try:
                if not started or step()[2] is True:
                    started = False
                    reset()
                    started = True
            except RuntimeError as e:
                errors.append(str(e))
            except gymnasium.error.ResetNeeded:
                errors.append("reset needed")
                started = False

    for step, reset in (
        (lambda: env.step(0), lambda: env.reset(seed=1)),
        (lambda: venv.step(np.zeros(2, dtype=np.int64)), lambda: venv.reset(seed=1)),
    ):
        threads = [threading.Thread(target=hammer, args=(step, reset)) for _ in range(4)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    busy = [e for e in errors if e != "reset needed"]
    assert busy, "no two calls met"
    assert all(e.startswith("this environment is in a call from another thread") for e in busy), \
        set(busy)


def test_regression_asking_a_baseline_again_changes_nothing():
    """Regression: every ask of a baseline drew from the episode's strategy stream again, so
    Baseline("random")(env) gave another action at each call of one decision, and a
    baseline episode that asked once more per step (to log the action) travelled another
    path (759.1 m instead of 729.7 m on this map with strategy "dt")."""
    m = frontier.Map.generate("office", seed=3)
    e = ExploreEnv(m, strategy="dt")
    e.reset(seed=1)
    asks = [Baseline("random")(e) for _ in range(5)]
    assert asks == [asks[0]] * 5
    e.step(asks[0])
    asks = [Baseline("random")(e) for _ in range(5)]
    assert asks == [asks[0]] * 5

    def run(asks_per_step, preset):
        env = ExploreEnv(m, strategy="dt")
        obs, _ = env.reset(seed=1)
        trace = []
        while True:
            actions = [Baseline(preset)(env) for _ in range(asks_per_step)]
            assert actions == [actions[0]] * asks_per_step
            obs, reward, terminated, truncated, info = env.step(actions[0])
            trace.append((actions[0], reward, obs["belief"].tobytes(), obs["pose"].tobytes(),
                          obs["candidates"].tobytes()))
            if terminated or truncated:
                return trace, info["path_length_m"]

    for preset in ("random", "dt"):
        once, path = run(1, preset)
        assert run(3, preset) == (once, path), preset
    v = ExploreVectorEnv(2, m, strategy="dt")
    v.reset(seed=1)
    asks = [Baseline("random")(v).tolist() for _ in range(4)]
    assert asks == [asks[0]] * 4
    pettingzoo = pytest.importorskip("frontier.pettingzoo")
    p = pettingzoo.ExploreParallelEnv(m, robots=2, strategy="dt")
    p.reset(seed=1)
    asks = [Baseline("random")(p) for _ in range(4)]
    assert asks == [asks[0]] * 4


def test_regression_asking_a_baseline_leaves_the_episode_as_it_was():
    """Regression: the first ask of a baseline at a decision drew from the episode's strategy
    stream, so an agent that logged Baseline("random")'s action beside its own got another
    episode than one that did not ask (with strategy "dt", which samples its candidates from
    that stream). The ask draws from a copy, which the episode takes only if the step takes
    the asked action (then the episode is the baseline's, as in a run of the preset)."""
    m = frontier.Map.generate("office", seed=3)

    def run(actions=None):
        env = ExploreEnv(m, strategy="dt")
        obs, _ = env.reset(seed=1)
        taken, trace = [], []
        for t in range(80):
            if actions is None:
                asked = Baseline("random")(env)
                offered = int(obs["action_mask"].sum())
                if offered < 2:
                    break  # no action other than the asked one
                action = (asked + 1) % offered
            else:
                action = actions[t]
            obs, reward, terminated, truncated, info = env.step(action)
            taken.append(action)
            trace.append((reward, obs["belief"].tobytes(), obs["candidates"].tobytes()))
            if terminated or truncated:
                break
        return taken, trace

    taken, asked = run()
    assert len(taken) >= 20, len(taken)
    assert run(taken)[1] == asked

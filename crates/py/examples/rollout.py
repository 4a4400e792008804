"""Roll out a random policy and the cf-rr baseline in one environment and in the vector
environment (no training) and print environment steps per second.

    python crates/py/examples/rollout.py [--envs 8,16] [--threads 2] [--steps 1000]
                                         [--rounds 5] [--sensing every-3]

The default setting is Explore-Bench's grid simulator's: a 250 x 250 map at 0.1 m and a
3.5 m sensing range (Explore-Bench reports about 5 steps/s there).

Each measurement runs in a process of its own (this script again, with --worker), as a
training script runs one kind of environment: stepping the other kind in the same process
between the vector environment's calls evicts the caches its threads step from, and made its
steps 4-21 % slower. One ExploreEnv and the vector environment are measured by turns, --rounds
times (the first of the two alternating), so that the machine's changing speed slows both
alike. It prints the median steps/s of each, the median of the rounds' ratios (each round's
two measurements run back to back, so its ratio is the least touched by the drift) and
each round's ratio.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

from frontier.gym import Baseline, ExploreEnv, ExploreVectorEnv, RandomPolicy


def single_steps(env, policy, episodes, steps):
    """One ExploreEnv: `steps` steps of episodes 0..episodes-1 (seed i), the resets
    included (as the vector environment's automatic resets are); yields 1 per step."""
    for i in range(episodes):
        obs, _ = env.reset(seed=i)
        for _ in range(steps):
            a = policy(env) if isinstance(policy, Baseline) else policy(obs)
            obs, _, term, trunc, _ = env.step(a)
            yield 1
            if term or trunc:
                break


def vector_steps(venv, policy, steps):
    """A vector env doing the same work: environment i runs episode i (ExploreEnv's seed
    i) for `steps` steps, all in one call per step; yields the steps of each call."""
    obs, _ = venv.reset(seed=0)
    for _ in range(steps):
        a = policy(venv) if isinstance(policy, Baseline) else policy(obs)
        obs, _, _, _, _ = venv.step(a)
        yield venv.num_envs


def rate(steps):
    """Steps per second of a generator of step counts, run to its end."""
    t0 = time.perf_counter()
    done = sum(steps)
    return done / (time.perf_counter() - t0)


def worker(a, common):
    """One measurement (`--worker single|vector`): print its steps per second."""
    policy = RandomPolicy(0) if a.policy == "random" else Baseline("cf-rr")
    n = a.n
    per_env = max(a.steps // n, 1)
    if a.worker == "single":
        steps = single_steps(ExploreEnv(**common), policy, n, per_env)
    else:
        steps = vector_steps(ExploreVectorEnv(n, threads=a.threads, **common), policy, per_env)
    print(json.dumps(rate(steps)))


def measure(kind, policy, n, argv):
    """Run one worker process and return its steps per second."""
    cmd = [sys.executable, __file__, *argv, "--worker", kind, "--policy", policy, "--n", str(n)]
    # numpy's OpenBLAS starts a worker thread per core, which spins for about 0.1 s after
    # numpy is imported: on two cores it would take one from the vector environment's
    # threads at the start of its measurement. Nothing here calls BLAS.
    env = dict(os.environ)
    env.setdefault("OPENBLAS_NUM_THREADS", "1")
    out = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env).stdout
    return float(out.strip().splitlines()[-1])


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--envs", default="8,16", help="environments in the vector env (list)")
    p.add_argument("--threads", type=int, default=None, help="Rust threads (default: cores)")
    p.add_argument("--steps", type=int, default=1000, help="environment steps per measurement")
    p.add_argument("--rounds", type=int, default=5, help="measurements of each, by turns")
    p.add_argument("--size", type=float, default=25.0, help="map side in metres")
    p.add_argument("--resolution", type=float, default=0.1, help="metres per cell")
    p.add_argument("--sensor", default="los:r=3.5", help="sensor spec")
    p.add_argument("--kind", default="office", help="generated environment kind")
    p.add_argument("--sensing", default=None,
                   help="sensing mode, e.g. every-3 (Explore-Bench's every third cell)")
    p.add_argument("--worker", choices=["single", "vector"], help=argparse.SUPPRESS)
    p.add_argument("--policy", choices=["random", "cf-rr"], help=argparse.SUPPRESS)
    p.add_argument("--n", type=int, help=argparse.SUPPRESS)
    a = p.parse_args()
    common = dict(
        maps=a.kind, size=(a.size, a.size), resolution=a.resolution, sensor=a.sensor, k=16,
    )
    if a.sensing:
        common["sensing"] = a.sensing
    if a.worker:
        worker(a, common)
        return
    # the workers get this run's own options (they ignore --envs and --rounds)
    argv = sys.argv[1:]
    print(f"{a.kind} {a.size:g} x {a.size:g} m at {a.resolution} m, sensor {a.sensor}, "
          f"sensing {a.sensing or 'continuous'}, K = 16, {a.rounds} rounds")
    for policy in ["random", "cf-rr"]:
        for n in [int(k) for k in a.envs.split(",")]:
            singles, vectors = [], []
            for r in range(a.rounds):
                kinds = ["single", "vector"] if r % 2 == 0 else ["vector", "single"]
                got = {k: measure(k, policy, n, argv) for k in kinds}
                singles.append(got["single"])
                vectors.append(got["vector"])
            ratios = [v / s for s, v in zip(singles, vectors)]
            single, vector = statistics.median(singles), statistics.median(vectors)
            print(
                f"{policy:>7}: ExploreEnv {single:7.0f} steps/s | ExploreVectorEnv {n} envs "
                f"{vector:7.0f} steps/s ({statistics.median(ratios):.2f}x; by round "
                f"{' '.join(f'{r:.2f}' for r in ratios)}) | Explore-Bench ~5 steps/s"
            )


if __name__ == "__main__":
    main()

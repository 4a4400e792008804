"""Roll out a random policy and the cf-rr baseline in one environment and in the vector
environment (no training) and print environment steps per second.

    python crates/py/examples/rollout.py [--envs 8,16] [--threads 2] [--steps 1000]

The default setting is Explore-Bench's grid simulator's: a 250 x 250 map at 0.1 m and a
3.5 m sensing range (Explore-Bench reports about 5 steps/s there).
"""

import argparse
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


def rates(contenders, slice_steps=400):
    """Steps per second of each generator, run by turns about `slice_steps` steps at a time
    so that the machine's changing speed slows them alike."""
    spent = [0.0] * len(contenders)
    done = [0] * len(contenders)
    live = set(range(len(contenders)))
    while live:
        for k in sorted(live):
            t0 = time.perf_counter()
            n = 0
            for d in contenders[k]:
                n += d
                if n >= slice_steps:
                    break
            else:
                live.discard(k)
            spent[k] += time.perf_counter() - t0
            done[k] += n
    return [d / t for d, t in zip(done, spent)]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--envs", default="8,16", help="environments in the vector env (list)")
    p.add_argument("--threads", type=int, default=None, help="Rust threads (default: cores)")
    p.add_argument("--steps", type=int, default=1000, help="environment steps per measurement")
    p.add_argument("--size", type=float, default=25.0, help="map side in metres")
    p.add_argument("--resolution", type=float, default=0.1, help="metres per cell")
    p.add_argument("--sensor", default="los:r=3.5", help="sensor spec")
    p.add_argument("--kind", default="office", help="generated environment kind")
    p.add_argument("--sensing", default=None,
                   help="sensing mode, e.g. every-3 (Explore-Bench's every third cell)")
    a = p.parse_args()
    common = dict(
        maps=a.kind, size=(a.size, a.size), resolution=a.resolution, sensor=a.sensor, k=16,
    )
    if a.sensing:
        common["sensing"] = a.sensing
    print(f"{a.kind} {a.size:g} x {a.size:g} m at {a.resolution} m, sensor {a.sensor}, "
          f"sensing {a.sensing or 'continuous'}, K = 16")
    envs = [int(n) for n in a.envs.split(",")]
    for name, make in [("random", lambda: RandomPolicy(0)), ("cf-rr", lambda: Baseline("cf-rr"))]:
        for n in envs:
            per_env = max(a.steps // n, 1)
            venv = ExploreVectorEnv(n, threads=a.threads, **common)
            single, vector = rates([
                single_steps(ExploreEnv(**common), make(), n, per_env),
                vector_steps(venv, make(), per_env),
            ])
            print(
                f"{name:>7}: ExploreEnv {single:7.0f} steps/s | ExploreVectorEnv {n} envs "
                f"{vector:7.0f} steps/s ({vector / single:.2f}x) | Explore-Bench ~5 steps/s"
            )


if __name__ == "__main__":
    main()

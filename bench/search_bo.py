#!/usr/bin/env python3
"""Bayesian optimisation (Python) against the C++ strategies on the planted 0.1 % failure.

Runs ``probrobscene.search`` on examples/table_cube.prs with a Python controller that fails
exactly as the built-in ``planted-1-permille`` (the cube within 2.88 cm of (-0.8, 0.3), score =
the distance to that disk) for seeds 1..N, per strategy, and prints the median episodes to the
first failure, the median failures in the budget, and the seconds per search.

usage: PYTHONPATH=build/python bench/search_bo.py [--budget 300] [--seeds 20]
                                                  [--strategies bo,ce,random]
"""
import argparse
import math
import os
import statistics
import time

import probrobscene as prs

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def planted(scene):
    x, y, _ = scene["Cube#5"].position
    gap = math.hypot(x + 0.8, y - 0.3) - 0.0288
    return {"outcome": "planted-failure" if gap <= 0 else "success", "score": gap}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--budget", type=int, default=300)
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--strategies", default="bo,ce,random")
    args = parser.parse_args()
    scenario = prs.load(os.path.join(ROOT, "examples/table_cube.prs"))
    print(f"planted 0.1 % (Python controller), budget {args.budget}, seeds 1..{args.seeds}")
    print(f"{'strategy':8} {'median first failure':>21} {'median failures':>16} {'s per search':>13}")
    for strategy in args.strategies.split(","):
        firsts, counts, seconds = [], [], []
        for seed in range(1, args.seeds + 1):
            begin = time.perf_counter()
            records = prs.search(scenario, planted, budget=args.budget, seed=seed,
                                 strategy=strategy)
            seconds.append(time.perf_counter() - begin)
            failed = [r["index"] for r in records if r["outcome"] != "success"]
            firsts.append(failed[0] + 1 if failed else args.budget + 1)
            counts.append(len(failed))
        print(f"{strategy:8} {statistics.median(firsts):>21} {statistics.median(counts):>16} "
              f"{statistics.mean(seconds):>13.2f}")


if __name__ == "__main__":
    main()

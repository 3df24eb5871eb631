#!/usr/bin/env python3
"""Failure search against i.i.d. sampling on planted failures (docs/benchmarks.md).

For each strategy and seed, runs `prs search` with a planted-failure controller and reads its
records: the number of episodes to the first failure, and the failures in the whole budget.
Prints, per strategy, the median over the seeds of both, and the ratios to `random` (i.i.d.).
A strategy that finds no failure in the budget counts the budget + 1 as its first failure
(so the median is a lower bound on the truth for i.i.d. at 0.1 %).

usage: bench/search_planted.py [--prs build/src/cli/prs] [--controller planted-1-permille]
                               [--budget 1000] [--seeds 20] [--first-seed 1]
                               [--strategies random,ce,anneal]
                               [-- extra prs search options]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(prs, spec, controller, strategy, budget, seed, extra):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "records.jsonl")
        subprocess.run([prs, "search", spec, "--controller", controller, "--strategy", strategy,
                        "--budget", str(budget), "-s", str(seed), "-o", out, "-q"] + extra,
                       check=True, stdout=subprocess.DEVNULL)
        first, failures = budget + 1, 0
        with open(out) as f:
            for n, line in enumerate(f, 1):
                if json.loads(line)["outcome"] != "success":
                    failures += 1
                    first = min(first, n)
        return first, failures


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--prs", default=os.path.join(ROOT, "build/src/cli/prs"))
    parser.add_argument("--spec", default=os.path.join(ROOT, "examples/table_cube.prs"))
    parser.add_argument("--controller", default="planted-1-permille")
    parser.add_argument("--budget", type=int, default=1000)
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--first-seed", type=int, default=1)
    parser.add_argument("--strategies", default="random,ce,anneal")
    args, extra = parser.parse_known_args()
    extra = [a for a in extra if a != "--"]
    results = {}
    for strategy in args.strategies.split(","):
        runs = [run(args.prs, args.spec, args.controller, strategy, args.budget, seed, extra)
                for seed in range(args.first_seed, args.first_seed + args.seeds)]
        results[strategy] = (statistics.median(r[0] for r in runs),
                             statistics.median(r[1] for r in runs),
                             sum(r[1] > 0 for r in runs))
    base = results.get("random")
    last = args.first_seed + args.seeds - 1
    print(f"{args.controller}, budget {args.budget}, seeds {args.first_seed}..{last} "
          f"{' '.join(extra)}")
    print(f"{'strategy':10} {'median first failure':>22} {'median failures':>16} "
          f"{'seeds with one':>15} {'first vs iid':>13} {'failures vs iid':>16}")
    for strategy, (first, failures, found) in results.items():
        ratio_first = f"{base[0] / first:.1f}x" if base else "-"
        ratio_fail = (f"{failures / base[1]:.1f}x" if base and base[1] > 0 else
                      ("inf" if failures > 0 else "-"))
        print(f"{strategy:10} {first:>22} {failures:>16} {found:>15} {ratio_first:>13} "
              f"{ratio_fail:>16}")


if __name__ == "__main__":
    sys.exit(main())

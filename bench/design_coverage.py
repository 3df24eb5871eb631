#!/usr/bin/env python3
"""Coverage of space-filling designs against i.i.d. points (docs/benchmarks.md).

Runs `prs test --design D -n 256` (the planted controller only to get records, which carry each
scene's coordinates) for seeds 1..10 and prints the mean L2-star discrepancy (Warnock's
formula) of the cube's two position coordinates and of all coordinates, per design. The
i.i.d. row uses `prs search --strategy random`, whose points are i.i.d. uniform.

usage: bench/design_coverage.py [--prs build/src/cli/prs] [-n 256] [--seeds 10]
"""
import argparse
import json
import os
import subprocess
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SPEC = os.path.join(ROOT, "examples/table_cube.prs")


def l2_star(points):
    x = np.asarray(points)
    n, d = x.shape
    single = np.prod((1 - x * x) / 2, axis=1).sum()
    pairs = np.prod(1 - np.maximum(x[:, None, :], x[None, :, :]), axis=2).sum()
    return np.sqrt(max(0.0, 3.0 ** -d - 2.0 / n * single + pairs / n ** 2))


def coordinates(prs, design, n, seed):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "r.jsonl")
        if design == "iid":
            cmd = [prs, "search", SPEC, "--strategy", "random", "--budget", str(n)]
        else:
            cmd = [prs, "test", SPEC, "--design", design, "-n", str(n)]
        subprocess.run(cmd + ["--controller", "planted-1-percent", "-s", str(seed), "-o", out,
                              "-q"], check=True, stdout=subprocess.DEVNULL)
        with open(out) as f:
            return [json.loads(line)["coordinates"] for line in f]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--prs", default=os.path.join(ROOT, "build/src/cli/prs"))
    parser.add_argument("-n", type=int, default=256)
    parser.add_argument("--seeds", type=int, default=10)
    args = parser.parse_args()
    print(f"table_cube.prs, n = {args.n}, mean over seeds 1..{args.seeds}")
    print(f"{'design':8} {'cube position (2 coords)':>25} {'all coordinates':>16}")
    for design in ["iid", "sobol", "halton", "lattice"]:
        cube, every = [], []
        for seed in range(1, args.seeds + 1):
            u = np.asarray(coordinates(args.prs, design, args.n, seed))
            cube.append(l2_star(u[:, 6:8]))
            every.append(l2_star(u))
        print(f"{design:8} {np.mean(cube):>25.5f} {np.mean(every):>16.5f}")


if __name__ == "__main__":
    main()

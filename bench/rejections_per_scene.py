#!/usr/bin/env python3
"""Rejections per accepted scene, by reason, as mean and standard error of the mean: the figures
of docs/benchmarks.md's Table II comparison. Reads the JSON Lines of `prs sample` on stdin
(each scene records its own rejections by reason) and prints one Markdown table row per reason.

    prs sample examples/table_cube_naive.prs --naive -n 1000 -s 1 | bench/rejections_per_scene.py
"""
import json
import math
import sys


def main() -> int:
    per_scene = []  # one {reason: count} per scene
    for number, line in enumerate(sys.stdin, 1):
        if not line.strip():
            continue
        try:
            per_scene.append(json.loads(line)["rejections"])
        except (ValueError, KeyError, TypeError) as error:
            print(f"rejections_per_scene: line {number} is not a prs scene: {error}", file=sys.stderr)
            return 1
    if len(per_scene) < 2:
        print("rejections_per_scene: need at least two scenes on stdin", file=sys.stderr)
        return 1
    reasons = sorted({reason for scene in per_scene for reason in scene})
    n = len(per_scene)
    print(f"| reason | mean ± s.e. per scene ({n} scenes) |")
    print("|---|---|")
    for reason in reasons + ["total"]:
        values = [sum(s.values()) if reason == "total" else s.get(reason, 0) for s in per_scene]
        mean = sum(values) / n
        variance = sum((v - mean) ** 2 for v in values) / (n - 1)
        print(f"| {reason} | {mean:.2f} ± {math.sqrt(variance / n):.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

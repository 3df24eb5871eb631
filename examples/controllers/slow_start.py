#!/usr/bin/env python3
r"""An example of a controller with a slow start, run as a persistent worker of `prs test`.

It pays its start-up (2 s of sleep standing in for a simulator's launch; PRS_EXAMPLE_STARTUP_S
sets the seconds) once per worker, then `probrobscene.serve` hands it scene after scene. It
decides like reach_check.py: every Cube must lie 0.25 to 0.855 m (a Franka Panda's reach) from
the nearest Robot, and the score is the margin in metres (larger is safer, 0 or less a failure).

    prs test examples/table_cube.prs --exec 'python3 examples/controllers/slow_start.py' \
        --persistent -n 200 --threads 2

Without --persistent it still works, one process per scene, paying the start-up every time.
Only the standard library: it finds probrobscene's pure-Python part in this repository's python/
directory, so it runs with Debian's /usr/bin/python3 as is, without building anything.
"""
import math
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from probrobscene.serve import serve  # noqa: E402  (after the path is set)

MAX_REACH_M = 0.855
MIN_REACH_M = 0.25


def start_simulator():
    """Stands in for launching a simulator: the slow part that a persistent worker pays once."""
    time.sleep(float(os.environ.get("PRS_EXAMPLE_STARTUP_S", "2")))
    print(f"worker {os.environ.get('PRS_WORKER', '-')} ready", file=sys.stderr)


def decide(scene):
    """One episode: the scene (spec §8 JSON, as a dict) in, an answer out."""
    objects = scene["objects"]
    robots = [o for o in objects if o["class"] == "Robot"]
    cubes = [(i, o) for i, o in enumerate(objects) if o["class"] == "Cube"]
    if not robots or not cubes:
        return {"outcome": "missing-object",
                "detail": "the scene needs at least one Cube and one Robot"}
    margins = []
    for index, cube in cubes:
        distance_m, robot = min((math.dist(cube["position"], r["position"]), r["name"])
                                for r in robots)
        name = cube["name"] if cube["name"] is not None else f"{cube['class']}#{index}"
        margin_m = min(MAX_REACH_M - distance_m, distance_m - MIN_REACH_M)
        margins.append((margin_m, f"{name} is {distance_m:.3f} m from {robot}", distance_m))
    margin_m, where, distance_m = min(margins)
    print(where, file=sys.stderr)  # print is free for logging: serve sends it to stderr
    if margin_m < 0:
        return {"outcome": "out-of-reach", "detail": f"{where}, out of the arm's reach",
                "score": margin_m, "distance_m": distance_m}
    return {"outcome": "success", "detail": "every Cube is within an arm's reach",
            "score": margin_m, "distance_m": distance_m}


if __name__ == "__main__":
    start_simulator()
    serve(decide)

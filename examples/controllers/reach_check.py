#!/usr/bin/env python3
"""An example of your own controller for `prs test --exec` (protocol: docs/harness.md).

Like the built-in `demo-reach`, it decides from the scene alone, without simulation: every Cube
must lie 0.25 to 0.855 m (a Franka Panda's reach) from the nearest Robot. A real controller would
build its simulated world from the same scene JSON, run, and report what happened.

    prs test examples/table_cube.prs --exec 'python3 examples/controllers/reach_check.py' -n 20

Only the standard library: it runs with Debian's /usr/bin/python3 as is.
"""
import json
import math
import os
import sys

MAX_REACH_M = 0.855
MIN_REACH_M = 0.25


def answer(outcome, detail, **extra):
    """The last line of stdout is the answer: one JSON object with an "outcome"."""
    print(json.dumps({"outcome": outcome, "detail": detail, **extra}))
    sys.exit(0)


def display_name(obj, index):
    """The object's variable name, or Class#index for an anonymous object (as prs names it)."""
    return obj["name"] if obj["name"] is not None else f"{obj['class']}#{index}"


def read_scene():
    """The scene arrives on stdin; the same line is in the file named by PRS_SCENE_FILE."""
    scene = json.loads(sys.stdin.readline())
    with open(os.environ["PRS_SCENE_FILE"], encoding="utf-8") as scene_file:
        same_file = json.loads(scene_file.readline()) == scene
    same_ids = (os.environ.get("PRS_SEED") == str(scene["seed"])
                and os.environ.get("PRS_INDEX") == str(scene["index"]))
    if not (same_file and same_ids):
        answer("bad-input", "stdin, PRS_SCENE_FILE, PRS_SEED and PRS_INDEX disagree")
    return scene


def main():
    scene = read_scene()
    objects = scene["objects"]
    robots = [o for o in objects if o["class"] == "Robot"]
    cubes = [(i, o) for i, o in enumerate(objects) if o["class"] == "Cube"]
    if not robots or not cubes:
        answer("missing-object", "the scene needs at least one Cube and one Robot")
    for index, cube in cubes:
        distance_m, robot = min((math.dist(cube["position"], r["position"]), r["name"])
                                for r in robots)
        name = display_name(cube, index)
        if distance_m > MAX_REACH_M:
            answer("no-path", f"{name} is {distance_m:.3f} m from {robot}, out of reach",
                   distance_m=distance_m)
        if distance_m < MIN_REACH_M:
            answer("no-path", f"{name} is {distance_m:.3f} m from {robot}, too close to the base",
                   distance_m=distance_m)
    print("every cube is within reach", file=sys.stderr)  # stderr is free for logging
    answer("success", "every Cube is within an arm's reach")


if __name__ == "__main__":
    main()

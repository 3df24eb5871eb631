#!/usr/bin/env python3
"""Why each perception fault of a case-study run happened: the cube wholly in the camera's view
(so something hid it: in the simulation, an arm), partly out of view, or wholly out of view.

Usage: bench/perception_faults.py RESULTS.jsonl SCENES.jsonl
  RESULTS: `prs test ... -o RESULTS.jsonl` records; SCENES: `prs sample` of the same scenario,
  seed and indices (the scene of each record is found by its index).
Prints the outcome counts and the perception faults split by view. The camera model is the
case study's: the Camera object looks along its +y with +z up, a 45° vertical field of view at
640 × 480 pixels (fovy_deg overrides the 45°), as prs export writes it into MJCF.
"""
import json
import math
import sys
from collections import Counter


def quaternion_matrix(w, x, y, z):
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def in_image(camera, point):
    """Whether a world point projects into the camera's 640 x 480 image."""
    r = quaternion_matrix(*camera["orientation"]["quaternion"])
    d = [point[i] - camera["position"][i] for i in range(3)]
    local = [sum(r[i][j] * d[i] for i in range(3)) for j in range(3)]  # x right, y look, z up
    if local[1] <= 0:
        return False
    fovy = camera.get("properties", {}).get("fovy_deg", 45)
    focal = 240 / math.tan(math.radians(fovy) / 2)
    column, row = 320 + focal * local[0] / local[1], 240 - focal * local[2] / local[1]
    return 0 <= column <= 640 and 0 <= row <= 480


def view_of_cube(scene):
    camera = next(o for o in scene["objects"] if o["class"] == "Camera")
    cube = next(o for o in scene["objects"] if o["class"] == "Cube")
    r = quaternion_matrix(*cube["orientation"]["quaternion"])
    half = [d / 2 for d in cube["dimensions"]]
    corners = []
    for k in range(8):
        s = [half[i] * (1 if k >> i & 1 else -1) for i in range(3)]
        corners.append([cube["position"][i] + sum(r[i][j] * s[j] for j in range(3)) for i in range(3)])
    seen = sum(in_image(camera, c) for c in corners)
    return "wholly in view" if seen == 8 else "wholly out of view" if seen == 0 else "partly out of view"


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    scenes = {}
    with open(sys.argv[2]) as f:
        for line in f:
            scene = json.loads(line)
            scenes[scene["index"]] = scene
    outcomes, faults = Counter(), Counter()
    with open(sys.argv[1]) as f:
        for line in f:
            record = json.loads(line)
            outcomes[record["outcome"]] += 1
            if record["outcome"] == "perception-fault":
                faults[view_of_cube(scenes[record["index"]])] += 1
    print("outcomes:", ", ".join(f"{k} {v}" for k, v in outcomes.most_common()))
    print("perception faults:", ", ".join(f"{k} {v}" for k, v in faults.most_common()) or "none")


if __name__ == "__main__":
    main()

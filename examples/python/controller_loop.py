#!/usr/bin/env python3
"""Runs a user's controller over sampled Table-Cube scenes, the way a test harness would: each
scene gives the start state, a toy proportional controller drives robot r1's gripper (a point
above the robot base) to just above the cube, and the loop reports how often it got there.

Swap `reach_cube` for your simulator step or policy; the scene loop stays the same.
Usage: controller_loop.py [N_SCENES] [SEED]    (defaults: 200, 1)
"""

import pathlib
import sys

import numpy as np

import probrobscene as prs

EXAMPLES = pathlib.Path(__file__).resolve().parents[1]
DT = 0.01           # s per control step
MAX_SPEED = 0.5     # m/s, the gripper's speed limit
GAIN = 4.0          # 1/s, proportional gain
TOLERANCE = 0.005   # m, "arrived"
MAX_STEPS = 500


def reach_cube(gripper: np.ndarray, target: np.ndarray) -> int:
    """Steps the gripper towards the target; returns the steps taken, or -1 if it never arrived."""
    for step in range(MAX_STEPS):
        error = target - gripper
        if np.linalg.norm(error) < TOLERANCE:
            return step
        velocity = GAIN * error
        speed = np.linalg.norm(velocity)
        if speed > MAX_SPEED:
            velocity *= MAX_SPEED / speed
        gripper = gripper + DT * velocity
    return -1


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 200
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    scenario = prs.load(EXAMPLES / "table_cube.prs")
    steps = []
    for scene in scenario.scenes(seed=seed, count=n):
        robot, cube = scene["r1"], scene["Cube#5"]
        gripper = robot.position + np.array([0.0, 0.0, 0.3])         # above the base
        target = cube.position + np.array([0.0, 0.0, cube.dimensions[2]])  # above the cube
        result = reach_cube(gripper, target)
        steps.append(result)
        if result < 0:
            print(f"scene {scene.index}: did not reach the cube at {cube.position.round(3)}")
    arrived = [s for s in steps if s >= 0]
    print(f"{len(arrived)}/{n} scenes reached (seed {seed}); "
          f"mean {np.mean(arrived) * DT:.2f} s, max {max(arrived) * DT:.2f} s")


if __name__ == "__main__":
    main()

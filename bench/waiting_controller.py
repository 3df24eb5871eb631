#!/usr/bin/env python3
"""A controller whose episode is waiting, for bench/harness_threads.sh: it sleeps
PRS_BENCH_EPISODE_S seconds (default 0.05) per scene, standing in for a simulator that runs
elsewhere (another process, a GPU), and answers "success". As a persistent worker
(`prs test --exec CMD --persistent`) it starts once per thread. Standard library only."""
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from probrobscene.serve import serve  # noqa: E402  (after the path is set)

EPISODE_S = float(os.environ.get("PRS_BENCH_EPISODE_S", "0.05"))


def wait(scene):
    time.sleep(EPISODE_S)
    return "success"


if __name__ == "__main__":
    serve(wait)

"""The Python examples run and produce what they promise (a PNG plot; a controller report)."""

import os
import subprocess
import sys

from conftest import REPO

SCRIPTS = REPO / "examples" / "python"


def run_example(name, *args, cwd):
    env = dict(os.environ, MPLBACKEND="Agg")
    result = subprocess.run([sys.executable, str(SCRIPTS / name), *map(str, args)], cwd=cwd,
                            env=env, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    return result.stdout


def test_plot_cube_positions_writes_a_png(tmp_path):
    out = tmp_path / "cubes.png"
    stdout = run_example("plot_cube_positions.py", 300, out, cwd=tmp_path)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "over 300 scenes" in stdout


def test_controller_loop_reaches_every_cube(tmp_path):
    stdout = run_example("controller_loop.py", 40, 3, cwd=tmp_path)
    assert "40/40 scenes reached (seed 3)" in stdout

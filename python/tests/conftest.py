"""Shared fixtures of the probrobscene tests: the repository's examples and the built `prs`."""

import os
import pathlib
import subprocess

import pytest

import probrobscene as prs

REPO = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"


@pytest.fixture(scope="session")
def prs_binary() -> pathlib.Path:
    """The `prs` command built from the same sources (PRS_BINARY, else build/src/cli/prs)."""
    path = pathlib.Path(os.environ.get("PRS_BINARY", REPO / "build" / "src" / "cli" / "prs"))
    if not path.is_file():
        pytest.fail(f"the prs binary is not built at {path} (set PRS_BINARY)")
    return path


@pytest.fixture(scope="session")
def table_cube() -> prs.Scenario:
    return prs.load(EXAMPLES / "table_cube.prs")


@pytest.fixture(scope="session")
def constructs() -> prs.Scenario:
    """About 0.3 ms a scene: heavy enough that sampling, not handing scenes to Python, dominates."""
    return prs.load(EXAMPLES / "constructs.prs")


def run_prs(binary: pathlib.Path, *args: str) -> subprocess.CompletedProcess:
    """Runs `prs ARGS...` and returns its result (stdout and stderr as text)."""
    return subprocess.run([str(binary), *args], capture_output=True, text=True, timeout=300)

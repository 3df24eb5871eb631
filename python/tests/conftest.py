"""Shared fixtures of the probrobscene tests: the repository's examples and the built `prs`."""

import os
import pathlib
import subprocess

import pytest

import probrobscene as prs
import probrobscene.campaign as campaign

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


def bin_program(cubes: int) -> str:
    """`cubes` 5 cm cubes at any yaw completely on a 0.5 x 0.4 m bin (examples/model.prs)."""
    return ("from model import *\n"
            "bin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4\n"
            f"for i in range({cubes}):\n"
            "    Cube completely on bin, with yaw Range(0, 2 * math.pi)\n")


def expect_prs_sample_scenes(binary: pathlib.Path, scenario: prs.Scenario, path: pathlib.Path,
                             seed: int, count: int) -> None:
    """`scenario` (`path` loaded with a sampler) gives the same scenes on 1 and 2 threads, and
    they are `prs sample --sampler SAMPLER`'s."""
    sampler = scenario.sampler
    one = [s.to_json() for s in scenario.scenes(seed=seed, count=count, threads=1)]
    two = [s.to_json() for s in scenario.scenes(seed=seed, count=count, threads=2)]
    assert one == two
    result = run_prs(binary, "sample", str(path), "-I", str(EXAMPLES), "--sampler", sampler,
                     "-s", str(seed), "-n", str(count))
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == one


def expect_campaign_is_prs_sample(binary: pathlib.Path, tmp_path: pathlib.Path,
                                  path: pathlib.Path, sampler: str, count: int) -> None:
    """A campaign of `count` scenes in shards of 7 (seed 4), run and merged, is `prs sample`'s
    output for the same sampler."""
    camp = tmp_path / "camp"
    campaign.init(camp, path, count, seed=4, shard_size=7, search_path=[EXAMPLES],
                  sampler=sampler)
    campaign.run(camp)
    campaign.merge(camp, tmp_path / "m.jsonl")
    result = run_prs(binary, "sample", str(path), "-I", str(EXAMPLES), "--sampler", sampler,
                     "-s", "4", "-n", str(count))
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "m.jsonl").read_text() == result.stdout

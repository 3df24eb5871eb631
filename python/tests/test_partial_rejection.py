"""sampler="partial-rejection": the same scenes as `prs sample --sampler partial-rejection`, for
any thread count and in campaigns of any shard size, with the sites and the pilot on the
scenario; programs outside its reach refused with the located message."""

import pytest

import probrobscene as prs
import probrobscene.campaign as campaign
from conftest import EXAMPLES, run_prs

BIN = """from model import *
bin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4
for i in range(6):
    Cube completely on bin, with yaw Range(0, 2 * math.pi)
"""


def test_partial_rejection_scenes_are_prs_samples_for_any_threads(prs_binary, tmp_path):
    path = tmp_path / "bin.prs"
    path.write_text(BIN)
    scenario = prs.load(path, search_path=[EXAMPLES], sampler="partial-rejection")
    assert scenario.sampler == "partial-rejection"
    assert scenario.partial_rejection is None  # no scene drawn yet
    one = [s.to_json() for s in scenario.scenes(seed=3, count=40, threads=1)]
    two = [s.to_json() for s in scenario.scenes(seed=3, count=40, threads=2)]
    assert one == two
    plan = scenario.partial_rejection
    assert [site["objects"] for site in plan["sites"]] == [6]
    assert plan["sites"][0]["coordinates"] == 3 and plan["sites"][0]["intensity"] > 0
    result = run_prs(prs_binary, "sample", str(path), "-I", str(EXAMPLES), "--sampler",
                     "partial-rejection", "-s", "3", "-n", "40")
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == one


def test_a_partial_rejection_campaign_is_prs_sample_for_any_shard_size(prs_binary, tmp_path):
    path = tmp_path / "bin.prs"
    path.write_text(BIN)
    camp = tmp_path / "camp"
    campaign.init(camp, path, 30, seed=4, shard_size=7, search_path=[EXAMPLES],
                  sampler="partial-rejection")
    campaign.run(camp)
    campaign.merge(camp, tmp_path / "m.jsonl")
    result = run_prs(prs_binary, "sample", str(path), "-I", str(EXAMPLES), "--sampler",
                     "partial-rejection", "-s", "4", "-n", "30")
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "m.jsonl").read_text() == result.stdout


def test_a_program_outside_its_reach_is_refused_with_where(prs_binary, tmp_path):
    path = tmp_path / "free.prs"
    path.write_text(BIN + "x = Range(0, 1)\n")
    with pytest.raises(prs.ScenarioError) as error:
        next(prs.load(path, search_path=[EXAMPLES], sampler="partial-rejection").scenes())
    assert error.value.id == "partial-rejection-unsupported"
    assert error.value.line == 5
    result = run_prs(prs_binary, "sample", str(path), "-I", str(EXAMPLES), "--sampler",
                     "partial-rejection")
    assert result.returncode == 1
    assert "draws numbers outside its random objects (Range at" in result.stderr

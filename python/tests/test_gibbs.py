"""sampler="gibbs": the same scenes as `prs sample --sampler gibbs`, for any thread count and in
campaigns of any shard size, with the chain's schedule on the scenario; bad values refused."""

import pytest

import probrobscene as prs
import probrobscene.campaign as campaign
from conftest import EXAMPLES, run_prs

BIN = """from model import *
bin = Table on V3D(0, 0, 0), with width 0.5, with length 0.4
for i in range(10):
    Cube completely on bin, with yaw Range(0, 2 * math.pi)
"""


def test_gibbs_scenes_are_prs_samples_for_any_threads(prs_binary, tmp_path):
    path = tmp_path / "bin.prs"
    path.write_text(BIN)
    scenario = prs.load(path, search_path=[EXAMPLES], sampler="gibbs")
    assert scenario.sampler == "gibbs"
    assert scenario.gibbs is None  # no scene drawn yet
    one = [s.to_json() for s in scenario.scenes(seed=3, count=40, threads=1)]
    two = [s.to_json() for s in scenario.scenes(seed=3, count=40, threads=2)]
    assert one == two
    plan = scenario.gibbs
    assert plan["blocks"] == 10 and plan["thin_sweeps"] >= 1
    assert plan["autocorrelation_sweeps"] >= 1
    result = run_prs(prs_binary, "sample", str(path), "-I", str(EXAMPLES), "--sampler", "gibbs",
                     "-s", "3", "-n", "40")
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == one


def test_a_gibbs_campaign_is_prs_sample_for_any_shard_size(prs_binary, tmp_path):
    path = tmp_path / "bin.prs"
    path.write_text(BIN)
    camp = tmp_path / "camp"
    campaign.init(camp, path, 45, seed=4, shard_size=7, search_path=[EXAMPLES], sampler="gibbs")
    campaign.run(camp)
    campaign.merge(camp, tmp_path / "m.jsonl")
    result = run_prs(prs_binary, "sample", str(path), "-I", str(EXAMPLES), "--sampler", "gibbs",
                     "-s", "4", "-n", "45")
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "m.jsonl").read_text() == result.stdout


def test_bad_samplers_are_refused():
    with pytest.raises(ValueError,
                       match="sampler must be 'rejection', 'partial-rejection' or 'gibbs'"):
        prs.loads(BIN, search_path=[EXAMPLES], sampler="metropolis")

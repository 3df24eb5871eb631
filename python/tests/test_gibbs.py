"""sampler="gibbs": the same scenes as `prs sample --sampler gibbs`, for any thread count and in
campaigns of any shard size, with the chain's schedule on the scenario; bad values refused."""

import pytest

import probrobscene as prs
from conftest import (EXAMPLES, bin_program, expect_campaign_is_prs_sample,
                      expect_prs_sample_scenes)

BIN = bin_program(10)


def test_gibbs_scenes_are_prs_samples_for_any_threads(prs_binary, tmp_path):
    path = tmp_path / "bin.prs"
    path.write_text(BIN)
    scenario = prs.load(path, search_path=[EXAMPLES], sampler="gibbs")
    assert scenario.sampler == "gibbs"
    assert scenario.gibbs is None  # no scene drawn yet
    expect_prs_sample_scenes(prs_binary, scenario, path, seed=3, count=40)
    plan = scenario.gibbs
    assert plan["blocks"] == 10 and plan["thin_sweeps"] >= 1
    assert plan["autocorrelation_sweeps"] >= 1


def test_a_gibbs_campaign_is_prs_sample_for_any_shard_size(prs_binary, tmp_path):
    path = tmp_path / "bin.prs"
    path.write_text(BIN)
    expect_campaign_is_prs_sample(prs_binary, tmp_path, path, "gibbs", 45)


def test_bad_samplers_are_refused():
    with pytest.raises(ValueError,
                       match="sampler must be 'rejection', 'partial-rejection' or 'gibbs'"):
        prs.loads(BIN, search_path=[EXAMPLES], sampler="metropolis")

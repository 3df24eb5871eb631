"""sampler="partial-rejection": the same scenes as `prs sample --sampler partial-rejection`, for
any thread count and in campaigns of any shard size, with the sites and the pilot on the
scenario; programs outside its reach refused with the located message."""

import pytest

import probrobscene as prs
from conftest import (EXAMPLES, bin_program, expect_campaign_is_prs_sample,
                      expect_prs_sample_scenes, run_prs)

BIN = bin_program(6)


def test_partial_rejection_scenes_are_prs_samples_for_any_threads(prs_binary, tmp_path):
    path = tmp_path / "bin.prs"
    path.write_text(BIN)
    scenario = prs.load(path, search_path=[EXAMPLES], sampler="partial-rejection")
    assert scenario.sampler == "partial-rejection"
    assert scenario.partial_rejection is None  # no scene drawn yet
    expect_prs_sample_scenes(prs_binary, scenario, path, seed=3, count=40)
    plan = scenario.partial_rejection
    assert [site["objects"] for site in plan["sites"]] == [6]
    assert plan["sites"][0]["coordinates"] == 3 and plan["sites"][0]["intensity"] > 0


def test_a_partial_rejection_campaign_is_prs_sample_for_any_shard_size(prs_binary, tmp_path):
    path = tmp_path / "bin.prs"
    path.write_text(BIN)
    expect_campaign_is_prs_sample(prs_binary, tmp_path, path, "partial-rejection", 30)


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

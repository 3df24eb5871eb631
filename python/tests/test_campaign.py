"""probrobscene.campaign on a real Dask LocalCluster (two worker processes): a merged campaign is
one machine's run (test, sample, search, estimate and dataset campaigns), shards done before are not run again, the
CLI and Python share directories, and bad directories get clear errors."""

import json
import os
import warnings

import pytest

import probrobscene as prs
import probrobscene.campaign as campaign
from conftest import EXAMPLES, run_prs

distributed = pytest.importorskip("distributed", reason="python3-distributed is not installed")

TABLE_CUBE = str(EXAMPLES / "table_cube.prs")


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        with distributed.Client(cluster) as dask_client:
            yield dask_client


def records_without_times(path):
    records = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            record = json.loads(line)
            record.pop("wall_s")
            records.append(record)
    return records


def test_dask_test_campaign_equals_one_machines_run(client, prs_binary, tmp_path):
    camp = tmp_path / "camp"
    # Shard 2 is done before the cluster starts: run() must leave it alone.
    campaign.init(camp, TABLE_CUBE, 26, seed=3, shard_size=5, controller="table-cube")
    campaign.run_shard(camp, 2)
    done_before = os.stat(camp / "shards" / "shard-00002.jsonl").st_mtime_ns
    assert campaign.status(camp)["to_run"] == [0, 1, 3, 4, 5]

    status = campaign.run(camp, client)
    assert status["counts"]["done"] == 6 and status["to_run"] == []
    assert os.stat(camp / "shards" / "shard-00002.jsonl").st_mtime_ns == done_before
    assert campaign.merge(camp, tmp_path / "merged.jsonl") == {"lines": 26, "skipped": []}

    result = run_prs(prs_binary, "test", TABLE_CUBE, "--controller", "table-cube", "-n", "26",
                     "-s", "3", "-o", str(tmp_path / "single.jsonl"))
    assert result.returncode == 0, result.stderr
    assert records_without_times(tmp_path / "merged.jsonl") == \
        records_without_times(tmp_path / "single.jsonl")


def test_dask_scene_campaign_from_a_scenario_file_equals_prs_sample(client, prs_binary,
                                                                    tmp_path):
    camp = tmp_path / "scenes"
    status = campaign.run(TABLE_CUBE, client, dir=camp, n=300, shard_size=64, seed=9,
                          threads_per_shard=2)
    assert status["kind"] == "sample" and status["counts"]["done"] == 5
    campaign.merge(camp, tmp_path / "merged.jsonl")
    expected = run_prs(prs_binary, "sample", TABLE_CUBE, "-n", "300", "-s", "9")
    assert expected.returncode == 0, expected.stderr
    assert (tmp_path / "merged.jsonl").read_text() == expected.stdout
    # The command line reads the same directory.
    result = run_prs(prs_binary, "campaign", "status", str(camp))
    assert "5 of 5 done" in result.stdout, result.stdout


def test_dask_dataset_campaign_merges_into_prs_datasets_files(client, prs_binary, tmp_path):
    camp = tmp_path / "data"
    status = campaign.run(TABLE_CUBE, client, dir=camp, n=5, shard_size=2, seed=6,
                          dataset={"size": (96, 72)})
    assert status["kind"] == "dataset" and status["counts"]["done"] == 3
    with pytest.raises(ValueError, match="every shard is done"):
        campaign.merge(camp, tmp_path / "partial", partial=True)
    assert campaign.merge(camp, tmp_path / "merged")["dataset"] == str(tmp_path / "merged")
    result = run_prs(prs_binary, "dataset", TABLE_CUBE, "-n", "5", "-s", "6", "--size", "96x72",
                     "-o", str(tmp_path / "single"))
    assert result.returncode == 0, result.stderr
    tree = lambda root: {str(p.relative_to(root)): p.read_bytes()
                         for p in sorted(root.rglob("*")) if p.is_file()}
    single = tree(tmp_path / "single")
    assert len(single) > 5 * 14 and tree(tmp_path / "merged") == single
    with pytest.raises(ValueError, match="unknown options"):
        campaign.init(tmp_path / "bad", TABLE_CUBE, 4, dataset={"colour": "red"})


def test_dask_search_campaign_runs_generation_after_generation_as_prs_search(client, prs_binary,
                                                                            tmp_path):
    camp = tmp_path / "search"
    status = campaign.run(TABLE_CUBE, client, dir=camp, n=120, shard_size=15, seed=5,
                          controller="planted-1-percent", search="ce", batch=40)
    assert status["kind"] == "search"
    assert status["counts"]["done"] == 9 and status["to_run"] == []
    assert sorted(os.listdir(camp / "search")) == \
        ["generation-0000.json", "generation-0001.json", "generation-0002.json"]
    campaign.merge(camp, tmp_path / "merged.jsonl")
    result = run_prs(prs_binary, "search", TABLE_CUBE, "--controller", "planted-1-percent",
                     "--budget", "120", "--batch", "40", "-s", "5", "--strategy", "ce", "-q",
                     "-o", str(tmp_path / "single.jsonl"))
    assert result.returncode == 0, result.stderr
    merged = records_without_times(tmp_path / "merged.jsonl")
    assert merged == records_without_times(tmp_path / "single.jsonl")
    assert [r["search"]["generation"] for r in merged] == [0] * 40 + [1] * 40 + [2] * 40


def test_dask_estimate_campaign_merges_into_prs_estimates_records_and_estimate(client, prs_binary,
                                                                               tmp_path):
    camp = tmp_path / "estimate"
    status = campaign.run(TABLE_CUBE, client, dir=camp, n=600, shard_size=40, seed=3,
                          controller="planted-1-percent", estimate=True)
    assert status["kind"] == "estimate" and status["to_run"] == []
    merged = campaign.merge(camp, tmp_path / "merged.jsonl")
    assert merged["lines"] == 600
    result = run_prs(prs_binary, "estimate", TABLE_CUBE, "--controller", "planted-1-percent",
                     "--budget", "600", "-s", "3", "--json", "-q",
                     "-o", str(tmp_path / "single.jsonl"))
    assert result.returncode == 0, result.stderr
    assert records_without_times(tmp_path / "merged.jsonl") == \
        records_without_times(tmp_path / "single.jsonl")
    single = json.loads(result.stdout)["estimates"]["planted-failure"]
    from_campaign = merged["estimate"]["estimates"]["planted-failure"]
    assert from_campaign["p"] == single["p"]
    assert list(from_campaign["ci95"]) == single["ci95"]
    # The command line merges the same directory into the same estimate.
    result = run_prs(prs_binary, "campaign", "merge", str(camp), "-o", str(tmp_path / "cli.jsonl"))
    assert result.returncode == 0, result.stderr
    assert "planted-failure" in result.stdout
    assert (tmp_path / "cli.jsonl").read_text() == (tmp_path / "merged.jsonl").read_text()
    with pytest.raises(ValueError, match="only when all are done"):
        campaign.merge(camp, tmp_path / "partial.jsonl", partial=True)


def test_a_campaign_made_by_prs_runs_here_without_a_cluster(prs_binary, tmp_path):
    camp = tmp_path / "camp"
    result = run_prs(prs_binary, "campaign", "init", str(camp), TABLE_CUBE, "-n", "40",
                     "--shard-size", "16", "-s", "4", "--controller", "demo-reach")
    assert result.returncode == 0, result.stderr
    status = campaign.run(camp)
    assert status["counts"] == {"done": 3, "queued": 0, "running": 0, "failed": 0,
                                "missing": 0, "bad": 0, "waiting": 0}
    result = run_prs(prs_binary, "campaign", "merge", str(camp), "-o", str(tmp_path / "m.jsonl"))
    assert result.returncode == 0, result.stderr
    result = run_prs(prs_binary, "test", TABLE_CUBE, "--controller", "demo-reach", "-n", "40",
                     "-s", "4", "-o", str(tmp_path / "single.jsonl"))
    assert records_without_times(tmp_path / "m.jsonl") == \
        records_without_times(tmp_path / "single.jsonl")


def test_a_shards_warnings_come_as_python_warnings_once(prs_binary, tmp_path):
    """The original model's cube has no mass: an --exec shard over it warns, once, that its
    scenes have no free body; the same shard over table_cube.prs (a cube of 0.1 kg) does not."""
    for example, warned in (("table_cube_paper_model.prs", True), ("table_cube.prs", False)):
        camp = tmp_path / example
        result = run_prs(prs_binary, "campaign", "init", str(camp), str(EXAMPLES / example),
                         "-n", "3", "--shard-size", "3", "-s", "1", "--exec", "true")
        assert result.returncode == 0, result.stderr
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            campaign.run_shard(str(camp), 0)
        messages = [str(w.message) for w in caught if issubclass(w.category, UserWarning)]
        if warned:
            assert len(messages) == 1 and messages[0].startswith("a scene has no free body"), \
                messages
        else:
            assert messages == [], messages


@pytest.mark.parametrize("option, text, rejection", [
    ({"stable": 0.5}, "d = Cube at V3D((-0.8, -0.6), 0.3, (0.825, 0.84))\n", "unstable"),
    ({"settle": True}, "c = Cube at V3D((0.85, 0.95), 0, 1.2)\nrequire settled c.z > 0.5\n",
     "unsettled"),
])
def test_stable_and_settled_campaigns_are_prs_samples(prs_binary, tmp_path, option, text,
                                                       rejection):
    """stable= and settle= at init are kept in the spec and applied by every shard."""
    path = tmp_path / "scenario.prs"
    path.write_text("from model import *\nt = Table on V3D(0, 0, 0)\n" + text)
    camp = tmp_path / "camp"
    campaign.init(camp, path, 9, seed=4, shard_size=4, search_path=[EXAMPLES], **option)
    campaign.run(camp)
    campaign.merge(camp, tmp_path / "m.jsonl")
    flag = "--stable=0.5" if "stable" in option else "--settle"
    result = run_prs(prs_binary, "sample", str(path), "-I", str(EXAMPLES), "-n", "9", "-s", "4",
                     flag)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "m.jsonl").read_text() == result.stdout
    assert rejection in result.stdout


def test_bad_campaigns_and_arguments_are_clear_errors(tmp_path):
    with pytest.raises(ValueError, match="not a campaign directory: to make one"):
        campaign.run(tmp_path / "nothing.prs")
    with pytest.raises(ValueError, match="unknown search strategy 'bo'"):
        campaign.init(tmp_path / "c2", TABLE_CUBE, 10, controller="demo-reach", search="bo")
    with pytest.raises(ValueError, match="needs a controller"):
        campaign.init(tmp_path / "c3", TABLE_CUBE, 10, search="ce")
    with pytest.raises(ValueError, match="an estimate needs a controller"):
        campaign.init(tmp_path / "c5", TABLE_CUBE, 400, estimate=True)
    with pytest.raises(ValueError, match="budget n must be >= 200"):
        campaign.init(tmp_path / "c6", TABLE_CUBE, 100, controller="demo-reach", estimate=True)
    with pytest.raises(ValueError, match="unknown controller 'tabel-cube'"):
        campaign.init(tmp_path / "c0", TABLE_CUBE, 10, controller="tabel-cube")
    with pytest.raises(prs.ScenarioError):
        (tmp_path / "broken.prs").write_text("x = Cube on\n")
        campaign.init(tmp_path / "c1", tmp_path / "broken.prs", 10)
    # An error that shows only when the program runs (a search's trial attempts): located.
    (tmp_path / "runtime.prs").write_text("from model import *\nt = Table at (0, 0, 0.5)\n")
    with pytest.raises(prs.ScenarioError) as error:
        campaign.init(tmp_path / "c4", tmp_path / "runtime.prs", 10, controller="demo-reach",
                      search="ce", search_path=[EXAMPLES])
    assert (error.value.line, error.value.column) == (2, 14)
    assert not (tmp_path / "c4").exists()

    camp = tmp_path / "camp"
    campaign.init(camp, TABLE_CUBE, 10, shard_size=4)
    with pytest.raises(ValueError, match="campaign already"):
        campaign.run(camp, n=5)
    with pytest.raises(ValueError, match="there is no shard 3"):
        campaign.run_shard(camp, 3)
    with pytest.raises(ValueError, match="shards not done: 0, 1, 2"):
        campaign.merge(camp, tmp_path / "out.jsonl")
    assert not (tmp_path / "out.jsonl").exists()
    assert campaign.merge(camp, tmp_path / "out.jsonl", partial=True) == \
        {"lines": 0, "skipped": [0, 1, 2]}
    with pytest.raises(ValueError, match="not empty|in use|exists"):
        campaign.init(camp, TABLE_CUBE, 10)
    # An edited spec is refused by every shard.
    spec = camp / "spec" / "table_cube.prs"
    spec.write_text(spec.read_text() + "\n# edited\n")
    with pytest.raises(ValueError, match="changed"):
        campaign.run_shard(camp, 0)
    with pytest.raises(ValueError, match="campaign.json"):
        campaign.status(tmp_path)

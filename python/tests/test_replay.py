"""Saved scenes from Python: read_scenes gives back what `prs sample -o` wrote, and test runs a
controller on them (a function, a built-in, an --exec command, persistent or not) with the
records `prs test SCENES.jsonl` writes."""

import json
import os
import sys

import numpy as np
import pytest

import probrobscene as prs
from conftest import EXAMPLES, REPO, run_prs

SLOW_START = REPO / "examples" / "controllers" / "slow_start.py"


def _comparable(records):
    return [{k: v for k, v in r.items() if k not in ("wall_s", "saved_scene", "regenerate")}
            for r in records]


@pytest.fixture(scope="module")
def scenes_file(prs_binary, tmp_path_factory):
    path = tmp_path_factory.mktemp("replay") / "scenes.jsonl"
    r = run_prs(prs_binary, "sample", str(EXAMPLES / "table_cube.prs"), "-n", "12", "-s", "4",
                "-o", str(path))
    assert r.returncode == 0, r.stderr
    return path


def test_read_scenes_gives_back_the_sampled_scenes(scenes_file, table_cube):
    scenes = prs.read_scenes(scenes_file)
    assert [(s.seed, s.index) for s in scenes] == [(4, i) for i in range(12)]
    for scene in scenes[:3]:
        drawn = table_cube.sample(4, scene.index)
        assert [o.class_name for o in scene.objects] == [o.class_name for o in drawn.objects]
        np.testing.assert_array_equal(prs.positions([scene], "tr_1"), prs.positions([drawn], "tr_1"))
        assert scene["tr_1"].properties == drawn["tr_1"].properties
    line = json.loads(scenes_file.read_text().splitlines()[5])
    again = scenes[5].to_dict()
    for scene in (line, again):  # a rotation written again may differ in its last digit
        for o in scene["objects"]:
            o.pop("orientation")
    assert again == line


def test_read_scenes_locates_a_bad_line(tmp_path, scenes_file):
    bad = tmp_path / "bad.jsonl"
    bad.write_text(scenes_file.read_text().splitlines()[0] + "\n{\"format\": \"prs-scene/1\"}\n")
    with pytest.raises(ValueError, match=r"bad\.jsonl:2: the scene: no \"seed\""):
        prs.read_scenes(bad)
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(ValueError, match="holds no scene"):
        prs.read_scenes(empty)


def test_a_builtin_on_saved_scenes_gives_the_command_lines_records(scenes_file, prs_binary,
                                                                   tmp_path):
    out = tmp_path / "cli.jsonl"
    r = run_prs(prs_binary, "test", str(scenes_file), "--controller", "demo-reach", "-o", str(out))
    assert r.returncode == 0, r.stderr
    cli = [json.loads(line) for line in out.read_text().splitlines()]
    assert _comparable(prs.test(scenes_file, "demo-reach", threads=2)) == _comparable(cli)


def test_a_function_an_exec_command_and_a_persistent_worker_agree(scenes_file, monkeypatch):
    monkeypatch.setenv("PRS_EXAMPLE_STARTUP_S", "0")
    scenes = prs.read_scenes(scenes_file)
    command = f"{sys.executable} {SLOW_START}"
    one_per_episode = prs.test(scenes, exec=command, threads=2)
    persistent = prs.test(scenes, exec=command, persistent=True, threads=2)
    assert _comparable(persistent) == _comparable(one_per_episode)
    outcomes = {r["outcome"] for r in persistent}
    assert outcomes <= {"success", "out-of-reach"} and "success" in outcomes

    seen = []

    def controller(scene):
        seen.append((scene.seed, scene.index))
        if scene.index == 3:
            raise RuntimeError("the gripper is not connected")
        return {"outcome": "success" if scene.index % 2 == 0 else "no-path", "k": scene.index}

    records = prs.test(scenes, controller)
    assert seen == [(4, i) for i in range(12)]
    assert [r["outcome"] for r in records[:4]] == ["success", "no-path", "success",
                                                   "controller-error"]
    assert "the gripper is not connected" in records[3]["detail"]
    assert records[2]["extra"] == {"k": 2}


def test_bad_requests_say_what_to_give(scenes_file):
    scenes = prs.read_scenes(scenes_file)
    with pytest.raises(ValueError, match="persistent=True needs exec"):
        prs.test(scenes, "demo-reach", persistent=True)
    with pytest.raises(ValueError, match="one controller"):
        prs.test(scenes, "demo-reach", exec="true")
    with pytest.raises(ValueError, match="unknown controller 'demo-rech'"):
        prs.test(scenes, "demo-rech")
    with pytest.raises(RuntimeError, match="before its handshake"):
        prs.test(scenes, exec="exit 3", persistent=True)

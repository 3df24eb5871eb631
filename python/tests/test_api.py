"""The Python API over one scenario: objects, numpy arrays, dicts, batch helpers, check()."""

import json
import math

import numpy as np
import pytest

import probrobscene as prs
from conftest import EXAMPLES, run_prs


def test_objects_carry_names_classes_and_poses(table_cube):
    scene = table_cube.sample(seed=1, index=2)
    assert (scene.seed, scene.index) == (1, 2)
    assert scene.attempts >= 1
    classes = [o.class_name for o in scene.objects]
    assert classes == ["Table", "Robot", "Robot", "Tray", "Tray", "Cube", "Camera"]
    assert [o.name for o in scene.objects][:5] == ["t", "r1", "r2", "tr_1", "tr_2"]
    cube = scene.objects[5]
    assert cube.name is None and cube.display_name == "Cube#5"
    assert scene["Cube#5"].position.tolist() == cube.position.tolist()
    assert "tr_1" in scene and "nope" not in scene and len(scene) == 7
    assert isinstance(cube.position, np.ndarray) and cube.position.shape == (3,)
    assert cube.dimensions.shape == (3,) and cube.quaternion.shape == (4,)
    assert math.isclose(np.linalg.norm(cube.quaternion), 1.0, abs_tol=1e-12)
    assert cube.yaw_pitch_roll.tolist() == [cube.yaw, cube.pitch, cube.roll]
    assert isinstance(cube.properties, dict)
    assert "position" not in cube.properties


def test_python_values_agree_with_the_json_line(table_cube):
    scene = table_cube.sample(seed=5, index=0)
    data = scene.to_dict()
    assert data == json.loads(scene.to_json())
    assert data["format"] == "prs-scene/1"
    for obj, expected in zip(scene.objects, data["objects"]):
        assert obj.name == expected["name"]
        assert obj.class_name == expected["class"]
        assert obj.position.tolist() == expected["position"]
        assert obj.dimensions.tolist() == expected["dimensions"]
        assert obj.quaternion.tolist() == expected["orientation"]["quaternion"]
        assert obj.yaw_pitch_roll.tolist() == expected["orientation"]["yaw_pitch_roll"]
        assert set(obj.properties) == set(expected["properties"])
    assert scene.rejections == data["rejections"]


def test_property_values_convert_to_python_types():
    scenario = prs.loads(
        "from model import *\n"
        "param mode = 'fast'\n"
        "t = Table on V3D(0, 0, 0), with color 'red', with tag (1, 'a'), with flag True,\n"
        "    with target V3D(1, 2, 3), with nothing None, with items [1, 2]\n",
        search_path=[EXAMPLES])
    scene = scenario.sample()
    props = scene["t"].properties
    assert props["color"] == "red"
    assert props["tag"] == (1.0, "a")
    assert props["flag"] is True and props["nothing"] is None
    assert props["items"] == [1.0, 2.0]
    assert isinstance(props["target"], np.ndarray) and props["target"].tolist() == [1, 2, 3]
    assert scene.params == {"mode": "fast"}


def test_a_mesh_shape_reads_as_in_the_json_line():
    scenario = prs.load(EXAMPLES / "kitchen_meshes.prs")
    scene = scenario.sample(seed=2, index=0)
    shape = scene["mug"].properties["shape"]
    assert shape == {"mesh": "assets/mug.obj", "path": shape["path"], "scale": 1.0}
    assert shape["path"].endswith("examples/assets/mug.obj")
    assert shape == json.loads(scene.to_json())["objects"][3]["properties"]["shape"]
    assert scene["mug"].dimensions.tolist() == pytest.approx([0.11, 0.08, 0.1], abs=1e-12)


def test_a_built_in_shape_reads_as_in_the_json_line():
    scenario = prs.load(EXAMPLES / "pantry_shapes.prs")
    scene = scenario.sample(seed=2, index=0)
    assert scene["ball"].properties["shape"] == {"primitive": "sphere"}
    assert scene["bottle"].properties["shape"] == {"primitive": "capsule"}
    assert scene["tin"].properties["shape"] == {"primitive": "cylinder"}
    objects = {o["name"]: o for o in json.loads(scene.to_json())["objects"]}
    assert objects["tin"]["properties"]["shape"] == {"primitive": "cylinder"}


def test_batch_helpers_stack_one_object_over_scenes(table_cube):
    scenes = table_cube.sample_batch(50, seed=2)
    xyz = prs.positions(scenes, "Cube#5")
    assert xyz.shape == (50, 3) and xyz.dtype == np.float64
    assert xyz.tolist() == [s["Cube#5"].position.tolist() for s in scenes]
    assert prs.dimensions(scenes, "tr_1").shape == (50, 3)
    assert prs.quaternions(iter(scenes), "Camera#6").shape == (50, 4)
    ypr = prs.yaw_pitch_roll(scenes, "r1")
    assert ypr.tolist() == [s["r1"].yaw_pitch_roll.tolist() for s in scenes]
    assert prs.positions([], "c1").shape == (0, 3)
    assert np.ptp(xyz[:, 0]) > 0, "the cube's position is random"
    with pytest.raises(KeyError, match="no object named 'c9'.*Cube#5"):
        prs.positions(scenes, "c9")
    with pytest.raises(TypeError, match="expected Scene objects, got int at position 1"):
        prs.positions([scenes[0], 3], "t")


def test_check_summarises_sites_classes_and_randomness(prs_binary, table_cube):
    summary = table_cube.check(n=10, seed=0)
    assert summary["file"].endswith("table_cube.prs")
    assert summary["modules"] == 2 and summary["scenes_observed"] == 10
    sites = {site["name"] or site["class"]: site for site in summary["sites"]}
    assert sites["t"]["position_region"] == "point" and sites["t"]["varied"] == []
    assert sites["tr_1"]["position_specifiers"] == ["completely on", "ahead of", "left of"]
    assert "position" in sites["Cube"]["varied"]
    assert sites["Cube"]["line"] == 17 and sites["Cube"]["min_objects"] == 1
    classes = {c["name"]: c for c in summary["classes"]}
    assert {"Table", "Robot", "Tray", "Cube", "Camera"} <= set(classes)
    assert classes["Cube"]["parent"] == "Object" and classes["Cube"]["file"].endswith("model.prs")
    # The same outline as `prs check` prints, row for row.
    text = run_prs(prs_binary, "check", str(EXAMPLES / "table_cube.prs"), "-n", "10").stdout
    for site in summary["sites"]:
        assert f"table_cube.prs:{site['line']}" in text
        assert site["position_region"] in text
    assert table_cube.check(n=0)["sites"][0]["varied"] == []


def test_bad_arguments_raise_python_errors(table_cube):
    with pytest.raises(ValueError, match="n must be >= 0"):
        table_cube.sample_batch(-1)
    with pytest.raises(ValueError, match="threads must be from 1 to 1024, got 0"):
        table_cube.sample_batch(2, threads=0)
    with pytest.raises(ValueError, match="threads must be from 1 to 1024, got 5000"):
        table_cube.check(threads=5000)
    with pytest.raises(ValueError, match=r"seed must be from 0 to 2\*\*64 - 1, got -1"):
        table_cube.sample(seed=-1)
    with pytest.raises(ValueError, match=r"seed must be from 0 to 2\*\*64 - 1, got -1"):
        table_cube.sample_batch(5, seed=-1)
    with pytest.raises(ValueError, match=r"start must be from 0 to 2\*\*64 - 1, got 18446744073709551616"):
        table_cube.sample_batch(1, start=2**64)
    with pytest.raises(TypeError, match="index must be an int, got str"):
        table_cube.sample(index="3")
    assert table_cube.sample(seed=2**64 - 1).seed == 2**64 - 1
    with pytest.raises(TypeError, match="param 'size': expected a number or a string"):
        prs.load(EXAMPLES / "table_cube.prs", params={"size": True})
    with pytest.raises(ValueError, match="max_attempts must be >= 1"):
        prs.load(EXAMPLES / "table_cube.prs", max_attempts=0)

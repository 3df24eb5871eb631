"""probrobscene.dataset writes the files `prs dataset` writes, and refuses what it refuses."""

import json

import pytest

import probrobscene as prs
from conftest import EXAMPLES, run_prs


def read_tree(root):
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


def test_sampled_scenes_give_the_command_lines_files(prs_binary, table_cube, tmp_path):
    result = run_prs(prs_binary, "dataset", str(EXAMPLES / "table_cube.prs"), "-s", "3",
                     "--start", "4", "-n", "3", "--size", "160x120", "-o", str(tmp_path / "cli"))
    assert result.returncode == 0, result.stderr
    scenes = table_cube.sample_batch(3, seed=3, start=4)
    summary = prs.dataset(scenes, tmp_path / "py", size=(160, 120), threads=2)
    assert summary["images"] == 3 and summary["scenes"] == 3
    assert summary["cameras"] == ["Camera#6"]
    assert set(summary["seconds"]) == {"render", "labels", "pictures", "json"}
    cli, py = read_tree(tmp_path / "cli"), read_tree(tmp_path / "py")
    assert len(cli) > 3 * 14
    assert cli == py
    gt = json.loads((tmp_path / "py/train_pbr/000000/scene_gt.json").read_text())
    assert sorted(gt) == ["4", "5", "6"]  # image ids are the scenes' indices


def test_a_scenes_file_numbered_as_its_program_and_coco_alone(prs_binary, table_cube, tmp_path):
    scenes = tmp_path / "s.jsonl"
    assert run_prs(prs_binary, "sample", str(EXAMPLES / "table_cube.prs"), "-n", "2", "-o",
                   str(scenes)).returncode == 0
    # Alone, a file knows only the classes it uses, in order: Table, Robot, Tray, Cube, Camera.
    prs.dataset(scenes, tmp_path / "own", size=(64, 48), format="coco", labels=["Cube"])
    coco = json.loads((tmp_path / "own/train_pbr/000000/annotations.json").read_text())
    assert [a["category_id"] for a in coco["annotations"]] == [4, 4]
    # With the program's classes, the ids of the program's own dataset (Object first).
    prs.dataset(scenes, tmp_path / "ds", size=(64, 48), format="coco", labels=["Cube"],
                classes=table_cube)
    chunk = tmp_path / "ds/train_pbr/000000"
    coco = json.loads((chunk / "annotations.json").read_text())
    assert [a["category_id"] for a in coco["annotations"]] == [5, 5]  # the cube, in each image
    assert [c["name"] for c in coco["categories"]] == ["Cube"]
    assert not (chunk / "mask").exists() and not (tmp_path / "ds/models").exists()


def test_bad_input(table_cube, tmp_path):
    scenes = table_cube.sample_batch(2, seed=0)
    with pytest.raises(ValueError, match="no object named 'nope'"):
        prs.dataset(scenes, tmp_path / "a", cameras=["nope"], size=(32, 32))
    assert (tmp_path / "a.partial").is_dir() and not (tmp_path / "a").exists()
    with pytest.raises(ValueError, match="format"):
        prs.dataset(scenes, tmp_path / "b", format="voc")
    with pytest.raises(ValueError, match="16 to 8192"):
        prs.dataset(scenes, tmp_path / "b", size=(0, 0))
    with pytest.raises(ValueError, match="same images"):
        prs.dataset([scenes[0], scenes[0]], tmp_path / "b")
    (tmp_path / "c").mkdir()
    (tmp_path / "c" / "keep").write_text("mine")
    with pytest.raises(RuntimeError, match="not an empty directory"):
        prs.dataset(scenes, tmp_path / "c")
    assert (tmp_path / "c" / "keep").read_text() == "mine"


def test_several_views_of_one_settled_pile(prs_binary, tmp_path):
    """examples/bin_pile.prs with -p views=3: one settled pile seen by three cameras. Every view
    labels each object at the pose `prs sample --settle` gives the same scene (the world pose
    recovered here from cam_R_w2c/cam_t_w2c and cam_R_m2c/cam_t_m2c), and the cameras differ."""
    import numpy as np
    common = [str(EXAMPLES / "bin_pile.prs"), "--settle", "-p", "views=3", "-s", "1", "-n", "1"]
    result = run_prs(prs_binary, "dataset", *common, "--size", "64x48", "-o", str(tmp_path / "d"))
    assert result.returncode == 0, result.stderr
    sampled = run_prs(prs_binary, "sample", *common)
    assert sampled.returncode == 0, sampled.stderr
    scene = json.loads(sampled.stdout)
    assert scene["settled_s"] > 0.5
    chunk = tmp_path / "d/train_pbr/000000"
    cameras = json.loads((chunk / "scene_camera.json").read_text())
    gt = json.loads((chunk / "scene_gt.json").read_text())
    assert sorted(cameras) == ["0", "1", "2"]  # scene 0 makes images 0, 1 and 2
    assert len({tuple(c["cam_t_w2c"]) for c in cameras.values()}) == 3
    # The objects with a mass, in scene order: the labels' objects (every class is labelled).
    piled = [o for o in scene["objects"] if o["properties"].get("mass", 0) > 0]
    assert len(piled) == 25
    for im_id, camera in cameras.items():
        R_CW = np.array(camera["cam_R_w2c"]).reshape(3, 3)
        p_CW_mm = np.array(camera["cam_t_w2c"])
        p_WO_of_label = []
        for label in gt[im_id]:
            R_CO = np.array(label["cam_R_m2c"]).reshape(3, 3)
            p_CO_mm = np.array(label["cam_t_m2c"])
            p_WO_of_label.append((R_CW.T @ (p_CO_mm - p_CW_mm) / 1000, R_CW.T @ R_CO))
        for o in piled:
            w, x, y, z = o["orientation"]["quaternion"]
            R_WO = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                             [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                             [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
            p_WO = np.array(o["position"])
            assert any(np.abs(p - p_WO).max() < 1e-6 and np.abs(R - R_WO).max() < 1e-6
                       for p, R in p_WO_of_label), (im_id, o["class"], p_WO)

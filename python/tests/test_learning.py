"""The learning loop's pieces (examples/learning, docs/learning.md): a perception request's
camera fields and pictures agree with a `prs dataset` of the same scenes (pinhole math written
here), serve_perception's answers, the trainer's messages, and a reduced loop that runs from one
command and gives the same files twice. Whether targeted data beats random data is not asserted
(docs/learning.md measures it)."""

import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from conftest import EXAMPLES, REPO, run_prs

LEARNING = EXAMPLES / "learning"
SCENARIO = EXAMPLES / "table_cube_decoy.prs"

# Saves every request with copies of its pictures, and says it saw no cube.
DUMP_WORKER = r"""
import json, shutil, sys
out = sys.argv[1]
print(json.dumps({"ready": True}), flush=True)
for line in sys.stdin:
    r = json.loads(line)
    key = "%d_%d" % (r["index"], r["sighting"])
    shutil.copy(r["rgb"], "%s/%s_rgb.png" % (out, key))
    shutil.copy(r["depth"], "%s/%s_depth.png" % (out, key))
    json.dump(r, open("%s/%s.json" % (out, key), "w"))
    print(json.dumps({"found": False, "seed": r["seed"], "index": r["index"],
                      "sighting": r["sighting"]}), flush=True)
"""


def project(K, R, t_mm, p_W_m):
    """Pixel (u, v) and camera-frame depth (m) of a world point, OpenCV convention."""
    p_C = np.asarray(R).reshape(3, 3) @ np.asarray(p_W_m) + np.asarray(t_mm) / 1000.0
    uvw = np.asarray(K).reshape(3, 3) @ p_C
    return uvw[:2] / uvw[2], p_C[2]


def test_a_perception_request_agrees_with_the_datasets_labels(prs_binary, tmp_path):
    (tmp_path / "requests").mkdir()
    worker = tmp_path / "dump.py"
    worker.write_text(DUMP_WORKER)
    command = f"/usr/bin/python3 {worker} {tmp_path / 'requests'}"
    r = run_prs(prs_binary, "test", str(SCENARIO), "--controller", "table-cube", "--perception",
                command, "-n", "3", "-s", "5", "--threads", "1", "-o", str(tmp_path / "r.jsonl"))
    assert r.returncode == 0, r.stderr
    r = run_prs(prs_binary, "dataset", str(SCENARIO), "-n", "3", "-s", "5", "--label", "Cube",
                "-o", str(tmp_path / "ds"))
    assert r.returncode == 0, r.stderr
    r = run_prs(prs_binary, "sample", str(SCENARIO), "-n", "3", "-s", "5",
                "-o", str(tmp_path / "scenes.jsonl"))
    assert r.returncode == 0, r.stderr
    chunk = tmp_path / "ds" / "train_pbr" / "000000"
    gt = json.loads((chunk / "scene_gt.json").read_text())
    cameras = json.loads((chunk / "scene_camera.json").read_text())
    scenes = [json.loads(line) for line in (tmp_path / "scenes.jsonl").read_text().splitlines()]
    for i, scene in enumerate(scenes):
        request = json.loads((tmp_path / "requests" / f"{i}_0.json").read_text())
        assert (request["seed"], request["index"], request["sighting"]) == (5, i, 0)
        assert (request["width"], request["height"]) == (640, 480)
        camera = cameras[str(i)]
        np.testing.assert_allclose(request["cam_K"], camera["cam_K"], atol=1e-9)
        np.testing.assert_allclose(request["cam_R_w2c"], camera["cam_R_w2c"], atol=1e-6)
        np.testing.assert_allclose(request["cam_t_w2c"], camera["cam_t_w2c"], atol=1e-3)
        cube = next(o for o in scene["objects"] if o["class"] == "Cube")
        # The cube's centre by the request's camera, and by the dataset's label.
        uv, _ = project(request["cam_K"], request["cam_R_w2c"], request["cam_t_w2c"],
                        cube["position"])
        label = gt[str(i)][0]["cam_t_m2c"]
        uv_label = (np.asarray(camera["cam_K"]).reshape(3, 3) @ label)
        np.testing.assert_allclose(uv, uv_label[:2] / uv_label[2], atol=0.5)
        # The depth picture at the centre of the cube's top face, in depth_scale units.
        top = np.asarray(cube["position"]) + [0, 0, cube["dimensions"][2] / 2]
        (u, v), z_top = project(request["cam_K"], request["cam_R_w2c"], request["cam_t_w2c"], top)
        depth_png = tmp_path / "requests" / f"{i}_0_depth.png"
        header = depth_png.read_bytes()[:26]  # IHDR: bit depth 16, colour type 0 (grey)
        assert header[1:4] == b"PNG" and header[24] == 16 and header[25] == 0
        depth = np.asarray(Image.open(depth_png))
        assert depth.shape == (480, 640)
        seen_m = depth[int(round(v)), int(round(u))] * request["depth_scale"] / 1000.0
        assert abs(seen_m - z_top) < 0.002, (i, seen_m, z_top)
        # ... and its colour there is the cube's blue, not the tray's.
        red, green, blue = np.asarray(Image.open(tmp_path / "requests" / f"{i}_0_rgb.png"))[
            int(round(v)), int(round(u))].astype(int)
        assert blue > 2 * red and blue > 2 * green, (i, red, green, blue)


def serve(perceive_source: str, requests):
    """Runs serve_perception(perceive) on the request lines; its stdout lines as JSON."""
    program = ("import sys; sys.path.insert(0, %r)\n" % str(REPO / "python") +
               "from probrobscene.perception import serve_perception\n" + perceive_source +
               "\nserve_perception(perceive)\n")
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                          input="".join(json.dumps(r) + "\n" for r in requests), timeout=60)
    assert done.returncode == 0, done.stderr
    return [json.loads(line) for line in done.stdout.splitlines()], done.stderr


def test_serve_perception_answers_each_kind_of_return():
    source = """
def perceive(request):
    i = request["index"]
    if i == 0: return [0.1, -0.2, 0.9]
    if i == 1: return None
    if i == 2: return {"found": False, "detail": "too dark"}
    if i == 3: raise ValueError("bad weights")
    if i == 4: return [1.0, float("nan"), 2.0]
    if i == 5: return "somewhere"
    return {"p_WCube_m": (1, 2, 3), "confidence": 0.5}
"""
    requests = [{"seed": 9, "index": i, "sighting": i % 2, "rgb": "", "depth": ""}
                for i in range(7)]
    answers, stderr = serve(source, requests)
    assert answers[0] == {"ready": True}
    answers = answers[1:]
    for i, answer in enumerate(answers):
        assert (answer["seed"], answer["index"], answer["sighting"]) == (9, i, i % 2)
    assert answers[0]["p_WCube_m"] == [0.1, -0.2, 0.9]
    assert answers[1]["found"] is False
    assert answers[2]["found"] is False and answers[2]["detail"] == "too dark"
    assert answers[3]["error"] == "ValueError: bad weights" and "Traceback" in stderr
    assert "not three finite numbers" in answers[4]["error"]
    assert "not three numbers" in answers[5]["error"]
    assert answers[6]["p_WCube_m"] == [1.0, 2.0, 3.0] and answers[6]["confidence"] == 0.5


def test_the_trainer_says_what_a_folder_lacks(prs_binary, tmp_path):
    train = [sys.executable, str(LEARNING / "train.py")]
    done = subprocess.run(train + [str(tmp_path), "-o", str(tmp_path / "m.pt")],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode != 0 and "no train_pbr/ folder" in done.stderr, done.stderr
    r = run_prs(prs_binary, "dataset", str(SCENARIO), "-n", "2", "-s", "1", "--format", "coco",
                "-o", str(tmp_path / "coco"))
    assert r.returncode == 0, r.stderr
    done = subprocess.run(train + [str(tmp_path / "coco"), "-o", str(tmp_path / "m.pt")],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode != 0 and "no scene_gt.json" in done.stderr, done.stderr
    assert not (tmp_path / "m.pt").exists()
    done = subprocess.run([sys.executable, str(LEARNING / "perceive.py"), str(tmp_path / "m.pt")],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode != 0 and "no model file" in done.stderr, done.stderr


def without_times(path: pathlib.Path):
    records = [json.loads(line) for line in path.read_text().splitlines()]
    for record in records:
        record.pop("wall_s")
    return records


def test_the_reduced_loop_runs_from_one_command_and_repeats_itself(prs_binary, tmp_path):
    import torch
    runs = []
    for name in ("a", "b"):
        out = tmp_path / name
        done = subprocess.run([sys.executable, str(LEARNING / "loop.py"), "-o", str(out),
                               "--tiny", "--prs", str(prs_binary)],
                              capture_output=True, text=True, timeout=600)
        assert done.returncode == 0, done.stderr[-3000:]
        runs.append(out)
    a, b = runs
    results = json.loads((a / "results.json").read_text())
    assert results == json.loads((b / "results.json").read_text())
    (seed,) = results["seeds"]
    for arm in ("round 0", "targeted", "i.i.d."):
        assert seed["arms"][arm]["episodes"] == results["test_episodes"] == 12
    assert (a / "results.md").read_text().startswith("| seed | round 0 |")
    for records in ("test_round0_seed0", "search_seed0", "test_targeted_seed0", "test_iid_seed0"):
        assert without_times(a / f"{records}.jsonl") == without_times(b / f"{records}.jsonl")
    # The targeted scenes are like the search's failures, and the datasets hold what was asked.
    assert len((a / "targeted_seed0.jsonl").read_text().splitlines()) == 24
    for model in ("round0_seed0.pt", "targeted_seed0.pt", "iid_seed0.pt"):
        first, second = torch.load(a / model)["state"], torch.load(b / model)["state"]
        assert all(torch.equal(first[k], second[k]) for k in first), model

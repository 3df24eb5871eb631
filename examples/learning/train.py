"""Trains cube_net.CubeNet on `prs dataset` BOP folders: where the cube's centre projects in each
picture, from scene_gt.json (cam_t_m2c, mm, OpenCV camera frame) and scene_camera.json (cam_K).

    /usr/bin/python3 examples/learning/train.py DATASET [DATASET ...] -o model.pt [--epochs 40]
        [--seed 0] [--lr 1e-3] [--class Cube] [--no-recolour]

Every image of every chunk (train_pbr/NNNNNN) of every DATASET is used; the class's obj_id comes
from the chunk's COCO categories (its name) or, without COCO, from --obj-id. Deterministic for a
seed: the same folders give the same model, byte for byte, on one machine.
"""

import argparse
import json
import os
import sys
import time

import numpy as np
import torch
from PIL import Image

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cube_net  # noqa: E402


class DatasetError(Exception):
    """A folder that is not a dataset this trainer can read: says which file and why."""


def find_obj_id(chunk: str, class_name: str) -> int:
    coco = os.path.join(chunk, "annotations.json")
    if not os.path.exists(coco):
        raise DatasetError(f"{chunk}: no annotations.json to find the class '{class_name}' in "
                           f"(write the dataset with --format both, or give --obj-id)")
    with open(coco) as f:
        categories = json.load(f)["categories"]
    for category in categories:
        if category["name"] == class_name:
            return int(category["id"])
    raise DatasetError(f"{coco}: no category '{class_name}' (it has "
                       f"{', '.join(c['name'] for c in categories)})")


def read_chunk(chunk: str, class_name: str, obj_id: int = 0):
    """(inputs, targets): each image's network input and the class's centre pixel (u, v)."""
    for name in ("scene_gt.json", "scene_camera.json"):
        if not os.path.exists(os.path.join(chunk, name)):
            raise DatasetError(f"{chunk}: no {name}; train.py reads a BOP dataset written by "
                               f"`prs dataset` (--format bop or both)")
    obj_id = obj_id or find_obj_id(chunk, class_name)
    with open(os.path.join(chunk, "scene_gt.json")) as f:
        gt = json.load(f)
    with open(os.path.join(chunk, "scene_camera.json")) as f:
        cameras = json.load(f)
    inputs, targets, masks = [], [], []
    for key in sorted(gt, key=int):
        objects = [k for k, o in enumerate(gt[key]) if o["obj_id"] == obj_id]
        if len(objects) != 1:
            raise DatasetError(f"{chunk}/scene_gt.json: image {key} has {len(objects)} objects "
                               f"of obj_id {obj_id} ('{class_name}'); the cube finder needs one")
        t_mm = np.asarray(gt[key][objects[0]]["cam_t_m2c"], dtype=np.float64)
        mask_path = os.path.join(chunk, "mask_visib", f"{int(key):06d}_{objects[0]:06d}.png")
        if not os.path.exists(mask_path):
            raise DatasetError(f"{mask_path}: missing; train.py recolours the cube by its exact "
                               f"visible mask (write the dataset with its masks)")
        with Image.open(mask_path) as picture:
            masks.append(cube_net.to_coverage(np.asarray(picture) > 0))
        K = np.asarray(cameras[key]["cam_K"], dtype=np.float64).reshape(3, 3)
        uvw = K @ t_mm
        path = os.path.join(chunk, "rgb", f"{int(key):06d}.png")
        if not os.path.exists(path):
            path = path[:-4] + ".jpg"
        with Image.open(path) as picture:
            rgb = np.asarray(picture.convert("RGB"))
        inputs.append(cube_net.to_input(rgb))
        targets.append(uvw[:2] / uvw[2])
    return inputs, targets, masks


def read_datasets(folders, class_name: str, obj_id: int = 0):
    inputs, targets, masks = [], [], []
    for folder in folders:
        split = os.path.join(folder, "train_pbr")
        if not os.path.isdir(split):
            raise DatasetError(f"{folder}: no train_pbr/ folder; give a folder `prs dataset -o` "
                               f"wrote")
        for chunk in sorted(os.listdir(split)):
            more = read_chunk(os.path.join(split, chunk), class_name, obj_id)
            inputs += more[0]
            targets += more[1]
            masks += more[2]
    if not inputs:
        raise DatasetError(f"no images in {', '.join(folders)}")
    return (torch.from_numpy(np.stack(inputs)),
            torch.from_numpy(np.stack(targets).astype(np.float32)),
            torch.from_numpy(np.stack(masks)))


def recolour(x: torch.Tensor, masks: torch.Tensor, generator: torch.Generator) -> torch.Tensor:
    """Colour augmentation by the cube's exact mask: its chromaticity scaled by a factor drawn
    in [0.3, 1], the rest of the picture's in [0.8, 1.2]. The simulator's camera sees the cube
    paler than the dataset renderer draws it where its light's highlight falls (docs/learning.md),
    so a model must find it by its shape as well as its colour."""
    n = len(x)
    cube = 0.3 + 0.7 * torch.rand(n, 1, 1, generator=generator)
    rest = 0.8 + 0.4 * torch.rand(n, 1, 1, generator=generator)
    return x * (rest + (cube - rest) * masks)[:, None]


def train(x: torch.Tensor, y: torch.Tensor, masks: torch.Tensor, epochs: int, seed: int,
          width: int = 16, batch: int = 16, log=None, recolour_cube: bool = True,
          lr: float = 1e-3
          ) -> cube_net.CubeNet:
    torch.manual_seed(seed)
    torch.use_deterministic_algorithms(True)
    model = cube_net.CubeNet(width)
    optimiser = torch.optim.Adam(model.parameters(), lr=lr)
    order = torch.Generator().manual_seed(seed)
    for epoch in range(epochs):
        permutation = torch.randperm(len(x), generator=order)
        total = 0.0
        for start in range(0, len(x), batch):
            pick = permutation[start:start + batch]
            # Huber on the pixel error: a few far-off answers early on do not dominate
            inputs = recolour(x[pick], masks[pick], order) if recolour_cube else x[pick]
            loss = torch.nn.functional.smooth_l1_loss(model(inputs), y[pick], beta=4.0)
            optimiser.zero_grad()
            loss.backward()
            optimiser.step()
            total += float(loss) * len(pick)
        if log:
            log(f"epoch {epoch + 1}/{epochs}: loss {total / len(x):.2f}")
    model.eval()
    return model


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("datasets", nargs="+", help="prs dataset folders (BOP)")
    parser.add_argument("-o", "--output", required=True, help="the model file to write")
    parser.add_argument("--epochs", type=int, default=40)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--width", type=int, default=16, help="channels per layer")
    parser.add_argument("--class", dest="class_name", default="Cube")
    parser.add_argument("--obj-id", type=int, default=0)
    parser.add_argument("--lr", type=float, default=1e-3,
                        help="Adam's learning rate (3e-3 left one of docs/learning.md's nine "
                             "trainings stuck at 8 px)")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--no-recolour", action="store_true",
                        help="train on the pictures as drawn, without recolouring the cube")
    args = parser.parse_args()
    torch.set_num_threads(args.threads)
    try:
        x, y, masks = read_datasets(args.datasets, args.class_name, args.obj_id)
    except (DatasetError, OSError, ValueError, KeyError) as error:
        sys.exit(f"train.py: error: {error}")
    start = time.time()
    model = train(x, y, masks, args.epochs, args.seed, args.width,
                  log=lambda line: print(line, file=sys.stderr, flush=True),
                  recolour_cube=not args.no_recolour, lr=args.lr)
    with torch.no_grad():
        error = (model(x) - y).norm(dim=1)
    print(f"train.py: {len(x)} images, {args.epochs} epochs in {time.time() - start:.1f} s; "
          f"training error median {float(error.median()):.2f} px, 95th percentile "
          f"{float(error.quantile(0.95)):.2f} px", file=sys.stderr)
    tmp = args.output + ".partial"
    cube_net.save(model, tmp, {"datasets": args.datasets, "images": len(x), "seed": args.seed,
                               "epochs": args.epochs, "lr": args.lr,
                               "recolour": not args.no_recolour})
    os.replace(tmp, args.output)


if __name__ == "__main__":
    main()

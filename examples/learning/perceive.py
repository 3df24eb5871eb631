"""The learned perception as a `prs test --perception` worker: cube_net finds the cube's pixel,
the depth picture there and the camera's pose place it in the world.

    prs test examples/table_cube_decoy.prs --controller table-cube-clear-view \\
        --perception '/usr/bin/python3 examples/learning/perceive.py model.pt' -n 100 -s 1
"""

import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))

CUBE_HALF_HEIGHT_M = 0.025  # the task's nominal cube (the controller knows it too)


def locate(model, sighting) -> np.ndarray:
    """The cube centre in the world (metres) from the model's pixel, the depth of the cube's top
    around it and the camera's pose (OpenCV frame: x right, y down, z forward)."""
    import torch
    import cube_net
    with torch.no_grad():
        u, v = model(torch.from_numpy(cube_net.to_input(sighting["rgb"]))[None])[0].tolist()
    depth = sighting["depth_m"]
    row, col = int(round(v)), int(round(u))
    if not (0 <= row < depth.shape[0] and 0 <= col < depth.shape[1]):
        return None
    window = depth[max(row - 2, 0):row + 3, max(col - 2, 0):col + 3]
    seen = window[window > 0]
    if seen.size == 0:
        return None
    z_top = float(np.median(seen))
    K = sighting["K"]
    p_top_C = np.array([(u - K[0, 2]) * z_top / K[0, 0], (v - K[1, 2]) * z_top / K[1, 1], z_top])
    p_top_W = sighting["R_w2c"].T @ (p_top_C - sighting["t_w2c_m"])
    return p_top_W - np.array([0.0, 0.0, CUBE_HALF_HEIGHT_M])


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: perceive.py MODEL.pt (a prs test --perception worker)")
    if not os.path.exists(sys.argv[1]):
        sys.exit(f"perceive.py: error: no model file {sys.argv[1]} (train one with train.py)")
    import torch
    import cube_net
    from probrobscene.perception import load_sighting, serve_perception
    torch.set_num_threads(1)  # one worker per prs thread
    model = cube_net.load(sys.argv[1])
    serve_perception(lambda request: locate(model, load_sighting(request)))


if __name__ == "__main__":
    main()

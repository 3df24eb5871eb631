"""The learned part of the case study: a small CNN that finds the cube in the ceiling camera's
picture, shared by train.py and perceive.py.

It sees the picture's chromaticity (each pixel's r, g, b over their sum), not its brightness: the
simulator's camera (prs test) and the dataset renderer (prs dataset) light the table differently
and only the simulator draws the arms, but both draw a grey table, grey trays and dark arms, which
have no colour. It answers a heatmap over the picture; its soft-argmax is the pixel (OpenCV
convention: column u, row v, pixel centres at whole numbers) where the cube's centre projects.
The depth picture there and the camera's pose then place the cube in the world (perceive.py).
"""

import numpy as np
import torch
from torch import nn

# The network's input: the 640 x 480 picture averaged over DOWNSAMPLE x DOWNSAMPLE blocks.
DOWNSAMPLE = 4


def to_input(rgb: np.ndarray) -> np.ndarray:
    """A picture (height x width x 3, uint8) as the network's input: 3 x h x w float32, each
    pixel's chromaticity minus 1/3, over blocks of DOWNSAMPLE x DOWNSAMPLE pixels."""
    h, w = rgb.shape[0] // DOWNSAMPLE, rgb.shape[1] // DOWNSAMPLE
    blocks = rgb[:h * DOWNSAMPLE, :w * DOWNSAMPLE].astype(np.float32)
    small = blocks.reshape(h, DOWNSAMPLE, w, DOWNSAMPLE, 3).mean(axis=(1, 3))
    chroma = small / (small.sum(axis=2, keepdims=True) + 1.0) - 1.0 / 3.0
    return np.ascontiguousarray(chroma.transpose(2, 0, 1))


def to_coverage(mask: np.ndarray) -> np.ndarray:
    """A full-size mask (height x width, bool) as the share of each input pixel it covers."""
    h, w = mask.shape[0] // DOWNSAMPLE, mask.shape[1] // DOWNSAMPLE
    blocks = mask[:h * DOWNSAMPLE, :w * DOWNSAMPLE].astype(np.float32)
    return blocks.reshape(h, DOWNSAMPLE, w, DOWNSAMPLE).mean(axis=(1, 3))


class CubeNet(nn.Module):
    """Chromaticity in, the cube centre's pixel (u, v) in the full-size picture out."""

    def __init__(self, width: int = 16):
        super().__init__()
        self.features = nn.Sequential(
            nn.Conv2d(3, width, 5, padding=2), nn.ReLU(),
            nn.Conv2d(width, width, 3, padding=1), nn.ReLU(),
            nn.Conv2d(width, width, 3, padding=2, dilation=2), nn.ReLU(),
            nn.Conv2d(width, 1, 1))

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        logits = self.features(x)  # n x 1 x h x w
        n, _, h, w = logits.shape
        weights = torch.softmax(logits.reshape(n, h * w), dim=1).reshape(n, h, w)
        cols = (torch.arange(w, dtype=x.dtype) + 0.5) * DOWNSAMPLE - 0.5
        rows = (torch.arange(h, dtype=x.dtype) + 0.5) * DOWNSAMPLE - 0.5
        u = (weights.sum(dim=1) * cols).sum(dim=1)
        v = (weights.sum(dim=2) * rows).sum(dim=1)
        return torch.stack([u, v], dim=1)


def save(model: CubeNet, path: str, meta: dict) -> None:
    torch.save({"state": model.state_dict(), "width": model.features[0].out_channels,
                "meta": meta}, path)


def load(path: str) -> CubeNet:
    saved = torch.load(path, map_location="cpu")
    model = CubeNet(saved["width"])
    model.load_state_dict(saved["state"])
    model.eval()
    return model

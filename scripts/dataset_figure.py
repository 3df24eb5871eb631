#!/usr/bin/env python3
"""The figure of docs/dataset.md: one image of a `prs dataset` folder beside its visible masks
in false colour, with each object's COCO box drawn on both. Standard library only (PNG read
and written with zlib), so it runs wherever prs's tests do.

Usage: scripts/dataset_figure.py DATASET_DIR CHUNK IM_ID OUT.png
  e.g. prs dataset examples/table_cube.prs -s 1 -n 1 -o /tmp/ds
       scripts/dataset_figure.py /tmp/ds 0 0 docs/images/dataset_table_cube.png
"""
import json
import struct
import sys
import zlib
from pathlib import Path


def read_png(path):
    """(width, height, channels, rows of bytes) of an 8-bit grey or RGB, non-interlaced PNG."""
    data = Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    at, idat = 8, b""
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour in (0, 2), f"{path}: not 8-bit grey or RGB"
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    channels = 3 if colour == 2 else 1
    raw, stride = zlib.decompress(idat), width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):  # undo the PNG filter of this row
            left = line[i - channels] if i >= channels else 0
            up, corner = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 255
        rows.append(line)
        previous = line
    return width, height, channels, rows


def write_png(path, width, height, rows):
    raw = b"".join(b"\x00" + bytes(row) for row in rows)
    chunk = lambda kind, body: (struct.pack(">I", len(body)) + kind + body
                                + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))
    Path(path).write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                           + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


PALETTE = [(230, 25, 75), (60, 180, 75), (255, 225, 25), (0, 130, 200), (245, 130, 48),
           (145, 30, 180), (70, 240, 240), (240, 50, 230), (210, 245, 60), (250, 190, 212)]


def main(dataset, chunk, im_id, out):
    folder = Path(dataset) / "train_pbr" / f"{int(chunk):06d}"
    width, height, _, rgb = read_png(folder / "rgb" / f"{int(im_id):06d}.png")
    coco = json.loads((folder / "annotations.json").read_text())
    image_id = next(i["id"] for i in coco["images"] if i["file_name"] == f"rgb/{int(im_id):06d}.png")
    gap = 8
    canvas = [bytearray([255] * (3 * (2 * width + gap))) for _ in range(height)]
    for y in range(height):
        canvas[y][:3 * width] = rgb[y]
        canvas[y][3 * (width + gap):] = bytes(v // 4 for v in rgb[y])  # darkened background
    gt_info = json.loads((folder / "scene_gt_info.json").read_text())[str(int(im_id))]
    for k in range(len(gt_info)):
        colour = PALETTE[k % len(PALETTE)]
        mask_path = folder / "mask_visib" / f"{int(im_id):06d}_{k:06d}.png"
        _, _, _, mask = read_png(mask_path)
        for y in range(height):
            for x in range(width):
                if mask[y][x]:
                    canvas[y][3 * (width + gap + x):3 * (width + gap + x) + 3] = bytes(colour)
    for a in coco["annotations"]:
        if a["image_id"] != image_id:
            continue
        k = a["id"] - image_id * 10000 - 1
        colour = bytes(PALETTE[k % len(PALETTE)])
        x0, y0, w, h = a["bbox"]
        for offset in (0, width + gap):
            for x in range(x0, x0 + w):
                for y in (y0, y0 + h - 1):
                    canvas[y][3 * (offset + x):3 * (offset + x) + 3] = colour
            for y in range(y0, y0 + h):
                for x in (x0, x0 + w - 1):
                    canvas[y][3 * (offset + x):3 * (offset + x) + 3] = colour
    write_png(out, 2 * width + gap, height, canvas)


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])

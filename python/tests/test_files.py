"""Scene.export writes what `prs export` writes; Scene.render writes a PNG of the asked size."""

import struct

import pytest

from conftest import EXAMPLES, run_prs


@pytest.mark.parametrize("fmt, ext", [("mjcf", "xml"), ("urdf", "urdf"), ("glb", "glb")])
def test_export_matches_the_command_line(table_cube, prs_binary, tmp_path, fmt, ext):
    scene = table_cube.sample(seed=3, index=7)
    ours = tmp_path / f"ours.{ext}"
    scene.export(fmt, str(ours))
    theirs = tmp_path / f"theirs.{ext}"
    result = run_prs(prs_binary, "export", str(EXAMPLES / "table_cube.prs"), "-s", "3", "--start",
                     "7", "-n", "1", "--format", fmt, "-o", str(theirs))
    assert result.returncode == 0, result.stderr
    assert ours.read_bytes() == theirs.read_bytes()


def test_export_names_the_formats_for_an_unknown_one(table_cube, tmp_path):
    with pytest.raises(ValueError, match="mjcf"):
        table_cube.sample().export("obj", str(tmp_path / "x.obj"))


def png_size(path):
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])  # IHDR width, height


def test_render_writes_a_png_of_the_asked_size(table_cube, tmp_path):
    scene = table_cube.sample(seed=1)
    scene.render(str(tmp_path / "a.png"), width=320, height=240)
    assert png_size(tmp_path / "a.png") == (320, 240)
    scene.render(str(tmp_path / "b.png"), width=200, height=150, view="camera:Camera")
    assert png_size(tmp_path / "b.png") == (200, 150)


def test_render_refuses_a_bad_view(table_cube, tmp_path):
    with pytest.raises(ValueError, match="overview"):
        table_cube.sample().render(str(tmp_path / "c.png"), view="sideways")
    with pytest.raises(ValueError, match="Camera"):
        table_cube.sample().render(str(tmp_path / "c.png"), view="camera:nobody")

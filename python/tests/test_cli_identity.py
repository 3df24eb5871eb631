"""Python samples exactly the scenes the command line does: same seed and index, same JSON line."""

import pytest

import probrobscene as prs
from conftest import EXAMPLES, run_prs


@pytest.mark.parametrize("example", ["table_cube.prs", "constructs.prs",
                                     "table_cube_reachable_visible.prs"])
@pytest.mark.parametrize("seed,start", [(0, 0), (1, 0), (7, 5), (2**64 - 1, 3)])
def test_batch_and_single_scenes_match_prs_sample(prs_binary, example, seed, start):
    path = EXAMPLES / example
    result = run_prs(prs_binary, "sample", str(path), "-n", "6", "-s", str(seed),
                     "--start", str(start))
    assert result.returncode == 0, result.stderr
    expected = result.stdout.splitlines()
    assert len(expected) == 6

    scenario = prs.load(path)
    batch = scenario.sample_batch(6, seed=seed, start=start, threads=3)
    assert [scene.to_json() for scene in batch] == expected
    assert [scenario.sample(seed, start + i).to_json() for i in range(6)] == expected
    assert [s.to_json() for s in scenario.scenes(seed=seed, start=start, count=6)] == expected


def test_thread_count_does_not_change_the_scenes(table_cube):
    one = [s.to_json() for s in table_cube.sample_batch(40, seed=3, threads=1)]
    many = [s.to_json() for s in table_cube.sample_batch(40, seed=3, threads=4)]
    default = [s.to_json() for s in table_cube.sample_batch(40, seed=3)]
    assert one == many == default
    assert len(set(one)) == 40, "different indices give different scenes"


def test_params_and_naive_mode_match_prs(prs_binary, tmp_path):
    program = tmp_path / "p.prs"
    program.write_text("from model import *\nparam size = 0.1\n"
                       "t = Table on V3D(0, 0, 0)\nc1 = Cube on t, with width size\n")
    result = run_prs(prs_binary, "sample", str(program), "-I", str(EXAMPLES), "-n", "3", "-s",
                     "4", "-p", "size=0.05", "--naive")
    assert result.returncode == 0, result.stderr
    scenario = prs.load(program, params={"size": 0.05}, search_path=[EXAMPLES], naive=True)
    assert [s.to_json() for s in scenario.sample_batch(3, seed=4)] == result.stdout.splitlines()
    assert scenario.sample(4, 0).params == {"size": 0.05}
    assert scenario.sample(4, 0)["c1"].dimensions[0] == 0.05


def test_scenes_iterator_in_batches_matches_single_scenes(table_cube):
    ahead = table_cube.scenes(seed=9, threads=2)  # endless, sampled 128 at a time
    got = [next(ahead).to_json() for _ in range(130)]
    assert got == [table_cube.sample(9, i).to_json() for i in range(130)]


DROP = ("from model import *\n"
        "t = Table on V3D(0, 0, 0)\n"
        "d = Cube at V3D((-0.8, -0.6), 0.3, (0.825, 0.84))\n")


def test_stable_matches_prs_and_bad_values_are_refused(prs_binary, tmp_path):
    """stable= is prs --stable: the same scenes (a cube drawn up to 1.5 cm above the table is
    rejected when its fall and its sinking on impact exceed 8 mm), and bad values are
    ValueErrors."""
    path = tmp_path / "drop.prs"
    path.write_text(DROP)
    result = run_prs(prs_binary, "sample", str(path), "-I", str(EXAMPLES), "-n", "8", "-s", "4",
                     "--stable=0.5", "--stable-move", "0.008")
    assert result.returncode == 0, result.stderr
    scenario = prs.load(path, search_path=[EXAMPLES], stable=0.5, stable_move=0.008)
    assert scenario.stable == 0.5
    assert [s.to_json() for s in scenario.sample_batch(8, seed=4, threads=2)] == \
        result.stdout.splitlines()
    assert "unstable" in result.stdout
    assert prs.load(path, search_path=[EXAMPLES]).stable is None
    for bad in (0, -1.0, "1", float("nan")):
        with pytest.raises(ValueError):
            prs.load(path, search_path=[EXAMPLES], stable=bad)
    with pytest.raises(ValueError, match="at least 0.2 s"):  # too short to find rest
        prs.load(path, search_path=[EXAMPLES], stable=0.1)
    with pytest.raises(ValueError):
        prs.load(path, search_path=[EXAMPLES], stable=True, stable_move=0)


FALL = ("from model import *\n"
        "t = Table on V3D(0, 0, 0)\n"
        "c = Cube at V3D((0.85, 0.95), 0, 1.2)\n"
        "require settled c.z > 0.5\n")


def test_settle_matches_prs_and_bad_values_are_refused(prs_binary, tmp_path):
    """settle= is prs --settle: the same settled scenes (cubes that fall off the table's edge are
    drawn again), and bad values, or settle= with stable=, are ValueErrors."""
    path = tmp_path / "fall.prs"
    path.write_text(FALL)
    result = run_prs(prs_binary, "sample", str(path), "-I", str(EXAMPLES), "-n", "6", "-s", "3",
                     "--settle")
    assert result.returncode == 0, result.stderr
    scenario = prs.load(path, search_path=[EXAMPLES], settle=True)
    assert scenario.settle == 4.0
    assert [s.to_json() for s in scenario.sample_batch(6, seed=3, threads=2)] == \
        result.stdout.splitlines()
    assert '"settled_s"' in result.stdout and "unsettled" in result.stdout
    for bad in (0, -1.0, "1", float("nan")):
        with pytest.raises(ValueError):
            prs.load(path, search_path=[EXAMPLES], settle=bad)
    with pytest.raises(ValueError, match="at least 0.5 s"):  # too short to find rest
        prs.load(path, search_path=[EXAMPLES], settle=0.4)
    with pytest.raises(ValueError):
        prs.load(path, search_path=[EXAMPLES], settle=True, stable=True)

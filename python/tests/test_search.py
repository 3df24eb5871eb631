"""Scene coordinates, failure search and failure reports from Python (docs/search.md)."""

import math

import pytest

import probrobscene as prs


def cube_in_corner(scene):
    """Fails when the cube is within 9 cm of (-0.8, 0.3), like `planted-1-percent`."""
    x, y, _ = scene["Cube#5"].position
    distance = math.hypot(x + 0.8, y - 0.3) - 0.09
    return {"outcome": "planted-failure" if distance <= 0 else "success", "score": distance,
            "cube_xy": [x, y]}


def test_coordinates_are_named_from_the_program(table_cube):
    coordinates = table_cube.coordinates()
    assert len(coordinates) == 11
    assert coordinates[6]["name"] == "Cube#5.position[0]"
    assert coordinates[6]["draw"] == "position"
    assert coordinates[6]["line"] == 17


def test_search_finds_more_failures_than_iid_and_reports_them(table_cube):
    seen = []

    def controller(scene):
        seen.append(scene.index)
        return cube_in_corner(scene)

    found = prs.search(table_cube, controller, budget=300, seed=4)
    baseline = prs.search(table_cube, cube_in_corner, budget=300, seed=4, strategy="random")
    assert [r["index"] for r in found] == list(range(300)) == seen
    failures = sum(r["outcome"] != "success" for r in found)
    iid_failures = sum(r["outcome"] != "success" for r in baseline)
    assert failures >= 3 * max(iid_failures, 1), (failures, iid_failures)
    record = found[0]
    assert record["search"]["strategy"] == "ce" and len(record["coordinates"]) == 11
    assert "cube_xy" in record["extra"] and isinstance(record["score"], float)
    # The same search from the same seed gives the same records.
    again = prs.search(table_cube, cube_in_corner, budget=300, seed=4)
    assert [r["coordinates"] for r in again] == [r["coordinates"] for r in found]
    markdown = prs.report(found)
    assert markdown.startswith("# Failure report")
    assert "The strongest single split: **" in markdown and "Cube#5" in markdown


def test_bayesian_optimisation_beats_iid(table_cube):
    bo = prs.search(table_cube, cube_in_corner, budget=120, seed=2, strategy="bo")
    iid = prs.search(table_cube, cube_in_corner, budget=120, seed=2, strategy="random")
    assert [r["search"]["strategy"] for r in bo[:1]] == ["bo"]
    assert bo[-1]["search"]["generation"] == 11  # generations of 10
    bo_failures = sum(r["outcome"] != "success" for r in bo)
    iid_failures = sum(r["outcome"] != "success" for r in iid)
    assert bo_failures >= 3 * max(iid_failures, 2), (bo_failures, iid_failures)
    again = prs.search(table_cube, cube_in_corner, budget=120, seed=2, strategy="bo")
    assert [r["coordinates"] for r in again] == [r["coordinates"] for r in bo]


def test_bad_requests_raise(table_cube):
    with pytest.raises(ValueError, match="unknown strategy 'cee'"):
        prs.search(table_cube, cube_in_corner, budget=10, strategy="cee")
    with pytest.raises(ValueError, match="budget must be >= 1"):
        prs.search(table_cube, cube_in_corner, budget=0)
    fixed = prs.loads("Object at Vector3D(0, 0, 0)\n")
    with pytest.raises(ValueError, match="draws nothing at random"):
        prs.search(fixed, cube_in_corner, budget=10)
    records = prs.search(table_cube, lambda scene: {"outcome": "success", "score": math.nan},
                         budget=3)
    assert {r["outcome"] for r in records} == {"bad-answer"}
    records = prs.search(table_cube, lambda scene: 42, budget=2)
    assert {r["outcome"] for r in records} == {"bad-answer"}
    with pytest.raises(ValueError, match="<records>:1: not an episode record"):
        prs.report([{"no": "outcome"}])


def test_keyboard_interrupt_stops_the_search_and_other_exceptions_do_not(table_cube):
    calls = []

    def interrupted(scene):
        calls.append(scene.index)
        if len(calls) == 5:
            raise KeyboardInterrupt
        return "success"

    with pytest.raises(KeyboardInterrupt):
        prs.search(table_cube, interrupted, budget=100)
    assert len(calls) == 5

    def broken(scene):
        raise RuntimeError("the gripper driver is not connected")

    records = prs.search(table_cube, broken, budget=4)
    assert {r["outcome"] for r in records} == {"controller-error"}
    assert "gripper driver" in records[0]["detail"]


def test_estimate_gives_the_planted_rate_with_a_function_or_a_builtin(table_cube):
    """planted-1-percent fails in 1.02 % of Table-Cube's scenes (2,000,000 i.i.d. episodes)."""
    by_function = prs.estimate(table_cube, cube_in_corner, budget=2000, seed=3)
    by_name = prs.estimate(table_cube, "planted-1-percent", budget=2000, seed=3, threads=2)
    for result in (by_function, by_name):
        assert result["reliable"]
        e = result["estimates"]["planted-failure"]
        assert 0.006 < e["p"] < 0.016
        assert e["ci95"][0] <= e["p"] <= e["ci95"][1]
        # As precise as more i.i.d. episodes than it ran (the reported precision is a
        # conservative one: docs/search.md, "How good, since 2026-11-28").
        assert e["iid_episodes_for_same_precision"] > 2000
        assert len(result["records"]) == 2000
        assert result["records"][-1]["search"]["strategy"] == "importance"
    # The same scenes and outcomes, so the same numbers, whoever runs the controller.
    assert by_function["estimates"]["planted-failure"]["p"] == \
        pytest.approx(by_name["estimates"]["planted-failure"]["p"])
    with pytest.raises(ValueError, match="budget must be >= 200"):
        prs.estimate(table_cube, cube_in_corner, budget=100)
    with pytest.raises(ValueError, match="unknown controller 'planted'"):
        prs.estimate(table_cube, "planted", budget=300)

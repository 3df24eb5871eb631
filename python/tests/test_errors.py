"""Bad programs raise ScenarioError with the located message `prs` prints; impossible scenarios
raise SamplingError."""

import pytest

import probrobscene as prs
from conftest import EXAMPLES, run_prs


def test_unknown_name_carries_its_location(tmp_path, prs_binary):
    program = tmp_path / "typo.prs"
    program.write_text("from model import *\nt = Table on V3D(0, 0, 0)\nc = Cueb on t\n")
    with pytest.raises(prs.ScenarioError) as caught:
        prs.load(program, search_path=[EXAMPLES])
    error = caught.value
    assert (error.file, error.line, error.column) == (str(program), 3, 5)
    assert error.id and "Cueb" in error.message
    assert str(error).startswith(f"{program}:3:5: error: ")
    assert "Cube" in str(error), "the rendering carries the did-you-mean note or fix-it"
    # The same text as the command line prints (without colour, as stderr is not a terminal).
    cli = run_prs(prs_binary, "check", str(program), "-I", str(EXAMPLES), "-n", "0")
    assert cli.returncode == 1
    assert error.text in cli.stderr


def test_syntax_error_in_text_names_the_given_name():
    with pytest.raises(prs.ScenarioError) as caught:
        prs.loads("x = (1, 2\ny = 3\n", name="inline.prs")
    error = caught.value
    assert error.file == "inline.prs" and error.line is not None and error.column is not None
    assert not isinstance(error, prs.SamplingError)


def test_error_in_an_imported_module_points_into_that_module(tmp_path):
    (tmp_path / "broken.prs").write_text("class Box(Object):\n    width: 1 +\n")
    (tmp_path / "main.prs").write_text("from broken import *\nb = Box\n")
    with pytest.raises(prs.ScenarioError) as caught:
        prs.load(tmp_path / "main.prs")
    assert caught.value.file == str(tmp_path / "broken.prs")
    assert caught.value.line == 2


def test_missing_file_names_the_file(tmp_path):
    missing = tmp_path / "missing.prs"
    with pytest.raises(prs.ScenarioError) as caught:
        prs.load(missing)
    error = caught.value
    assert error.id == "file-not-found" and error.file == str(missing)
    assert error.line is None and error.column is None
    assert str(missing) in str(error)


def test_unknown_param_override_is_an_error():
    with pytest.raises(prs.ScenarioError) as caught:
        prs.load(EXAMPLES / "table_cube.prs", params={"no_such_param": 1})
    assert "no_such_param" in str(caught.value)


def test_impossible_scenario_raises_sampling_error_with_location(prs_binary, tmp_path):
    program = tmp_path / "impossible.prs"
    program.write_text("from model import *\nt = Table on V3D(0, 0, 0)\n"
                       "c = Cube on t\nrequire c.position.x > 100\n")
    scenario = prs.load(program, search_path=[EXAMPLES], max_attempts=50)
    with pytest.raises(prs.SamplingError) as caught:
        scenario.sample(seed=1)
    error = caught.value
    assert isinstance(error, prs.ScenarioError)
    assert error.id == "sampling-failed" and error.file is not None and error.line is not None
    with pytest.raises(prs.SamplingError):
        scenario.sample_batch(4, seed=1)
    cli = run_prs(prs_binary, "sample", str(program), "-I", str(EXAMPLES), "--max-attempts", "50",
                  "-s", "1")
    assert cli.returncode == 3
    assert error.text in cli.stderr


def test_run_time_error_is_located():
    scenario = prs.loads("x = 1 / 0\n", name="div.prs")
    with pytest.raises(prs.ScenarioError) as caught:
        scenario.sample()
    assert (caught.value.file, caught.value.line) == ("div.prs", 1)


@pytest.mark.parametrize("text", [
    "x = 1" + " + 1" * 100_000,
    "x = Vector3D(1, 0, 0)" + ".normalized()" * 100_000,
    "x = [0]" + "[0]" * 100_000,
    "x = " + "-" * 100_000 + "1",
])
def test_long_chains_raise_instead_of_crashing_the_interpreter(text):
    with pytest.raises(prs.ScenarioError) as caught:
        prs.loads(text + "\n", name="long.prs")
    assert caught.value.id == "too-deeply-nested"
    assert (caught.value.file, caught.value.line) == ("long.prs", 1)
    assert len(caught.value.text) < 2000, "a window of the line, not all of it"


def test_values_nested_by_a_loop_raise_when_sampled():
    scenario = prs.loads("x = ()\nfor i in range(5000):\n    x = (x,)\n", name="nest.prs")
    with pytest.raises(prs.ScenarioError, match="nested more than 1000 levels"):
        scenario.sample()


def test_arms_and_cameras_are_checked_with_located_errors(tmp_path):
    header = "from model import *\nt = Table on V3D(0, 0, 0)\n"
    not_an_arm = tmp_path / "arm.prs"
    not_an_arm.write_text(header + "c = Cube on t, reachable by t\n")
    with pytest.raises(prs.ScenarioError) as caught:
        prs.load(not_an_arm, search_path=[EXAMPLES]).sample(0, 0)
    assert (caught.value.line, caught.value.id) == (3, "not-an-arm")
    assert "t is a Table, which is not an arm" in caught.value.message
    wide = tmp_path / "camera.prs"
    wide.write_text(header + "cam = Camera at V3D(0, 0, 2), facing V3D(0, 0, -1), with fovy_deg 190\n"
                    "d = Cube on t, in view of cam\n")
    with pytest.raises(prs.ScenarioError) as caught:
        prs.load(wide, search_path=[EXAMPLES]).sample(0, 0)
    assert (caught.value.line, caught.value.id) == (4, "bad-camera")
    assert "between 0° and 180°, not 190°" in caught.value.message

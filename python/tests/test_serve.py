"""probrobscene.serve, the Python side of `prs test --exec CMD --persistent`, driven by hand:
workers run as subprocesses on the package's sources alone (no compiled module, no prs)."""

import json
import os
import queue
import subprocess
import sys
import textwrap
import threading
import time

import pytest

from conftest import REPO

PYTHON_DIR = REPO / "python"
SLOW_START = REPO / "examples" / "controllers" / "slow_start.py"
WAIT_S = 20  # for what should take milliseconds: generous on a busy machine

# A controller that does what the scene's "case" asks; after serve returns it checks that the
# real stdout is back (exit 3 if not).
CONTROLLER = textwrap.dedent('''\
    import os, subprocess, sys
    from probrobscene.serve import serve

    STDOUT, STDOUT_INODE = sys.stdout, os.fstat(1).st_ino
    print("start-up chatter, before serve")

    def noisy(scene):
        print("from print")
        os.write(1, b"from file descriptor 1\\n")
        subprocess.run(["echo", "from a child process"], check=True)
        return {"outcome": "success", "stdout_is_stderr": sys.stdout is sys.stderr}

    def fail(scene):
        raise ValueError("boom")

    def leave(scene):
        raise SystemExit(7)

    def read_stdin(scene):  # stdin is not the protocol's while the controller runs
        child = subprocess.run(["cat"], capture_output=True, text=True, check=True).stdout
        return {"outcome": "success", "read": sys.stdin.readline(), "child_read": child}

    CASES = {
        "name": lambda scene: "no-path",
        "dict": lambda scene: {"outcome": "poor-grip", "detail": "it slipped", "score": 2,
                               "grip_N": [3.5, 1], "seed": "the controller's own"},
        "noisy": noisy,
        "raise": fail,
        "exit": leave,
        "read-stdin": read_stdin,
        "int": lambda scene: 42,
        "none": lambda scene: None,
        "no-outcome": lambda scene: {"detail": "no outcome"},
        "bad-name": lambda scene: "No Path",
        "long-name": lambda scene: "x" * 65,
        "bad-detail": lambda scene: {"outcome": "success", "detail": 3},
        "nan-score": lambda scene: {"outcome": "success", "score": float("nan")},
        "inf-score": lambda scene: {"outcome": "success", "score": float("inf")},
        "text-score": lambda scene: {"outcome": "success", "score": "1.0"},
        "bool-score": lambda scene: {"outcome": "success", "score": True},
        "set-extra": lambda scene: {"outcome": "success", "seen": {1, 2}},
        "nan-extra": lambda scene: {"outcome": "success", "error_m": float("nan")},
    }

    serve(lambda scene: CASES[scene["case"]](scene), ready_extra={"name": "test-worker"})
    sys.exit(0 if sys.stdout is STDOUT and os.fstat(1).st_ino == STDOUT_INODE else 3)
''')

BAD_RETURNS = {  # case: what the detail says
    "int": "the controller returned 42, not a str or a dict",
    "none": "the controller returned None, not a str or a dict",
    "no-outcome": "the outcome None is not a lowercase-hyphenated name",
    "bad-name": "the outcome 'No Path' is not a lowercase-hyphenated name",
    "long-name": "the outcome 'xxxxx",
    "bad-detail": "the detail 3 is not a string",
    "nan-score": "the score nan is not a finite number",
    "inf-score": "the score inf is not a finite number",
    "text-score": "the score '1.0' is not a finite number",
    "bool-score": "the score True is not a finite number",
    "set-extra": "the answer cannot be written as JSON (Object of type set",
    "nan-extra": "the answer cannot be written as JSON (Out of range float",
}


def scene_line(index, case="name", seed=1, **more):
    return json.dumps({"format": "prs-scene/1", "seed": seed, "index": index, "case": case,
                       "objects": [], **more})


class Worker:
    """A worker process with PYTHONPATH=python/ only; stdout lines arrive through a queue."""

    def __init__(self, script, tmp_path, persistent=True, env_extra=None):
        env = {key: value for key, value in os.environ.items() if key != "PRS_PERSISTENT"}
        env.update(env_extra or {})
        if persistent:
            env.update(PRS_PERSISTENT="1", PRS_WORKER="0")
        env["PYTHONPATH"] = str(PYTHON_DIR)
        self.stderr_path = tmp_path / "stderr.txt"
        with open(self.stderr_path, "wb") as stderr:
            self.process = subprocess.Popen([sys.executable, str(script)], cwd=tmp_path, env=env,
                                            stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                            stderr=stderr, text=True)
        self.lines = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        for line in self.process.stdout:
            self.lines.put(line)
        self.lines.put(None)  # end of stdout

    def send(self, line):
        self.process.stdin.write(line + "\n")
        self.process.stdin.flush()

    def read_line(self):
        """The next stdout line (None at its end)."""
        return self.lines.get(timeout=WAIT_S)

    def read_json(self):
        line = self.read_line()
        assert line is not None and line.startswith("{"), f"{line!r}; stderr: {self.stderr()}"
        return json.loads(line)

    def read_protocol(self):
        """The first line that starts with "{", as prs reads it (it skips start-up chatter)."""
        line = self.read_line()
        while line is not None and not line.startswith("{"):
            line = self.read_line()
        assert line is not None, f"stdout ended; stderr: {self.stderr()}"
        return json.loads(line)

    def ask(self, index, case, **more):
        self.send(scene_line(index, case, **more))
        return self.read_json()

    def close_and_wait(self):
        """Closes stdin and returns the exit status and what was left on stdout."""
        self.process.stdin.close()
        status = self.process.wait(timeout=WAIT_S)
        rest = []
        while (line := self.read_line()) is not None:
            rest.append(line)
        return status, rest

    def stderr(self):
        return self.stderr_path.read_text()


@pytest.fixture
def worker(tmp_path):
    script = tmp_path / "controller.py"
    script.write_text(CONTROLLER)
    started = Worker(script, tmp_path)
    yield started
    if started.process.poll() is None:
        started.process.kill()
        started.process.wait()


def test_handshake_comes_first_then_answers_that_name_their_scene(worker):
    assert worker.read_line() == "start-up chatter, before serve\n"  # the script's own print
    assert worker.read_json() == {"name": "test-worker", "ready": True}
    assert worker.ask(0, "name") == {"outcome": "no-path", "seed": 1, "index": 0}
    big_seed = 2**64 - 1
    assert worker.ask(17, "dict", seed=big_seed) == {
        "outcome": "poor-grip", "detail": "it slipped", "score": 2.0, "grip_N": [3.5, 1],
        "seed": big_seed, "index": 17}
    assert worker.close_and_wait() == (0, [])


def test_print_and_child_processes_write_to_stderr_not_to_the_protocol(worker):
    worker.read_protocol()
    assert worker.ask(3, "noisy") == {"outcome": "success", "stdout_is_stderr": True,
                                      "seed": 1, "index": 3}
    assert worker.ask(4, "name")["outcome"] == "no-path"
    assert worker.close_and_wait() == (0, [])
    stderr = worker.stderr()
    for text in ["from print", "from file descriptor 1", "from a child process"]:
        assert text in stderr


def test_the_controller_and_its_children_read_nothing_from_stdin(worker):
    worker.read_protocol()
    assert worker.ask(11, "read-stdin") == {"outcome": "success", "read": "", "child_read": "",
                                            "seed": 1, "index": 11}
    assert worker.ask(12, "name")["outcome"] == "no-path"
    assert worker.close_and_wait() == (0, [])


def test_an_exception_answers_controller_error_and_the_worker_goes_on(worker):
    worker.read_protocol()
    assert worker.ask(5, "raise") == {"outcome": "controller-error",
                                      "detail": "ValueError: boom", "seed": 1, "index": 5}
    assert worker.ask(6, "name") == {"outcome": "no-path", "seed": 1, "index": 6}
    assert worker.close_and_wait() == (0, [])
    assert "Traceback (most recent call last)" in worker.stderr()
    assert 'raise ValueError("boom")' in worker.stderr()


@pytest.mark.parametrize("case, problem", BAD_RETURNS.items())
def test_a_bad_return_answers_controller_error_saying_what_to_return(worker, case, problem):
    worker.read_protocol()
    answer = worker.ask(8, case)
    assert answer["outcome"] == "controller-error", answer
    assert (answer["seed"], answer["index"]) == (1, 8)
    assert answer["detail"].startswith(problem), answer["detail"]
    assert 'return an outcome name such as "success"' in answer["detail"]
    assert worker.ask(9, "name") == {"outcome": "no-path", "seed": 1, "index": 9}
    assert worker.close_and_wait() == (0, [])


def test_system_exit_in_the_controller_ends_the_worker(worker):
    worker.read_protocol()
    worker.send(scene_line(10, "exit"))
    assert worker.process.wait(timeout=WAIT_S) == 7
    assert worker.read_line() is None  # no answer


def test_end_of_stdin_ends_the_worker_promptly_with_status_0(worker):
    worker.read_protocol()
    begin = time.monotonic()
    assert worker.close_and_wait() == (0, [])
    assert time.monotonic() - begin < 5


@pytest.mark.parametrize("line", ["{not json", "[1, 2]", '{"index": 4}', "\xff"])
def test_a_stdin_line_that_is_not_a_scene_exits_2(worker, line):
    worker.read_protocol()
    worker.send(line)
    assert worker.process.wait(timeout=WAIT_S) == 2
    assert worker.read_line() is None
    assert "probrobscene.serve: error: a stdin line is not" in worker.stderr()


@pytest.mark.parametrize("persistent_value", [None, "0"])
def test_one_shot_mode_answers_one_scene_and_exits_0(tmp_path, persistent_value):
    script = tmp_path / "controller.py"
    script.write_text(CONTROLLER)
    env = {} if persistent_value is None else {"PRS_PERSISTENT": persistent_value}
    worker = Worker(script, tmp_path, persistent=False, env_extra=env)
    worker.send(scene_line(2, "dict"))
    worker.send(scene_line(3, "name"))  # not read: one scene per process
    status, lines = worker.close_and_wait()
    assert status == 0, worker.stderr()
    assert lines[0] == "start-up chatter, before serve\n"  # no handshake
    assert [json.loads(line) for line in lines[1:]] == [{
        "outcome": "poor-grip", "detail": "it slipped", "score": 2.0, "grip_N": [3.5, 1],
        "seed": 1, "index": 2}]


def test_one_shot_mode_without_a_scene_exits_2(tmp_path):
    script = tmp_path / "controller.py"
    script.write_text(CONTROLLER)
    worker = Worker(script, tmp_path, persistent=False)
    status, lines = worker.close_and_wait()
    assert status == 2
    assert lines == ["start-up chatter, before serve\n"]
    assert "stdin ended before a scene arrived" in worker.stderr()


def test_the_package_imports_serve_without_the_compiled_module():
    assert not list((PYTHON_DIR / "probrobscene").glob("_core*")), "python/ must stay source only"
    code = textwrap.dedent('''\
        import sys
        import probrobscene
        from probrobscene.serve import serve
        assert probrobscene.serve is serve and callable(serve)
        assert "serve" in probrobscene.__all__
        exec("from probrobscene import *", {})  # every name in __all__ exists
        assert "probrobscene._core" not in sys.modules
        try:
            probrobscene.load
        except ImportError as error:
            assert "probrobscene._core is not built" in str(error), error
        else:
            raise AssertionError("probrobscene.load exists without _core")
        print("ok")
    ''')
    env = dict(os.environ, PYTHONPATH=str(PYTHON_DIR))
    result = subprocess.run([sys.executable, "-c", code], cwd="/", env=env, capture_output=True,
                            text=True, timeout=WAIT_S)
    assert (result.returncode, result.stdout) == (0, "ok\n"), result.stderr


def reach_scene(index, cube_xyz):
    return json.dumps({"format": "prs-scene/1", "seed": 4, "index": index, "objects": [
        {"name": "r1", "class": "Robot", "position": [0.0, 0.0, 0.0]},
        {"name": None, "class": "Cube", "position": cube_xyz}]})


@pytest.mark.parametrize("persistent", [True, False])
def test_slow_start_example_decides_reach_in_both_modes(tmp_path, persistent):
    env = dict(os.environ, PRS_EXAMPLE_STARTUP_S="0")
    env.pop("PYTHONPATH", None)  # the example finds python/ by itself
    env.pop("PRS_PERSISTENT", None)
    if persistent:
        env.update(PRS_PERSISTENT="1", PRS_WORKER="0")
    scenes = [reach_scene(0, [0.5, 0.0, 0.0]), reach_scene(1, [0.0, 2.0, 0.0])]
    result = subprocess.run([sys.executable, str(SLOW_START)], cwd=tmp_path, env=env,
                            input="\n".join(scenes if persistent else scenes[1:]) + "\n",
                            capture_output=True, text=True, timeout=WAIT_S)
    assert result.returncode == 0, result.stderr
    answers = [json.loads(line) for line in result.stdout.splitlines()]
    out_of_reach = {"outcome": "out-of-reach", "seed": 4, "index": 1, "distance_m": 2.0,
                    "detail": "Cube#1 is 2.000 m from r1, out of the arm's reach",
                    "score": pytest.approx(0.855 - 2.0)}
    if persistent:
        assert answers == [{"ready": True},
                           {"outcome": "success", "seed": 4, "index": 0, "distance_m": 0.5,
                            "detail": "every Cube is within an arm's reach",
                            "score": pytest.approx(0.25)},
                           out_of_reach]
    else:
        assert answers == [out_of_reach]
    assert "Cube#1 is 2.000 m from r1" in result.stderr  # its print went to stderr

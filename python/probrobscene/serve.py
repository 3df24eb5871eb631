"""Your controller as a worker of ``prs test --exec CMD``: ``serve(controller)`` speaks the
protocol (docs/harness.md), so a controller is one function from a scene to an outcome.

Standard library only: it runs without the compiled module, under Debian's /usr/bin/python3.
"""

import contextlib
import json
import math
import numbers
import os
import re
import sys
import traceback
from typing import (Any, BinaryIO, Callable, Dict, Iterator, Mapping, NoReturn, Optional, Tuple,
                    Union)

Answer = Union[str, Mapping[str, Any]]

_OUTCOME = re.compile(r"[a-z0-9]+(?:-[a-z0-9]+)*")  # as prs checks it, at most 64 characters
_HOW_TO_ANSWER = ('return an outcome name such as "success", or a dict with "outcome" and '
                  'optionally "detail" (a string), "score" (a finite number) and other keys')


def serve(controller: Callable[[Dict[str, Any]], Answer], *,
          ready_extra: Optional[Mapping[str, Any]] = None) -> None:
    """Answers the scenes ``prs test --exec`` sends with ``controller(scene)``.

    With ``PRS_PERSISTENT=1`` in the environment (``prs test --exec CMD --persistent``) it
    first writes the handshake ``{"ready": true}`` (and the keys of ``ready_extra``, which must
    be JSON), then answers scene after scene until stdin ends, and returns. Otherwise it answers
    the one scene on stdin and returns. Pay your start-up (a simulator's launch) before calling.

    ``controller`` gets the scene as a dict (spec §8 JSON, as ``prs sample`` writes it) and
    returns an outcome name (``"success"``, ``"no-path"``, ...) or a dict with ``"outcome"``
    and optionally ``"detail"`` (a sentence), ``"score"`` (a finite number) and other keys
    (the record's ``extra``). The answer echoes the scene's ``"seed"`` and ``"index"``; the
    controller's own keys of those names are overwritten. An exception (but KeyboardInterrupt
    and SystemExit, which end the worker) or a return that is none of these answers
    ``"controller-error"``, the traceback or what to return printed on stderr, and the next
    scene is served as usual.

    While it runs, stdout (``sys.stdout`` and file descriptor 1, which child processes inherit)
    goes to stderr and stdin reads nothing: only the protocol's lines reach the real ones. A
    stdin line that is not a JSON object with ``"seed"`` and ``"index"``, or no scene at all in
    one-shot mode, is a message on stderr and ``SystemExit(2)``: the answer could not name its
    scene (prs records the episode as ``exit-2`` and starts the worker again).
    """
    persistent = os.environ.get("PRS_PERSISTENT") == "1"
    with _protocol_channel() as (scenes, answers):
        if persistent:
            _send(answers, json.dumps({**(ready_extra or {}), "ready": True}, allow_nan=False))
        for line in scenes:
            if not line.strip():
                continue
            _send(answers, _answer_line(controller, _parse_scene(line)))
            if not persistent:
                return
        if not persistent:
            _exit_bad_input("stdin ended before a scene arrived")


@contextlib.contextmanager
def _protocol_channel() -> Iterator[Tuple[BinaryIO, BinaryIO]]:
    """The real stdin and stdout, for the protocol alone; meanwhile descriptor 0 reads
    /dev/null and 1 writes to stderr, so neither the controller nor a process it starts (which
    inherits 0 and 1, not the copies) can take a scene or write into the answers."""
    sys.stdout.flush()
    saved = os.dup(0), os.dup(1)  # not inheritable (PEP 446)
    original_stdout = sys.stdout
    null = os.open(os.devnull, os.O_RDONLY)
    os.dup2(null, 0)
    os.close(null)
    os.dup2(2, 1)
    sys.stdout = sys.stderr
    try:
        with os.fdopen(saved[0], "rb", closefd=False) as scenes, \
                os.fdopen(saved[1], "wb", closefd=False) as answers:
            yield scenes, answers
    finally:
        sys.stdout = original_stdout
        for fd, copy in enumerate(saved):
            os.dup2(copy, fd)
            os.close(copy)


def _send(answers: BinaryIO, line: str) -> None:
    answers.write(line.encode("utf-8") + b"\n")
    answers.flush()


def _parse_scene(line: bytes) -> Dict[str, Any]:
    try:
        scene = json.loads(line)
    except ValueError as error:  # JSONDecodeError, UnicodeDecodeError
        _exit_bad_input(f"a stdin line is not JSON ({error})")
    if not isinstance(scene, dict) or "seed" not in scene or "index" not in scene:
        _exit_bad_input('a stdin line is not a scene: a JSON object with "seed" and "index"')
    return scene


def _exit_bad_input(message: str) -> NoReturn:
    print(f"probrobscene.serve: error: {message}", file=sys.stderr, flush=True)
    sys.exit(2)


def _answer_line(controller: Callable[[Dict[str, Any]], Answer], scene: Dict[str, Any]) -> str:
    """The answer to ``scene`` as one line of JSON; "controller-error" if there is none."""
    ids = {"seed": scene["seed"], "index": scene["index"]}  # before the controller can change them
    try:
        return _answer_json(controller(scene), ids)
    except _BadAnswer as error:
        detail = f"{error}; {_HOW_TO_ANSWER}"
        print(f"probrobscene.serve: {detail}", file=sys.stderr, flush=True)
    except Exception as error:  # KeyboardInterrupt and SystemExit are not Exceptions
        traceback.print_exc()  # on sys.stderr
        detail = f"{type(error).__name__}: {error}" if str(error) else type(error).__name__
    return json.dumps({"outcome": "controller-error", "detail": detail, **ids})


class _BadAnswer(Exception):
    """The controller returned something that is not an answer."""


def _answer_json(result: Any, ids: Dict[str, Any]) -> str:
    """The controller's return with ``ids`` as a JSON line, or _BadAnswer saying what is wrong."""
    if isinstance(result, str):
        result = {"outcome": result}
    if not isinstance(result, Mapping):
        raise _BadAnswer(f"the controller returned {_short(result)}, not a str or a dict")
    answer = {**result, **ids}  # a copy: the controller's dict is left as it was
    outcome = answer.get("outcome")
    if not (isinstance(outcome, str) and len(outcome) <= 64 and _OUTCOME.fullmatch(outcome)):
        raise _BadAnswer(f"the outcome {_short(outcome)} is not a lowercase-hyphenated name")
    if not isinstance(answer.get("detail", ""), str):
        raise _BadAnswer(f"the detail {_short(answer['detail'])} is not a string")
    if "score" in answer:
        if not _is_finite_number(answer["score"]):
            raise _BadAnswer(f"the score {_short(answer['score'])} is not a finite number")
        answer["score"] = float(answer["score"])  # numpy scalars too
    try:
        return json.dumps(answer, allow_nan=False)
    except (TypeError, ValueError) as error:
        raise _BadAnswer(f"the answer cannot be written as JSON ({error})") from None


def _is_finite_number(value: Any) -> bool:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return False
    try:
        return math.isfinite(value)
    except OverflowError:  # an int too large for a float
        return False


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."

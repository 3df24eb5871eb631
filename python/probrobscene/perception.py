"""A learned perception as a worker of ``prs test --controller table-cube --perception CMD``:
``serve_perception(perceive)`` speaks the protocol (docs/harness.md, "Perception workers"), so
a perception is one function from a sighting to the cube's position.

Standard library only, but for ``load_sighting`` (numpy and Pillow, Debian's python3-numpy and
python3-pil), which reads a sighting's pictures as arrays.
"""

import json
import math
import sys
import traceback
from typing import Any, Callable, Dict, Mapping, Optional, Sequence, Union

from .serve import _exit_bad_input, _protocol_channel, _send, _short

Position = Sequence[float]  # x, y, z in metres, world frame
Answer = Union[None, Position, Mapping[str, Any]]

_HOW_TO_ANSWER = ('return the cube centre\'s [x, y, z] in metres in the world frame, None when '
                  'no cube is seen, or a dict with "p_WCube_m" or "found": False')


def serve_perception(perceive: Callable[[Dict[str, Any]], Answer], *,
                     ready_extra: Optional[Mapping[str, Any]] = None) -> None:
    """Answers the sightings ``prs test --perception`` sends with ``perceive(request)``.

    Writes the handshake ``{"ready": true}`` (with the keys of ``ready_extra``) first: load the
    model before calling. Then answers request after request until stdin ends, and returns.

    ``request`` is a dict: ``"rgb"`` and ``"depth"`` (paths of the sighting's PNG pictures, as
    a BOP dataset's rgb/ and depth/ hold them; ``load_sighting`` reads them), ``"width"``,
    ``"height"``, and BOP's ``"cam_K"``, ``"cam_R_w2c"``, ``"cam_t_w2c"`` (mm) and
    ``"depth_scale"`` (mm per depth unit), in OpenCV's camera frame; ``"seed"``, ``"index"``
    (the scene) and ``"sighting"`` (0 at the start, 1 after the hand-over).

    ``perceive`` returns the cube centre's ``[x, y, z]`` in metres in the world frame, ``None``
    when it sees no cube (the episode is a ``perception-fault``), or a dict with
    ``"p_WCube_m"`` or ``"found": False`` and an optional ``"detail"``. An exception (but
    KeyboardInterrupt and SystemExit, which end the worker) answers ``"error"``: the episode is
    a ``controller-error`` with the exception's text, and the next sighting is served as usual.
    """
    with _protocol_channel() as (requests, answers):
        _send(answers, json.dumps({**(ready_extra or {}), "ready": True}, allow_nan=False))
        for line in requests:
            if not line.strip():
                continue
            _send(answers, _answer_line(perceive, _parse_request(line)))


def load_sighting(request: Mapping[str, Any]) -> Dict[str, Any]:
    """The sighting's pictures as arrays: ``"rgb"`` (height x width x 3, uint8, rows from the
    top) and ``"depth_m"`` (height x width, float32, metres along the camera's z; 0 where
    nothing was seen), with ``"K"`` (3 x 3), ``"R_w2c"`` (3 x 3) and ``"t_w2c_m"`` (3)."""
    import numpy as np
    from PIL import Image

    with Image.open(request["rgb"]) as picture:
        rgb = np.asarray(picture.convert("RGB"), dtype=np.uint8)
    with Image.open(request["depth"]) as picture:
        depth = np.asarray(picture, dtype=np.float32) * (float(request["depth_scale"]) / 1000.0)
    return {"rgb": rgb, "depth_m": depth,
            "K": np.asarray(request["cam_K"], dtype=np.float64).reshape(3, 3),
            "R_w2c": np.asarray(request["cam_R_w2c"], dtype=np.float64).reshape(3, 3),
            "t_w2c_m": np.asarray(request["cam_t_w2c"], dtype=np.float64) / 1000.0}


def _parse_request(line: bytes) -> Dict[str, Any]:
    try:
        request = json.loads(line)
    except ValueError as error:
        _exit_bad_input(f"a stdin line is not JSON ({error})")
    if not isinstance(request, dict) or not all(k in request for k in ("seed", "index",
                                                                        "sighting")):
        _exit_bad_input('a stdin line is not a sighting: a JSON object with "seed", "index" and '
                        '"sighting"')
    return request


def _answer_line(perceive: Callable[[Dict[str, Any]], Answer], request: Dict[str, Any]) -> str:
    ids = {key: request[key] for key in ("seed", "index", "sighting")}
    try:
        return json.dumps({**_answer(perceive(request)), **ids}, allow_nan=False)
    except _BadAnswer as error:
        message = f"{error}; {_HOW_TO_ANSWER}"
        print(f"probrobscene.serve_perception: {message}", file=sys.stderr, flush=True)
    except Exception as error:  # KeyboardInterrupt and SystemExit are not Exceptions
        traceback.print_exc()
        message = f"{type(error).__name__}: {error}" if str(error) else type(error).__name__
    return json.dumps({"error": message, **ids})


class _BadAnswer(Exception):
    """perceive returned something that is not an answer."""


def _answer(result: Answer) -> Dict[str, Any]:
    if result is None:
        return {"found": False}
    if isinstance(result, Mapping):
        answer = dict(result)
        if answer.get("found") is False:
            return answer
        if "p_WCube_m" not in answer:
            raise _BadAnswer(f"perceive returned {_short(result)}, without \"p_WCube_m\"")
        answer["p_WCube_m"] = _position(answer["p_WCube_m"])
        return answer
    return {"p_WCube_m": _position(result)}


def _position(value: Any) -> list:
    try:
        p = [float(x) for x in value]  # numpy arrays and tensors too
    except (TypeError, ValueError):
        raise _BadAnswer(f"perceive returned {_short(value)}, not three numbers") from None
    if len(p) != 3 or not all(math.isfinite(x) for x in p):
        raise _BadAnswer(f"perceive returned {_short(value)}, not three finite numbers")
    return p

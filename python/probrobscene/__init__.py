"""ProbRobScene from Python: compile ``.prs`` scenarios and sample scenes at C++ speed.

    import probrobscene as prs
    scenario = prs.load("examples/table_cube.prs")
    scenes = scenario.sample_batch(1000, seed=1)      # all threads, without the GIL
    xyz = prs.positions(scenes, "c1")                 # numpy array (1000, 3)

Scene ``i`` of seed ``s`` is the scene ``prs sample -s s --start i`` prints, on any machine and
any number of threads. Units are metres and radians. See docs/python.md.

``serve`` (your controller as a ``prs test --exec`` worker) and ``serve_perception`` (a learned
perception as a ``prs test --perception`` worker) are pure Python: from the sources alone,
without the compiled module ``_core``, the package imports with them and the errors.
"""

from __future__ import annotations  # the hints name compiled classes, absent without _core

import json
import numbers
import os
from typing import Any, Dict, Iterable, Iterator, List, Mapping, Optional, Sequence, Union

from ._errors import SamplingError, ScenarioError
from .perception import load_sighting, serve_perception
from .serve import serve

try:  # `from ._core import` first: unlike `from . import _core`, it raises ModuleNotFoundError
    from ._core import (Scenario, Scene, SceneObject, dimensions, positions, quaternions,
                        yaw_pitch_roll)
    from . import _core
    _BUILT = True
except ModuleNotFoundError as missing:
    if missing.name != f"{__name__}._core":
        raise  # something the compiled module needs (numpy) is missing: say that
    _BUILT = False

__version__ = "0.1.0"
__all__ = [
    "load", "loads", "Scenario", "Scene", "SceneObject", "ScenarioError", "SamplingError",
    "positions", "dimensions", "quaternions", "yaw_pitch_roll", "search", "report", "campaign",
    "read_scenes", "test", "estimate", "dataset", "serve", "serve_perception", "load_sighting",
]

PathLike = Union[str, "os.PathLike[str]"]
ParamValue = Union[int, float, str]


def load(path: PathLike, params: Optional[Mapping[str, ParamValue]] = None,
         search_path: Optional[Sequence[PathLike]] = None, *, max_attempts: int = 10_000,
         naive: bool = False, stable: Union[bool, float, None] = None,
         stable_move: float = 0.01, stable_turn: float = 5.0,
         settle: Union[bool, float, None] = None, sampler: str = "rejection") -> Scenario:
    """Compiles the scenario in the file ``path``.

    Args:
        path: The ``.prs`` file. Its own directory is searched first for imported modules.
        params: Overrides of the scenario's ``param`` values, as ``prs -p NAME=VALUE``: numbers,
            or strings (a string that reads as a number becomes that number, as on the command
            line). A name the scenario does not declare is an error.
        search_path: Further directories searched for ``from NAME import *``; the directories
            in the environment variable ``PRS_PATH`` follow them, as for ``prs``.
        max_attempts: Attempts per scene before sampling fails (``prs --max-attempts``).
        naive: Sample positions from the workspace and check the specifiers afterwards (the
            paper's baseline, ``prs --naive``); the scenes differ from the default mode's.
        stable: Keep only scenes whose free bodies stay put under gravity (``prs --stable``):
            ``True`` simulates 1 s, a number that many seconds (at least 0.2, the least time
            in which a body can be found at rest); a scene in which a body moves more than
            ``stable_move`` metres or turns more than ``stable_turn`` degrees is rejected as
            "unstable" (docs/physics.md).
        settle: Let the free bodies fall and come to rest, and give the scenes as they end
            (``prs --settle``): ``True`` allows 4 s of simulated time to find rest, a number
            that many seconds (at least 0.5: rest is judged over the last 0.5 s, then confirmed
            for 1 s from standstill); a scene not at rest by then, with an object outside the
            workspace, or breaking a ``require settled``, is rejected as "unsettled"
            (docs/physics.md). Not with ``stable``.
        sampler: ``"rejection"`` (exact, the default), ``"partial-rejection"`` (``prs --sampler
            partial-rejection``: exact, independent scenes of clutter, objects that only must not
            overlap, by partial rejection sampling) or ``"gibbs"`` (``prs --sampler gibbs``):
            scenes from a Markov chain over the scene coordinates, for clutter whole-scene
            rejection cannot reach; they are correlated (``Scenario.gibbs`` says how much, once
            scenes were drawn; docs/sampling.md).

    Raises:
        ScenarioError: The file cannot be read or the program has errors; the exception carries
            the first error's message, id, file, line and column, and every error's text.
    """
    return _core.compile_file(os.fspath(path),
                              _load_options(params, search_path, max_attempts, naive,
                                            stable, stable_move, stable_turn, settle, sampler))


def loads(text: str, params: Optional[Mapping[str, ParamValue]] = None,
          search_path: Optional[Sequence[PathLike]] = None, *, name: str = "<string>",
          max_attempts: int = 10_000, naive: bool = False,
          stable: Union[bool, float, None] = None, stable_move: float = 0.01,
          stable_turn: float = 5.0, settle: Union[bool, float, None] = None,
          sampler: str = "rejection") -> Scenario:
    """Compiles scenario source text; ``name`` names it in messages and anchors its imports.

    The other arguments and the errors are those of :func:`load`.
    """
    return _core.compile_text(text, name,
                              _load_options(params, search_path, max_attempts, naive,
                                            stable, stable_move, stable_turn, settle, sampler))


def _param_text(name: str, value: ParamValue) -> str:
    if isinstance(value, str):
        return value
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"param {name!r}: expected a number or a string, "
                        f"got {type(value).__name__}")
    if isinstance(value, numbers.Integral):
        return str(int(value))
    return repr(float(value))  # the shortest text that reads back as the same float


def _seconds(name: str, value, default: float) -> float:
    """stable= or settle=: True for the default, else a number of seconds above 0."""
    if value is True:
        return default
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not value > 0:
        raise ValueError(f"{name} must be True or a number of seconds above 0, got {value!r}")
    return float(value)


def _load_options(params, search_path, max_attempts, naive, stable=None, stable_move=0.01,
                  stable_turn=5.0, settle=None, sampler="rejection") -> "_core.LoadOptions":
    options = _core.LoadOptions()
    options.params = [(str(k), _param_text(str(k), v)) for k, v in (params or {}).items()]
    dirs = [os.fspath(d) for d in (search_path or [])]
    dirs += [d for d in os.environ.get("PRS_PATH", "").split(":") if d]
    options.search_path = dirs
    options.max_attempts = max_attempts
    options.naive = naive
    if stable is not None and stable is not False:
        options.stable_s = _seconds("stable", stable, 1.0)
        options.stable_move_m = float(stable_move)
        options.stable_turn_deg = float(stable_turn)
    if settle is not None and settle is not False:
        options.settle_s = _seconds("settle", settle, 4.0)
    if sampler not in ("rejection", "partial-rejection", "gibbs"):
        raise ValueError(
            f"sampler must be 'rejection', 'partial-rejection' or 'gibbs', got {sampler!r}")
    options.sampler = sampler
    return options


def _scenes(self: Scenario, seed: int = 0, start: int = 0, count: Optional[int] = None,
            threads: Optional[int] = 1) -> Iterator[Scene]:
    """Iterates over scenes ``start``, ``start + 1``, ... of ``seed``, forever unless ``count``.

    With ``threads=1`` (the default) each scene is sampled when it is asked for. With more
    threads (``None``: all), scenes are sampled ahead in batches of 64 per thread by
    :meth:`sample_batch`; the scenes are the same either way.
    """
    if count is not None and count < 0:
        raise ValueError(f"count must be >= 0, got {count}")
    end = None if count is None else start + count
    index = start
    if threads == 1:
        while end is None or index < end:
            yield self.sample(seed, index)
            index += 1
        return
    chunk = 64 * (threads or os.cpu_count() or 1)
    while end is None or index < end:
        n = chunk if end is None else min(chunk, end - index)
        yield from self.sample_batch(n, seed=seed, start=index, threads=threads)
        index += n


if _BUILT:
    Scenario.scenes = _scenes


def search(scenario: Scenario, controller, budget: int, strategy: str = "ce", seed: int = 0,
           batch: Optional[int] = None) -> List[Dict[str, Any]]:
    """Searches for scenes where ``controller`` fails, as ``prs search`` (docs/search.md).

    ``controller(scene)`` returns an outcome name (``"success"``, ``"no-path"``, ...) or a dict
    with ``"outcome"`` and optionally ``"detail"``, ``"score"`` (a finite number: larger is
    safer, 0 or less a failure; the search descends it) and anything else (the record's
    ``"extra"``). ``strategy`` is ``"ce"`` (cross-entropy), ``"anneal"`` or ``"random"``
    (i.i.d., the baseline). Every scene the controller sees satisfies the whole scenario.
    Returns the records as dicts, as ``prs search -o`` writes them (each with the scene's
    ``"coordinates"`` and ``"features"``); pass them to :func:`report`.
    """
    return scenario.search(controller, budget, strategy=strategy, seed=seed, batch=batch)


def estimate(scenario: Scenario, controller, budget: int, seed: int = 0,
             threads: int = 1) -> Dict[str, Any]:
    """How often ``controller`` fails under the scenario's own law, with 95 % intervals, as
    ``prs estimate`` (docs/search.md): a cross-entropy adaptation toward failures, then
    importance sampling from a defensive mixture.

    ``controller`` is a function of a Scene as for :func:`search` (it runs on this thread), or
    a built-in controller's name (run on ``threads`` threads). Returns a dict: ``"episodes"``
    (weighted), ``"ess"``, ``"reliable"`` (False when the weights degenerate or the proposal
    misses where the controller nearly fails: then do not use the numbers, and
    ``"unreliable_because"`` says why), ``"estimates"`` (per failure outcome: ``"p"``,
    ``"ci95"``, ``"ess"``,
    ``"failing_episodes"``, ``"iid_episodes_for_same_precision"``), ``"upper_bound_95"`` when
    nothing failed, and ``"records"`` (as ``prs estimate -o`` writes them). ValueError for a
    budget under 200 or an unknown controller name.
    """
    return scenario.estimate(controller, budget, seed=seed, threads=threads)


def report(records: Union[PathLike, Iterable[Mapping[str, Any]]]) -> str:
    """A failure report in Markdown, as ``prs report`` prints it: what separates failures from
    successes, a depth-2 tree, failure modes with a representative each, error tables.

    ``records`` is a JSON Lines file of episode records (``prs test -o``, ``prs search -o``) or
    the records themselves (e.g. what :func:`search` returned). Raises ValueError naming the
    line of a record that is not one.
    """
    if isinstance(records, (str, os.PathLike)):
        path = os.fspath(records)
        with open(path, encoding="utf-8") as f:
            return _core.report_markdown(f.read().splitlines(), path)
    return _core.report_markdown([json.dumps(r) for r in records], "<records>")


def read_scenes(path: PathLike) -> List[Scene]:
    """The scenes of a scenes file (``prs sample -o``, a ``--save-failures`` file), or of every
    ``*.json``/``*.jsonl`` file in a directory (then in seed and index order), as ``Scene``s
    that export, render and pass to controllers like sampled ones, as ``prs test PATH`` reads
    them. A Scene read back knows its objects' class names but not the classes' ancestry.

    Raises:
        ValueError: ``"PATH:LINE: what is wrong"`` for a line that is not a scene, or when
            there is no scene at all.
    """
    path = os.fspath(path)
    if os.path.isdir(path):
        files = sorted(os.path.join(path, f) for f in os.listdir(path)
                       if f.endswith((".json", ".jsonl", ".ndjson"))
                       and os.path.isfile(os.path.join(path, f)))
    else:
        files = [path]
    scenes: List[Scene] = []
    for file in files:
        with open(file, encoding="utf-8") as f:
            scenes += _core.read_scene_lines(f.read().splitlines(), file)
    if os.path.isdir(path):
        scenes.sort(key=lambda s: (s.seed, s.index))
    if not scenes:
        raise ValueError(f"{path} holds no scene")
    return scenes


def test(scenes: Union[PathLike, Iterable[Scene]], controller=None, *, exec: Optional[str] = None,
         persistent: bool = False, timeout: float = 60.0, startup_timeout: float = 120.0,
         threads: int = 1) -> List[Dict[str, Any]]:
    """Runs a controller in each of ``scenes`` (Scenes, or a path for :func:`read_scenes`), as
    ``prs test SCENES.jsonl`` does, and returns one record per scene (dicts, as ``prs test -o``
    writes them, each with its scene's seed and index), in the scenes' order.

    ``controller`` is a function of a Scene that returns an outcome name or a dict with
    ``"outcome"`` (and optionally ``"detail"``, ``"score"``, anything else), as for
    :func:`search` (it runs on one thread); or the name of a built-in controller
    (``"table-cube"``), run on ``threads`` threads. Or give ``exec``, a shell command
    (docs/harness.md), with ``persistent=True`` started once per thread (``--persistent``,
    ``startup_timeout`` seconds for its handshake) and ``timeout`` seconds per episode.

    Raises:
        ValueError: Not exactly one controller, or an unknown built-in name.
        RuntimeError: A persistent worker that cannot start (the message says why).
    """
    if isinstance(scenes, (str, os.PathLike)):
        scenes = read_scenes(scenes)
    return _core.test_scenes(list(scenes), controller, exec or "", persistent, float(timeout),
                             float(startup_timeout), threads)



def dataset(scenes: Union[PathLike, Iterable[Scene]], out: PathLike, *,
            cameras: Optional[Sequence[str]] = None, size: Optional[Sequence[int]] = None,
            format: str = "both", labels: Optional[Sequence[str]] = None,
            start: Optional[int] = None, threads: Optional[int] = None,
            classes: Optional[Scenario] = None, jpeg: bool = False) -> Dict[str, Any]:
    """Writes ``scenes`` (Scenes, or a path for :func:`read_scenes`) as a labelled dataset in
    ``out``, as ``prs dataset`` does (docs/dataset.md): BOP (RGB, depth, full and visible masks,
    poses in mm in OpenCV's camera frame, boxes, models) and COCO annotations, every mask exact.

    ``cameras``: the camera objects to look through (default: every camera object of the first
    scene); ``size``: ``(width, height)`` (default: each camera's aspect at 640 wide);
    ``format``: ``"bop"``, ``"coco"`` or ``"both"``; ``labels``: the classes labelled (default
    all); ``jpeg``: colour pictures as JPEG instead of PNG. Scene ``k`` makes the images of position ``start + k``, or of its own index when
    ``start`` is None (sampled scenes: then the files are those ``prs dataset`` writes for the
    same seed and indices). ``out`` is written as ``out.partial`` and renamed when complete.
    Objects are numbered (``obj_id``, ``category_id``) by their program's classes; scenes read
    from a file know only the classes they use, in order of appearance: give ``classes`` (the
    Scenario they were drawn from) to number them as that program's own dataset does.

    Returns a dict: ``dir``, ``images``, ``scenes``, ``cameras`` and ``seconds`` (time by stage).

    Raises:
        ValueError: An unknown camera or one without fovy_deg, aspect, near and far, a size
            under 16 pixels, an unknown format, a scene with nothing to label, or two scenes
            that would make the same images.
        RuntimeError: ``out`` holds anything, or a file cannot be written.
    """
    if isinstance(scenes, (str, os.PathLike)):
        scenes = read_scenes(scenes)
        start = 0 if start is None else start
    scenes = list(scenes)
    if format not in ("bop", "coco", "both"):
        raise ValueError(f"format must be 'bop', 'coco' or 'both', not {format!r}")
    width, height = (0, 0) if size is None else (int(size[0]), int(size[1]))
    if size is not None and (width < 16 or height < 16 or width > 8192 or height > 8192):
        raise ValueError("size: width and height must be from 16 to 8192 pixels")
    positions = ([s.index for s in scenes] if start is None
                 else [int(start) + k for k in range(len(scenes))])
    return _core.write_dataset(scenes, os.fspath(out), list(cameras or []), width, height,
                               format != "coco", format != "bop", bool(jpeg),
                               list(labels or []), positions,
                               threads or os.cpu_count() or 1,
                               classes._dataset_classes() if classes is not None else [])


if _BUILT:
    from . import campaign  # noqa: E402  (probrobscene.campaign.run: shards on a Dask cluster)
else:
    _PURE = ["serve", "serve_perception", "load_sighting", "ScenarioError", "SamplingError"]
    _NEEDS_CORE = set(__all__) - set(_PURE) | {"_core"}
    __all__[:] = _PURE  # in place: linters read the above
    del load, loads, search, report, read_scenes, test, estimate, dataset

    def __getattr__(name: str) -> Any:
        """The compiled API, asked for where it is not built: an ImportError that says so."""
        if name in _NEEDS_CORE:
            raise ImportError(f"probrobscene.{name}: the compiled module probrobscene._core is "
                              f"not built beside {os.path.dirname(__file__)} (build or install "
                              f"the package: docs/python.md); only probrobscene.serve and "
                              f"serve_perception work without it")
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

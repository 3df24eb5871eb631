# Type hints for the probrobscene package (the C++ extension _core and the Python wrapper).
import os
from typing import Any, Callable, Dict, Iterable, Iterator, List, Mapping, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

PathLike = Union[str, os.PathLike[str]]
ParamValue = Union[int, float, str]
FloatArray = npt.NDArray[np.float64]

class ScenarioError(Exception):
    message: str
    id: str
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    text: str
    def __init__(self, message: str, *, id: str = ..., file: Optional[str] = ...,
                 line: Optional[int] = ..., column: Optional[int] = ...,
                 text: Optional[str] = ...) -> None: ...

class SamplingError(ScenarioError): ...

class SceneObject:
    @property
    def name(self) -> Optional[str]: ...
    @property
    def display_name(self) -> str: ...
    @property
    def class_name(self) -> str: ...
    @property
    def position(self) -> FloatArray: ...  # (3,) metres, world frame
    @property
    def dimensions(self) -> FloatArray: ...  # (3,) width, length, height
    @property
    def quaternion(self) -> FloatArray: ...  # (4,) w, x, y, z
    @property
    def yaw_pitch_roll(self) -> FloatArray: ...  # (3,) radians
    @property
    def yaw(self) -> float: ...
    @property
    def pitch(self) -> float: ...
    @property
    def roll(self) -> float: ...
    @property
    def properties(self) -> Dict[str, Any]: ...

class Scene:
    @property
    def seed(self) -> int: ...
    @property
    def index(self) -> int: ...
    @property
    def attempts(self) -> int: ...
    @property
    def rejections(self) -> Dict[str, int]: ...
    @property
    def params(self) -> Dict[str, Any]: ...
    @property
    def objects(self) -> List[SceneObject]: ...
    def __getitem__(self, name: str) -> SceneObject: ...
    def __contains__(self, name: str) -> bool: ...
    def __len__(self) -> int: ...
    def to_json(self) -> str: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def export(self, format: str, path: str) -> None: ...  # 'mjcf', 'urdf', 'sdf', 'usda', 'gltf', 'glb'
    def render(self, path: str, width: int = 640, height: int = 480,
               view: str = "overview") -> None: ...  # PNG; view 'overview', 'top', 'front', 'camera:NAME'

class Scenario:
    @property
    def path(self) -> str: ...
    @property
    def max_attempts(self) -> int: ...
    @property
    def naive(self) -> bool: ...
    @property
    def stable(self) -> Optional[float]: ...
    @property
    def settle(self) -> Optional[float]: ...
    def sample(self, seed: int = 0, index: int = 0) -> Scene: ...
    def sample_batch(self, n: int, seed: int = 0, start: int = 0,
                     threads: Optional[int] = None) -> List[Scene]: ...
    def scenes(self, seed: int = 0, start: int = 0, count: Optional[int] = None,
               threads: Optional[int] = 1) -> Iterator[Scene]: ...
    def check(self, n: int = 20, seed: int = 0,
              threads: Optional[int] = None) -> Dict[str, Any]: ...
    def coordinates(self) -> List[Dict[str, Any]]: ...  # name, draw, file, line, column
    def estimate(self, controller: Union[Callable[[Scene], Union[str, Mapping[str, Any]]], str],
                 budget: int, seed: int = 0, threads: int = 1) -> Dict[str, Any]: ...
    def search(self, controller: Callable[[Scene], Union[str, Mapping[str, Any]]], budget: int,
               strategy: str = "ce", seed: int = 0,
               batch: Optional[int] = None) -> List[Dict[str, Any]]: ...

def load(path: PathLike, params: Optional[Mapping[str, ParamValue]] = None,
         search_path: Optional[Sequence[PathLike]] = None, *, max_attempts: int = 10000,
         naive: bool = False, stable: Union[bool, float, None] = None,
         stable_move: float = 0.01, stable_turn: float = 5.0,
         settle: Union[bool, float, None] = None) -> Scenario: ...
def loads(text: str, params: Optional[Mapping[str, ParamValue]] = None,
          search_path: Optional[Sequence[PathLike]] = None, *, name: str = "<string>",
          max_attempts: int = 10000, naive: bool = False,
          stable: Union[bool, float, None] = None, stable_move: float = 0.01,
          stable_turn: float = 5.0, settle: Union[bool, float, None] = None) -> Scenario: ...

def search(scenario: Scenario, controller: Callable[[Scene], Union[str, Mapping[str, Any]]],
           budget: int, strategy: str = "ce", seed: int = 0,
           batch: Optional[int] = None) -> List[Dict[str, Any]]: ...
def report(records: Union[PathLike, Iterable[Mapping[str, Any]]]) -> str: ...  # Markdown
def estimate(scenario: Scenario,
             controller: Union[Callable[[Scene], Union[str, Mapping[str, Any]]], str],
             budget: int, seed: int = 0, threads: int = 1) -> Dict[str, Any]: ...
def read_scenes(path: PathLike) -> List[Scene]: ...  # a scenes file, or a directory of them
def dataset(scenes: Union[PathLike, Iterable[Scene]], out: PathLike, *,
            cameras: Optional[Sequence[str]] = None, size: Optional[Sequence[int]] = None,
            format: str = "both", labels: Optional[Sequence[str]] = None,
            start: Optional[int] = None, threads: Optional[int] = None,
            classes: Optional[Scenario] = None, jpeg: bool = False) -> Dict[str, Any]: ...
def test(scenes: Union[PathLike, Iterable[Scene]],
         controller: Union[Callable[[Scene], Union[str, Mapping[str, Any]]], str, None] = None, *,
         exec: Optional[str] = None, persistent: bool = False, timeout: float = 60.0,
         startup_timeout: float = 120.0, threads: int = 1) -> List[Dict[str, Any]]: ...

# Your controller as a `prs test --exec` worker (serve.py; pure Python, works without _core).
def serve(controller: Callable[[Dict[str, Any]], Union[str, Mapping[str, Any]]], *,
          ready_extra: Optional[Mapping[str, Any]] = ...) -> None: ...

# A learned perception as a `prs test --perception` worker (perception.py; pure Python but for
# load_sighting, which needs numpy and Pillow).
def serve_perception(perceive: Callable[[Dict[str, Any]], Any], *,
                     ready_extra: Optional[Mapping[str, Any]] = ...) -> None: ...
def load_sighting(request: Mapping[str, Any]) -> Dict[str, Any]: ...

def positions(scenes: Iterable[Scene], name: str) -> FloatArray: ...  # (n, 3)
def dimensions(scenes: Iterable[Scene], name: str) -> FloatArray: ...  # (n, 3)
def quaternions(scenes: Iterable[Scene], name: str) -> FloatArray: ...  # (n, 4)
def yaw_pitch_roll(scenes: Iterable[Scene], name: str) -> FloatArray: ...  # (n, 3)

from . import campaign as campaign  # campaigns on a Dask cluster (campaign.py is typed itself)

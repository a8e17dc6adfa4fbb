# Type stubs of the partreg module (the compiled _partreg, re-exported by partreg/__init__.py).
# Point sets in: (N, 3) float64 or float32 arrays of any strides, an Open3D PointCloud or Vector3dVector, a list
# of [x, y, z] (PointsLike; copied once into the library). Arrays out: float64 (N, 3); int32 parts.
# Units and frames are in each docstring of the module itself (help(partreg.register)).
import os
from typing import Any, Optional, Protocol, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str
model_format_version: int

Float64Array = npt.NDArray[np.float64]
Int32Array = npt.NDArray[np.int32]
IndexArray = Union[npt.NDArray[np.int32], npt.NDArray[np.int64]]
PathLike = Union[str, os.PathLike[str]]

class _HasPoints(Protocol):
    """An Open3D PointCloud (or a partreg View): its `points` are taken."""
    @property
    def points(self) -> Any: ...

PointsLike = Union[npt.ArrayLike, _HasPoints]

class InputError(RuntimeError):
    """Bad data or a failing resource: missing file, NaN points, a model of another format version."""

class UsageError(ValueError):
    """A request that can never succeed as stated: unknown setting, wrong array shape or dtype."""

class Mesh:
    def __init__(self, vertices: PointsLike, faces: IndexArray) -> None: ...
    @property
    def vertices(self) -> Float64Array:
        """(V, 3) vertex positions."""
    @property
    def faces(self) -> Int32Array:
        """(F, 3) vertex indices."""
    @property
    def normals(self) -> Float64Array:
        """(V, 3) unit vertex normals, or (0, 3)."""

class Frame:
    name: str
    def __init__(self, name: str, position: Float64Array, rotation: Optional[Float64Array] = None) -> None: ...
    @property
    def position(self) -> Float64Array:
        """(3,) position, data units."""
    @property
    def rotation(self) -> Float64Array:
        """(3, 3) rotation; columns are the frame's axes."""

class ShapeSpace:
    name: str
    point_indices: list[int]
    beta: float
    total_variance: float
    @property
    def dimensions(self) -> int: ...
    @property
    def point_count(self) -> int: ...
    @property
    def canonical(self) -> Float64Array:
        """(M, 3) canonical points, normalised units."""
    @property
    def mean(self) -> Float64Array:
        """(3M,) mean weight field."""
    @property
    def basis(self) -> Float64Array:
        """(3M, q) weight fields of the principal directions."""
    @property
    def variances(self) -> Float64Array:
        """(q,) descending."""
    @property
    def kernel_mean(self) -> Float64Array: ...
    @property
    def kernel_basis(self) -> Float64Array: ...
    @property
    def training_latents(self) -> Float64Array:
        """(K, q)."""
    def explained_fraction(self) -> Float64Array: ...
    def weights(self, latent: Float64Array) -> Float64Array:
        """(M, 3) kernel weights W(x)."""
    def deformed(self, latent: Float64Array) -> Float64Array:
        """(M, 3) the shape at a latent, normalised units, canonical frame."""

class Model:
    category: str
    part_names: list[str]
    @property
    def has_parts(self) -> bool: ...
    @property
    def scale(self) -> float:
        """The canonical's bounding-box diagonal, data units."""
    @property
    def centre(self) -> Float64Array: ...
    @property
    def size(self) -> float | None:
        """The category's real size in metres (train size=...): observations in metres; None: data units."""
    @property
    def training_instances(self) -> list[str]: ...
    @property
    def canonical_name(self) -> str: ...
    @property
    def seam_weight(self) -> Optional[float]: ...
    @property
    def seam_weight_choice(self) -> str: ...
    @property
    def seam_weight_trials(self) -> dict[float, float]: ...
    @property
    def spaces(self) -> list[ShapeSpace]: ...
    @property
    def canonical(self) -> Float64Array:
        """(M, 3) normalised units."""
    @property
    def canonical_part(self) -> Int32Array: ...
    @property
    def mesh_vertex_part(self) -> Int32Array: ...
    @property
    def canonical_mesh(self) -> Mesh: ...
    def space(self, name: str) -> ShapeSpace: ...
    def to_data(self, points: PointsLike) -> Float64Array: ...
    def shape_at(self, latent: Float64Array, space: str = "holistic") -> Float64Array:
        """(M, 3) the space's canonical at a latent, data frame and units."""

class FitStatistics:
    mean: float
    p90: float
    mean_normalised: float
    p90_normalised: float
    strays: int

class SpaceFit:
    space: str
    @property
    def stop_reason(self) -> str: ...
    scale: float
    cost: float
    iterations: int
    seconds: float
    hypotheses: int
    score: float
    runner_up_score: float
    runner_up_shift: float
    latent_distance: float
    @property
    def latent(self) -> Float64Array: ...
    @property
    def T_observed_canonical(self) -> Float64Array:
        """(4, 4) canonical data frame -> observed frame."""

class HistoryStep:
    space: str
    cost: float
    seconds: float
    @property
    def latent(self) -> Float64Array: ...
    @property
    def T_observed_canonical(self) -> Float64Array: ...

class Refinement:
    """What the fit beyond the shape space did; movements are shares of the model's diagonal."""
    points: int
    observed: int
    matched: int
    noise: float
    outlier_weight: float
    width: float
    iterations: int
    seconds: float
    mean_movement: float
    max_movement: float
    @property
    def applied(self) -> bool: ...

class MixtureFinish:
    """Whether the space fits ended in a Gaussian mixture (noise above mixture_noise); shares of the diagonal."""
    applied: bool
    noise: float
    sigma: float

class TrustFigures:
    """What a registration says of itself without the truth; lengths are shares of the model's diagonal."""
    observed_rms: float
    inlier_share: float
    latent_distance: float
    refinement_movement: float
    pose_ambiguity: float
    seam_gap_mean: float
    seam_gap_max: float
    mesh_stretch: float
    scale: float
    scale_at_bound: bool
    free_space_violation: float | None

class RegistrationResult:
    figures: TrustFigures
    @property
    def verdict(self) -> str:
        """'good', 'doubtful' or 'failed' (docs/verdict.md)."""
    @property
    def reasons(self) -> list[str]: ...
    fits: list[SpaceFit]
    history: list[HistoryStep]
    fit: FitStatistics
    refinement: Refinement
    mixture: MixtureFinish
    seconds: float
    warm_score: float
    pose_score: float
    @property
    def variant(self) -> str: ...
    @property
    def start(self) -> str: ...
    @property
    def stage_seconds(self) -> dict[str, float]: ...
    @property
    def deformed(self) -> Float64Array:
        """(M, 3) deformed canonical points, observed frame, data units."""
    @property
    def part(self) -> Int32Array: ...
    def space_fit(self, name: str) -> SpaceFit: ...

class _CpdResult:
    sigma2: float
    iterations: int
    seconds: float
    @property
    def stop_reason(self) -> str: ...
    @property
    def moved(self) -> Float64Array: ...

class RigidCpdResult(_CpdResult):
    scale: float
    @property
    def rotation(self) -> Float64Array: ...
    @property
    def translation(self) -> Float64Array: ...
    @property
    def T_target_source(self) -> Float64Array: ...

class AffineCpdResult(_CpdResult):
    @property
    def linear(self) -> Float64Array: ...
    @property
    def translation(self) -> Float64Array: ...

class NonrigidCpdResult(_CpdResult):
    beta: float
    kernel_rank: int
    @property
    def weights(self) -> Float64Array: ...
    def apply(self, points: PointsLike) -> Float64Array: ...

class View:
    @property
    def points(self) -> Float64Array: ...
    @property
    def normals(self) -> Float64Array: ...
    @property
    def viewpoint(self) -> Float64Array: ...
    @property
    def direction(self) -> Float64Array: ...

def read_model(path: PathLike) -> Model: ...
def write_model(path: PathLike, model: Model) -> None: ...
def read_cloud(path: PathLike, mesh_samples: int = 3000, seed: int = 1) -> Float64Array: ...
def read_mesh(path: PathLike) -> Mesh: ...
def write_mesh(path: PathLike, mesh: Mesh, vertex_part: Optional[IndexArray] = None) -> None: ...
def write_cloud(path: PathLike, points: PointsLike, part: Optional[IndexArray] = None) -> None: ...
def read_frames(path: PathLike) -> list[Frame]: ...
def write_frames(path: PathLike, frames: Sequence[Frame]) -> None: ...
# The keywords are the training settings, generated from the library's one table of them (lambda_ for
# --lambda): training_defaults() lists every name with its default.
def train(dataset_dir: PathLike, *, labels: Optional[Union[PathLike, Sequence[PathLike]]] = None, canonical: Optional[str] = None,
          samples: int = 4000, seed: int = 1, threads: int = 0, **settings: Any) -> Model: ...
def training_defaults() -> dict[str, Any]: ...
def training_options() -> list[dict[str, Any]]: ...
# The keywords are the registration settings, generated from the library's one table of them:
# registration_defaults() lists every name with its default.
def register(model: Model, points: PointsLike, *, threads: int = 0,
             init: Optional[Union[RegistrationResult, Float64Array]] = None, **settings: Any) -> RegistrationResult: ...
def track(model: Model, frames: Sequence[PointsLike], *, threads: int = 0,
          init: Optional[Union[RegistrationResult, Float64Array]] = None, **settings: Any) -> list[RegistrationResult]: ...
def registration_defaults() -> dict[str, Any]: ...
def registration_options() -> list[dict[str, Any]]: ...
def deform_mesh(model: Model, result: RegistrationResult) -> Mesh: ...
def mesh_stretch(model: Model, result: RegistrationResult) -> float: ...
def deform_points(model: Model, result: RegistrationResult, points: PointsLike) -> Float64Array: ...
def transfer_frames(model: Model, result: RegistrationResult, frames: Sequence[Frame]) -> list[Frame]: ...
def cpd(source: PointsLike, target: PointsLike, mode: str = "nonrigid",
        **settings: Any) -> Union[RigidCpdResult, AffineCpdResult, NonrigidCpdResult]: ...
def sphere_directions(count: int = 42) -> list[Float64Array]: ...
def views(geometry: Union[Mesh, PointsLike], count: int = 42, width: int = 160, height: int = 120,
          fov_degrees: float = 45.0, margin: float = 1.1, threads: int = 0) -> list[View]: ...
def measure_errors(deformed: PointsLike, part: IndexArray, part_names: Sequence[str], truth: PointsLike,
                   diagonal: Optional[float] = None, truth_part: Optional[IndexArray] = None) -> dict[str, Any]: ...

# Grasps (docs/grasps.md).
class Gripper:
    max_aperture: float
    pad_size: float
    finger_depth: float
    friction: float
    relative_to_diagonal: bool
    def __init__(self, max_aperture: float, pad_size: float = 0.02, finger_depth: float = 0.04,
                 friction: float = 0.5, relative_to_diagonal: bool = False) -> None: ...

class Grasp:
    name: str
    part: str
    width: float
    quality: float
    def __init__(self, name: str, position: Float64Array, rotation: Float64Array, width: float,
                 part: str = "", quality: float = 0.0) -> None: ...
    @property
    def position(self) -> Float64Array:
        """(3,) midway between the contacts, data units."""
    @property
    def rotation(self) -> Float64Array:
        """(3, 3): columns closing axis x, pad axis y, approach z."""

def read_grasps(path: PathLike) -> tuple[list[Grasp], Optional[Gripper]]: ...
def write_grasps(path: PathLike, grasps: Sequence[Grasp], gripper: Optional[Gripper] = None) -> None: ...
def sample_grasps(vertices: Float64Array, faces: IndexArray, gripper: Gripper, count: int = 50,
                  seed: int = 1) -> list[Grasp]: ...
def check_grasps(vertices: Float64Array, faces: IndexArray, grasps: Sequence[Grasp],
                 gripper: Gripper) -> list[dict[str, Any]]: ...
def transfer_grasps(model: Model, result: RegistrationResult, grasps: Sequence[Grasp], gripper: Gripper,
                    observed: Optional[Float64Array] = None) -> list[Grasp]: ...
# Depth cameras (docs/camera.md): depth (H, W) metres or a file, intrinsics a dict or a JSON file.
def segment_depth(depth: Any, intrinsics: Any, *, mask: Any = None, pick: Optional[Sequence[float]] = None,
                  **settings: Any) -> dict[str, Any]: ...
def register_depth(model: Model, depth: Any, intrinsics: Any, *, mask: Any = None,
                   pick: Optional[Sequence[float]] = None, threads: int = 0,
                   **settings: Any) -> tuple[RegistrationResult, dict[str, Any]]: ...

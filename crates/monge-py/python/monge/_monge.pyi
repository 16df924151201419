"""Type stubs of the native module monge._monge (re-exported by ``monge``)."""

import os
from typing import Any, Dict, List, Literal, Optional, Tuple, Union, final

import numpy as np
import numpy.typing as npt

__version__: str

__all__ = [
    "__version__",
    "MongeError",
    "FileError",
    "DesignError",
    "ThetaError",
    "DegenerateError",
    "MeshError",
    "SmoothError",
    "FabricationError",
    "ScanError",
    "OptimiseError",
    "FarFromOriginWarning",
    "InexactWarning",
    "Design",
    "PatchesDesign",
    "TrimmedDesign",
    "Mesh",
    "generate",
    "info",
    "check",
    "smooth",
    "fabricate",
    "scan",
    "fit",
    "optimise_panels",
    "approximate",
    "target_points",
]

# Private aliases: names of the stub only, not of the module.
_Kind = Literal["circular", "conical"]
_PathLike = Union[str, "os.PathLike[str]"]
_Array = npt.NDArray[np.float64]

class MongeError(Exception):
    """Every error raised by monge; the message says what, where, by how much, and how to fix it."""

class FileError(MongeError):
    """A file cannot be found, read or written."""

class DesignError(MongeError):
    """A design is malformed or invalid: its guides, their start point and angle, its size (§3)."""

class ThetaError(DesignError):
    """θ is not finite, outside the admissible range of the guides (§3.2) or singular (θ = +90°)."""

class DegenerateError(MongeError):
    """The Gauss map degenerates: the mesh pinches, a curvature line is straight there, or the normal barely turns along a guide (§5.2)."""

class MeshError(MongeError):
    """A mesh (file or arrays) is not a regular row-major quad grid of finite points."""

class SmoothError(MongeError):
    """The cyclidic net (§4.4) cannot be built on the mesh."""

class FabricationError(MongeError):
    """Panels, beams or nodes (§6) cannot be built."""

class ScanError(MongeError):
    """A design-space scan (§4.3) cannot be run: bad values or parameter path."""

class OptimiseError(MongeError):
    """θ fitting (§4.7) or panel-size optimisation (§4.8) cannot be run."""

class FarFromOriginWarning(UserWarning):
    """The coordinates lie so far from the origin, compared with the design's size, that their rounding as f64 numbers can put the mesh's error above 1e-9 of its size: generate with base_point="start" (coordinates relative to the guides' start point), or model the design near the origin."""

class InexactWarning(UserWarning):
    """The mesh, measured as `check` measures it, has an error above the design's tolerance (1e-9 of its size by default); the message gives the error and its likely cause (folded faces, coordinates far from the origin, θ near the singular +90°)."""

@final
class Design:
    """A design (§3): two planar guide curves that meet at 90° and the angle θ."""

    theta_deg: float
    """θ in degrees (§3.1, §3.2); settable."""
    @property
    def mesh(self) -> _Kind:
        """The mesh ``generate`` builds by default (the file's ``"mesh"``)."""
    @property
    def source(self) -> Optional[str]:
        """The file the design was read from, or None."""
    @staticmethod
    def from_file(path: _PathLike) -> "Design":
        """Reads a design file, JSON or TOML by its extension (§3)."""
    @staticmethod
    def from_dict(d: Dict[str, Any]) -> "Design":
        """A design from the keys of a design file; numpy arrays accepted for lists."""
    def to_dict(self) -> Dict[str, Any]:
        """The design as a dict with the keys of a design file."""
    def to_file(self, path: _PathLike) -> None:
        """Writes the design file, pretty JSON or TOML by the extension, atomically."""

@final
class PatchesDesign:
    """A multi-patch design (§4.7), as ``monge approximate --patches``/``--tolerance``
    writes it and ``monge patches`` reads it (``approximate`` returns one for several patches)."""

    @property
    def theta_deg(self) -> List[float]:
        """θ of each patch in degrees, in design order."""
    def to_dict(self) -> Dict[str, Any]:
        """The design as a dict with the keys of a multi-patch design file (what ``fit`` takes)."""
    def to_file(self, path: _PathLike) -> None:
        """Writes the multi-patch design file, pretty JSON or TOML by the extension, atomically."""
    def __len__(self) -> int: ...

@final
class TrimmedDesign:
    """A design (or a multi-patch design) and the outline its mesh is cut by, as
    ``monge approximate`` writes a trimmed result and ``monge generate`` reads it
    (``approximate`` returns one where its result is trimmed)."""

    @staticmethod
    def from_file(path: _PathLike) -> "TrimmedDesign":
        """Reads a trimmed design file (the keys ``design`` and ``trim``), JSON or TOML."""
    def to_file(self, path: _PathLike) -> None:
        """Writes the trimmed design file, pretty JSON or TOML by the extension, atomically, as the command does."""
    @property
    def design(self) -> Union[Design, PatchesDesign]:
        """The design before trimming."""
    @property
    def outline(self) -> _Array:
        """(n, 3): the outline's corners in space, a polygon in a plane seen along its normal."""
    def mesh(self) -> Dict[str, Any]:
        """The mesh cut by the outline, as ``monge generate`` writes it: ``vertices``, ``faces`` (polygons), ``cut``, ``from``, ``mesh_faces``."""
    def __eq__(self, value: object, /) -> bool: ...

@final
class Mesh:
    """A generated mesh (§2.2, §2.3); arrays are read-only views of its memory."""

    @property
    def vertices(self) -> _Array:
        """(rows, cols, 3): vertex (i, j), i along guide_u, j along guide_v."""
    @property
    def normals(self) -> Optional[_Array]:
        """(rows, cols, 3) unit node axes, the Gauss map (circular meshes; None for conical)."""
    @property
    def face_normals(self) -> Optional[_Array]:
        """(rows − 1, cols − 1, 3) unit face normals of a conical mesh (None for circular)."""
    @property
    def faces(self) -> npt.NDArray[np.uint64]:
        """(faces, 4) indices into vertices.reshape(-1, 3), wound as in the OBJ/PLY files of ``monge generate``."""
    @property
    def rows(self) -> int: ...
    @property
    def cols(self) -> int: ...
    @property
    def kind(self) -> _Kind: ...
    @property
    def theta_deg(self) -> float: ...
    @property
    def mode(self) -> Literal["characteristic", "arbitrary"]: ...
    @property
    def offset_distance(self) -> float:
        """Distance from the generated mesh (0 for it)."""
    @property
    def base_point(self) -> Optional[Tuple[float, float, float]]:
        """The point the coordinates are relative to (generate's base_point), or None."""
    @property
    def report(self) -> Dict[str, Any]:
        """folded_faces, first_fold, min_crossing_sine, min_crossing_face (§5.2), max_error (as check).

        For an offset, folded_faces and first_fold are those check() finds on it.
        """
    def offset(self, d: float) -> "Mesh":
        """Node offset (circular, §2.2) or face offset (conical, §2.3) at distance d."""

def generate(
    design: Design,
    kind: Optional[_Kind] = None,
    max_vertices: int = 25000000,
    base_point: Union[Literal["start"], Tuple[float, float, float], None] = None,
) -> Mesh:
    """The circular (§2.2) or conical (§2.3) mesh of a design (§3).

    A grid of more than ``max_vertices`` vertices (default 25 000 000, about
    1.2 GB) is refused (DesignError) before anything is allocated.
    With ``base_point`` ("start", the guides' common start point, or (x, y, z))
    the mesh is computed and returned relative to that point
    (``Mesh.base_point``), exact far from the origin.
    """

def info(design: Design) -> Dict[str, Any]:
    """Mode, θ and its admissible range, grid size, guides (§3.1, §3.2)."""

def check(
    vertices: Union[Mesh, _PathLike, npt.ArrayLike],
    normals: Optional[npt.ArrayLike] = None,
    *,
    kind: Optional[_Kind] = None,
) -> Dict[str, Any]:
    """Independent measurements of a quad mesh (§2.2, §2.3) and its folded faces (§5.2), as ``monge check``."""

def smooth(
    design: Union[Design, Mesh],
    samples: int = 9,
    allow_folded: bool = False,
    max_bytes: float = 8e9,
) -> Dict[str, Any]:
    """The cyclidic net (§4.4): patches, curvature lines as arcs, one NURBS surface.

    Refused (SmoothError) for a design that asks for a conical mesh (as ``monge
    smooth``), for a mesh with folded faces (those ``check`` counts, §5.2; the
    first is named) unless ``allow_folded=True``, and before anything is built if the result would take more than
    ``max_bytes`` of memory (default 8e9, 8 GB).
    """

def fabricate(
    design: Design,
    layers: npt.ArrayLike = [0.0],
    tol: float = 1e-9,
    radius_tol: Optional[float] = None,
    angle_tol_deg: float = 1e-4,
    max_bytes: float = 8e9,
) -> Dict[str, Any]:
    """Layers, panels, beams, nodes and summary (§6), as ``monge fabricate``.

    Refused (FabricationError) before anything is built if the result would take
    more than ``max_bytes`` of memory (default 8e9, 8 GB; about 10 kB a face and layer).
    """

def scan(design: Design, values: npt.ArrayLike, param: str = "theta") -> Dict[str, Any]:
    """Design-space scan (§4.3) in parallel, GIL released; returns columns."""

def optimise_panels(
    design: Design, max_gap_ratio: float = 8.0, max_evaluations: Optional[int] = None
) -> Dict[str, Any]:
    """Panel-size optimisation (§4.8), as ``monge optimise-panels``."""

def fit(design: Union[_PathLike, Dict[str, Any]]) -> Dict[str, Any]:
    """Fit θ of a multi-patch design (§4.7), as ``monge fit``."""

def approximate(
    target: Union[npt.ArrayLike, _PathLike, Any],
    grid: Tuple[int, int] = (40, 40),
    kind: _Kind = "circular",
    starts: int = 4,
    max_evaluations: int = 1500,
    time_limit: Optional[float] = None,
    keep_boundary: bool = False,
    trim: bool = False,
    patches: Union[str, int, Tuple[int, int], None] = None,
    tolerance: Union[float, str, None] = None,
    max_patches: Optional[int] = None,
    angle_tol_deg: Optional[float] = None,
) -> Dict[str, Any]:
    """The design nearest to a target (points, a Rhino or COMPAS mesh, a Rhino surface or Brep, a file), as ``monge approximate``.

    ``patches`` ("2x3", 3 or (2, 3)) fits that many patches (§4.7) as ``--patches``;
    ``tolerance`` (5e-3 of the target's size, or "0.05m", "5cm", "50mm") fits up to
    ``max_patches`` (default 6) until within it, as ``--tolerance`` (on a scan, as far as
    its points tell its edge: ``stop`` is "scan_edge" where only that edge reads above it); its report's
    ``node_types`` group nodes whose angles agree within ``angle_tol_deg`` degrees (default 0.5);
    it is None, and ``node_types_why_not`` says why, when fabrication refuses the mesh found.
    ``design`` is a ``Design``, or a ``PatchesDesign`` of several patches; of a trimmed result, a ``TrimmedDesign`` (the command's file).
    ``trim=True`` (as ``--trim``) fits a mesh that covers the target and cuts it by the
    target's outline (with ``patches``, the patches cover it too and are cut where kept): ``trimmed`` holds its ``vertices``, ``faces`` (planar polygons),
    ``cut`` (per face, whether the outline cut it), ``from`` (per face, the grid's face
    ``(i, j)`` it was cut from) and ``mesh_faces`` (the faces as
    triangles and quads: each cut polygon split in its plane, for Rhino, Grasshopper and
    glTF); otherwise it is None. ``panels`` then counts its polygons.
    """

def target_points(target: Union[npt.ArrayLike, _PathLike, Any]) -> _Array:
    """The points ``approximate`` takes from a target, as an array (N, 3)."""

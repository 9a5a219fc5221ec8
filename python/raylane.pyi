# python: the module's type stubs, beside raylane*.so where installed (`pip install .`) and in the
# build folder; tests/python/test_stubs.py checks them against the module.
"""Raylane: scenes rendered to NumPy images, and ray queries against triangle meshes on the SIMD
packet path. See docs/python.md."""

from typing import Any, Literal, TypedDict

import numpy as np
from numpy.typing import NDArray

__version__: str

_Path = Literal["packet", "scalar"]
_Aov = Literal["color", "normal", "depth", "bvh-cost"]
_Isa = Literal["sse4.2", "avx2", "avx512"]
# ray arrays: float32 is read in place, other real or integer dtypes are converted once
_Floats = NDArray[np.floating[Any]] | NDArray[np.integer[Any]]

class _Hits(TypedDict):
    """Mesh.intersect's result, one entry per ray (and the arrays `out=` may hand it)."""

    t: NDArray[np.float32]  # (N,), inf on a miss
    prim: NDArray[np.int32]  # (N,) triangle index, -1 on a miss
    u: NDArray[np.float32]  # (N,) barycentric weight of the triangle's second corner
    v: NDArray[np.float32]  # (N,) barycentric weight of its third corner
    normal: NDArray[np.float32]  # (N, 3) unit geometric normal, 0 on a miss

class _InstructionSets(TypedDict):
    compiled: list[str]
    cpu: list[str]
    in_use: str
    packet_width: int

class Error(ValueError):
    """A malformed scene or model: the command line's one line (file, line or JSON path,
    reason)."""

class Scene:
    """A scene loaded by raylane.load_scene, with its BVHs (built once, at load)."""

    def render(
        self,
        spp: int = 0,
        threads: int = 0,
        path: _Path = "packet",
        aov: _Aov = "color",
        width: int = 0,
        height: int = 0,
        seed: int = 0,
    ) -> NDArray[np.float32]:
        """Renders the scene; returns float32 linear values, (H, W, 3) for color and normal,
        (H, W) for depth and bvh-cost, row 0 at the top: the pixels `raylane render -o
        FILE.pfm` writes with the same options (0 = the scene's own value)."""
    def compare(
        self,
        spp: int = 0,
        threads: int = 0,
        width: int = 0,
        height: int = 0,
        repeats: int = 3,
        tolerance: float = 2e-3,
        id_allowance: int = 0,
    ) -> dict[str, Any]:
        """Renders with both paths, as `raylane compare` does; returns its figures as a dict
        (scalar_ms, packet_ms, speedup, max_abs_diff, rmse, hit_id_mismatches, agree, ...)."""
    def info(self) -> dict[str, Any]:
        """The figures `raylane info` prints (scene contents, BVH statistics, memory, load and
        build time) as a dict."""
    @property
    def source(self) -> str:
        """The file the scene was loaded from."""
    @property
    def width(self) -> int:
        """The scene's own image width in pixels."""
    @property
    def height(self) -> int:
        """The scene's own image height in pixels."""
    @property
    def spp(self) -> int:
        """The scene's own samples per pixel."""

class Mesh:
    """A triangle mesh and its BVHs, for ray queries on the packet path (or the scalar path, the
    reference)."""

    def __init__(
        self, vertices: NDArray[np.float32], triangles: NDArray[np.integer[Any]]
    ) -> None:
        """Builds a mesh from an (N, 3) float32 array of vertices and an (M, 3) integer array of
        vertex indices (copied once; any strides)."""
    def intersect(
        self,
        origins: _Floats,
        directions: _Floats | None = None,
        tmax: float | NDArray[np.floating[Any]] = ...,
        *,
        path: _Path = "packet",
        coherent: bool | None = None,
        threads: int = 0,
        out: _Hits | dict[str, NDArray[Any]] | None = None,
    ) -> _Hits:
        """Closest hits in (0, tmax) of rays given as (N, 3) origins and directions, or one
        (N, 6) array; tmax (default inf) is a number or an (N,) array. Returns a dict of arrays:
        t (float32, inf on a miss), prim (int32 triangle index, -1 on a miss), u, v
        (barycentrics of the second and third corners), normal ((N, 3) unit geometric normal, 0
        on a miss). `out`: a dict of preallocated arrays with those keys, dtypes and shapes,
        filled and returned instead of new ones."""
    def occluded(
        self,
        origins: _Floats,
        directions: _Floats | None = None,
        tmax: float | NDArray[np.floating[Any]] = ...,
        *,
        path: _Path = "packet",
        coherent: bool | None = None,
        threads: int = 0,
        out: NDArray[np.bool_] | None = None,
    ) -> NDArray[np.bool_]:
        """Whether each ray hits anything in (0, tmax): an (N,) bool array (`out`, when given, a
        preallocated one, filled and returned)."""
    @property
    def vertices(self) -> NDArray[np.float32]:
        """(N, 3) float32 copy of the vertices"""
    @property
    def triangles(self) -> NDArray[np.int32]:
        """(M, 3) int32 copy of the indices"""
    @property
    def triangle_count(self) -> int:
        """The number of triangles."""
    @property
    def build_ms(self) -> float:
        """milliseconds taken to build the BVHs"""

def load_scene(path: str) -> Scene:
    """Loads a JSON scene or a model file (.obj, .ply: the model's own scene) as `raylane
    render` does; models named by a scene are looked up beside it, then on
    RAYLANE_MODEL_PATH."""

def load_mesh(path: str) -> Mesh:
    """Loads an OBJ or PLY model (.obj, .ply, optionally .gz) as a Mesh; a relative name that is
    not a file is looked up on RAYLANE_MODEL_PATH. Zero-area faces are dropped, as when a scene
    loads the model."""

def save_rays(path: str, origins: _Floats, directions: _Floats | None = None) -> None:
    """Writes rays as an (N, 6) float32 .npy file (origin, direction), the ray file of
    `bench_intersect --rays FILE`."""

def instruction_sets() -> _InstructionSets:
    """The packet path's instruction sets: 'compiled' (in this module), 'cpu' (those this CPU
    runs), 'in_use' (RAYLANE_ISA's, or use_isa's, else the widest) and its 'packet_width'."""

def use_isa(name: _Isa) -> None:
    """Uses the instruction set `name` ('sse4.2', 'avx2' or 'avx512') from now on;
    raylane.Error (a ValueError) when it is unknown or this CPU does not run it."""

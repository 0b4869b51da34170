"""The Mesh object mesh() returns: arrays, save(), report()."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..nodes.base import Node
from .lattice import Lattice

if TYPE_CHECKING:  # pragma: no cover - imported where report() runs
    from .printing import PrintReport
    from .report import MeshReport


@dataclass(eq=False)
class Mesh:
    """A triangle mesh of a scene's solid, as ``sg.mesh(scene, ...)`` returns it.

    Attributes:
        vertices: float64 (N, 3) positions in scene units, projected onto the surface.
        faces: int64 (M, 3) vertex indices, counter-clockwise seen from outside.
        normals: float64 (N, 3) unit field gradients at the vertices.
        colors: float32 (N, 3) the scene's colour field at the vertices (linear 0..1), or
            None when meshed with ``colors=False``.
        scene: the node it was meshed from; lattice: the sampling lattice (``step`` is its
            cell size); mode: "mc" (marching cubes) or "sharp" (dual contouring).
        timings: seconds per stage (``extract_s``, ``project_s``: summed over the passes of
            a refined mesh; ``simplify_s``: an adaptive mesh's simplification and splits; ``total_s``: all of it, estimates included).
        samples: field samples the extraction took (every pass).
        default_step: with no size given, the default step the mesher refined from because
            the volume was estimated off by more than 0.25 % there; None otherwise.
        tolerance: the ``tolerance`` an adaptive mesh was made within (None: uniform);
        error: for an adaptive mesh, the largest |f| at its vertices and distance from its
            face centres to the surface, measured on the GPU (float32).

    ``save(path)`` writes STL/OBJ/PLY/glTF/3MF by suffix, ``to_trimesh()`` hands it to
    trimesh, ``report()`` measures it against the field.

    Example:
        >>> m = sg.mesh(sg.sphere(1), resolution=8)
        >>> m.faces.shape[1], m.faces.dtype.name, m.vertices.shape == m.normals.shape
        (3, 'int64', True)
        >>> bool(abs((m.vertices ** 2).sum(axis=1) ** 0.5 - 1).max() < 1e-3)  # on the unit sphere
        True
    """

    vertices: np.ndarray
    faces: np.ndarray
    normals: np.ndarray
    colors: np.ndarray | None = None
    scene: Node | None = None
    lattice: Lattice | None = None
    mode: str = "mc"
    timings: dict[str, float] = field(default_factory=dict)
    samples: int = 0  # lattice samples it took (the dense lattice has lattice.samples)
    default_step: float | None = None
    tolerance: float | None = None
    error: float | None = None

    def __repr__(self) -> str:
        return f"Mesh({len(self.vertices)} vertices, {len(self.faces)} triangles, mode={self.mode!r})"

    @property
    def step(self) -> float:
        """The lattice cell size the mesh was extracted at."""
        return self.lattice.step if self.lattice is not None else float("nan")

    def to_trimesh(self) -> Any:
        """A ``trimesh.Trimesh`` of this mesh (vertex colours included)."""
        from .deps import require
        trimesh = require("trimesh")
        vc = None if self.colors is None else np.clip(np.round(self.colors * 255), 0, 255).astype(np.uint8)
        return trimesh.Trimesh(self.vertices, self.faces, vertex_normals=self.normals, vertex_colors=vc,
                               process=False, validate=False)

    def save(self, path: str | Path, **options: Any) -> Path:
        """Write the mesh; the format comes from the suffix: .stl (binary), .obj (+ .mtl with
        one material per colour), .ply (vertex colours), .glb / .gltf (vertex colours), .3mf
        (one object with a base material per colour; ``units="mm"`` etc. names what a scene
        unit is, default millimetres). Several parts in one file: :func:`sdfgl.save_3mf`."""
        from .writers import write
        return write(self, Path(path), **options)

    def report(self, twin_samples: int = 20000, volume_resolution: int = 48) -> MeshReport:
        """Accuracy of the mesh against the float64 twin (see :class:`sdfgl.mesh.report.MeshReport`)."""
        from .report import measure
        return measure(self, twin_samples, volume_resolution)

    def print_report(self, min_wall: float | None = None, overhang: float = 45.0, density: float | None = None,
                     units: str = "millimeter", up: object = "z") -> PrintReport:
        """Printing checks (see :class:`sdfgl.mesh.printing.PrintReport`): bounding box and
        volume in ``units`` (scene units taken as that unit), mass in grams for a ``density``
        in g/cm^3, the area facing down more than ``overhang`` degrees from vertical (``up``
        is the build direction), and with ``min_wall`` the thinnest wall below it and where."""
        from .printing import measure_print
        return measure_print(self, min_wall, overhang, density, units, up)

"""Printing checks of a mesh: size, volume and mass, overhangs, and walls too thin to print.

- bounding box and volume of the mesh, in the chosen unit (scene coordinates are taken as
  that unit, as the 3MF writer takes them); mass for a density in g/cm^3;
- overhang area: the summed area of the triangles that face down and lie more than
  ``overhang`` degrees from vertical (a box's bottom face lies 90 degrees from vertical),
  also without those on the build plate (the lowest layer, where the part rests);
- thin walls: inside a wall of thickness t the field is above -t/2, so its ridge (the
  medial surface, where the nearest surface switches from one side to the other) tells the
  thickness. The float64 twin is sampled on a grid of spacing ``min_wall / 4`` over the
  mesh's box (coarser when that would pass MAX_WALL_SAMPLES; the report gives the spacing);
  a sample inside the solid is a ridge sample along an axis when its |f| is not below its
  two neighbours' on that axis and the field gradients there point apart (more than 120
  degrees: two facing surfaces, not the two faces of an edge). Each neighbour's nearest
  surface point is ``q - f(q) grad f(q)``; the wall thickness is the distance of the two
  points along the wall's normal, exact for flat walls and for the walls' rims alike.
  The thinnest wall below ``min_wall`` is reported with where it is (its mid-point).
  Walls thinner than about the grid spacing may fall between the samples.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from ..errors import ParameterError
from ..values.axes import direction
from ..values.units import MILLIMETRES, SYMBOLS, unit_name
from .geometry import volume
from .report import Twin

MAX_WALL_SAMPLES = 1 << 22
"""The most field samples the thin-wall search takes (2^22, as the default mesh)."""
OPPOSED = -0.5
"""Cosine below which the gradients at a ridge sample's two neighbours count as facing walls."""


@dataclass
class PrintReport:
    """Figures a slicer would ask about, in ``units`` (lengths), ``units``^2 and ``units``^3.

    ``mass`` is in grams (None without a density); ``thinnest`` / ``thinnest_at`` are the
    thickness and the mid-point of the thinnest wall below ``min_wall`` (None when there is
    none, or when no ``min_wall`` was asked for); ``thin_samples`` counts the ridge samples
    thinner than ``min_wall``; ``wall_step`` is the spacing the walls were sampled at.
    """

    units: str
    bbox_min: tuple[float, float, float]
    bbox_max: tuple[float, float, float]
    volume: float
    density: float | None
    mass: float | None
    overhang: float
    overhang_area: float
    overhang_area_off_bed: float
    min_wall: float | None
    thinnest: float | None
    thinnest_at: tuple[float, float, float] | None
    thin_samples: int
    wall_step: float | None

    @property
    def size(self) -> tuple[float, float, float]:
        """The bounding box's extent along x, y, z."""
        return tuple(float(b - a) for a, b in zip(self.bbox_min, self.bbox_max))  # type: ignore[return-value]

    def as_dict(self) -> dict:
        """The figures as a plain dict (with ``size``)."""
        return {**asdict(self), "size": self.size}

    def __str__(self) -> str:
        u = SYMBOLS[self.units]
        size = " x ".join(f"{s:.4g}" for s in self.size)
        text = f"size {size} {u}; volume {self.volume:.6g} {u}^3"
        if self.mass is not None:
            text += f", mass {self.mass:.4g} g at {self.density:g} g/cm^3"
        text += (f"; overhang past {self.overhang:g} deg from vertical {self.overhang_area:.4g} {u}^2 "
                 f"({self.overhang_area_off_bed:.4g} {u}^2 off the build plate)")
        if self.min_wall is not None:
            if self.thinnest is None:
                text += f"; no wall thinner than {self.min_wall:g} {u}"
            else:
                at = ", ".join(f"{c:.4g}" for c in self.thinnest_at)  # type: ignore[union-attr]
                text += (f"; THIN WALL: {self.thinnest:.3g} {u} at ({at}), thinner than {self.min_wall:g} {u} "
                         f"at {self.thin_samples} samples (spacing {self.wall_step:.3g} {u})")
        return text


def measure_print(mesh, min_wall: float | None = None, overhang: float = 45.0, density: float | None = None,  # noqa: ANN001
                  units: str = "millimeter", up: object = "z") -> PrintReport:
    """The :class:`PrintReport` of ``mesh`` (see the module docstring)."""
    unit = unit_name(units, "print_report: parameter 'units'")
    if not (isinstance(overhang, (int, float)) and 0 <= overhang <= 90):
        raise ParameterError(f"print_report: parameter 'overhang' must be an angle in [0, 90] degrees, got {overhang!r}")
    if density is not None and not (isinstance(density, (int, float)) and density > 0):
        raise ParameterError(f"print_report: parameter 'density' must be > 0 (g/cm^3), got {density!r}")
    if min_wall is not None and not (isinstance(min_wall, (int, float)) and min_wall > 0 and np.isfinite(min_wall)):
        raise ParameterError(f"print_report: parameter 'min_wall' must be a length > 0, got {min_wall!r}")
    if len(mesh.faces) == 0:
        raise ParameterError("print_report: the mesh is empty")
    if min_wall is not None and (mesh.scene is None or mesh.lattice is None):
        raise ParameterError("print_report: 'min_wall' reads the scene's field, and this mesh has no scene "
                             "(mesh it with sg.mesh)")
    up_dir = direction("print_report", "up", up)
    up_dir = up_dir / np.linalg.norm(up_dir)
    V, F = mesh.vertices, mesh.faces
    vol = volume(V, F)
    cm = MILLIMETRES[unit] / 10.0
    mass = None if density is None else vol * cm ** 3 * float(density)
    area, area_off_bed = overhang_areas(V, F, up_dir, float(overhang), mesh.step)
    thinnest = at = step = None
    count = 0
    if min_wall is not None:
        thinnest, at, count, step = thin_walls(Twin(mesh.scene, mesh.lattice.box), float(min_wall))
    return PrintReport(unit, tuple(map(float, V.min(axis=0))), tuple(map(float, V.max(axis=0))), vol,
                       None if density is None else float(density), mass, float(overhang), area, area_off_bed,
                       None if min_wall is None else float(min_wall), thinnest, at, count, step)


def overhang_areas(V: np.ndarray, F: np.ndarray, up: np.ndarray, angle: float, step: float) -> tuple[float, float]:
    """(area of the faces facing down more than ``angle`` degrees from vertical, the same
    without the faces lying on the build plate: within half a ``step`` of the lowest point)."""
    tri = V[F]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    twice = np.linalg.norm(cross, axis=1)
    down = -(cross @ up) / np.maximum(twice, 1e-300)  # sine of the face's tilt from vertical, downward faces > 0
    tilt = np.degrees(np.arcsin(np.clip(down, -1.0, 1.0)))
    over = (down > 1e-9) & (tilt >= angle - 1e-9)
    height = tri @ up
    tol = 0.5 * step if np.isfinite(step) else 1e-6 * float(np.ptp(height))
    on_bed = height.max(axis=1) <= height.min() + tol
    return float(twice[over].sum() / 2), float(twice[over & ~on_bed].sum() / 2)


def thin_walls(twin: Twin, min_wall: float, batch: int = 1 << 18
               ) -> tuple[float | None, tuple[float, float, float] | None, int, float]:
    """(thinnest wall below ``min_wall`` or None, its mid-point, ridge samples below
    ``min_wall``, the sample spacing) of the twin's solid (see the module docstring)."""
    lo, hi = twin.lo, twin.hi
    extent = hi - lo
    h = max(min_wall / 4, float(np.prod(extent) / MAX_WALL_SAMPLES) ** (1 / 3))
    n = np.maximum(np.ceil(extent / h).astype(int) + 1, 3)
    axes = [lo[i] + np.arange(n[i]) * h for i in range(3)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)
    f = np.concatenate([twin(grid[i:i + batch]) for i in range(0, len(grid), batch)]).reshape(*n)
    found_t, found_at = [], []
    for axis in range(3):
        lo_s, mid, hi_s = [slice(None)] * 3, [slice(None)] * 3, [slice(None)] * 3
        lo_s[axis], mid[axis], hi_s[axis] = slice(0, -2), slice(1, -1), slice(2, None)
        a, b, c = f[tuple(lo_s)], f[tuple(mid)], f[tuple(hi_s)]
        ridge = (b < 0) & (b <= a) & (b <= c) & (b > -min_wall / 2)
        idx = np.argwhere(ridge)
        if len(idx) == 0:
            continue
        idx[:, axis] += 1
        p = lo + idx * h
        e = np.zeros(3)
        e[axis] = h
        feet, normals = [], []
        for q in (p - e, p + e):
            g = twin.gradient(q, 1e-3 * h)
            g /= np.maximum(np.linalg.norm(g, axis=1, keepdims=True), 1e-300)
            feet.append(q - twin(q)[:, None] * g)
            normals.append(g)
        facing = np.einsum("ij,ij->i", normals[0], normals[1]) < OPPOSED
        across = normals[1] - normals[0]
        across /= np.maximum(np.linalg.norm(across, axis=1, keepdims=True), 1e-300)
        thickness = np.einsum("ij,ij->i", feet[1] - feet[0], across)
        keep = facing & (thickness < min_wall)
        found_t.append(thickness[keep])
        found_at.append(((feet[0] + feet[1]) / 2)[keep])
    t = np.concatenate(found_t) if found_t else np.zeros(0)
    if len(t) == 0:
        return None, None, 0, h
    i = int(np.argmin(t))
    at = np.concatenate(found_at)[i]
    return float(t[i]), (float(at[0]), float(at[1]), float(at[2])), len(t), h

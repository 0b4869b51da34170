"""The accuracy report of a mesh, held against the float64 twin.

- |field| at the vertices (max, p99), in units and in cells: the twin of the clipped field;
- Hausdorff distance both ways: mesh -> surface is |f| / |grad f| at points sampled on the
  triangles, surface -> mesh is the distance from points put on the twin's surface (Newton
  steps from seeds spread over the box and the mesh) to the nearest triangle;
- volume of the mesh against the twin's integration (adaptive: cells the surface may cross,
  by the Lipschitz bound, are refined three times from a ``volume_resolution``^3 grid);
- topology: every edge on exactly two faces (watertight), no directed edge twice (winding).
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from .geometry import distance_to_mesh, sample_surface, volume
from .topology import edge_use


@dataclass
class MeshReport:
    vertices: int
    faces: int
    step: float
    max_field: float          # max |f| at vertices (units)
    p99_field: float
    hausdorff_mesh_to_surface: float
    hausdorff_surface_to_mesh: float
    volume: float             # of the mesh
    twin_volume: float        # the twin's integration
    watertight: bool
    winding_consistent: bool
    time_s: float

    @property
    def hausdorff(self) -> float:
        return max(self.hausdorff_mesh_to_surface, self.hausdorff_surface_to_mesh)

    @property
    def volume_error(self) -> float:
        """Relative volume difference to the twin."""
        return abs(self.volume - self.twin_volume) / max(abs(self.twin_volume), 1e-300)

    def as_dict(self) -> dict:
        return {**asdict(self), "hausdorff": self.hausdorff, "volume_error": self.volume_error}

    def __str__(self) -> str:
        h = self.step
        return (f"{self.vertices} vertices, {self.faces} triangles, cell {h:.4g}; |f| at vertices max "
                f"{self.max_field:.2e} ({self.max_field / h:.3f} cell), p99 {self.p99_field:.2e} "
                f"({self.p99_field / h:.3f} cell); Hausdorff {self.hausdorff:.2e} ({self.hausdorff / h:.3f} cell: "
                f"mesh->surface {self.hausdorff_mesh_to_surface / h:.3f}, surface->mesh "
                f"{self.hausdorff_surface_to_mesh / h:.3f}); volume {self.volume:.6g} vs twin {self.twin_volume:.6g} "
                f"({100 * self.volume_error:.3f} %); {'watertight' if self.watertight else 'NOT watertight'}, "
                f"{'winding consistent' if self.winding_consistent else 'winding NOT consistent'}")


class Twin:
    """The float64 twin of the mesh's field: the scene cut by the sampling box."""

    def __init__(self, scene, box: tuple[np.ndarray, np.ndarray]) -> None:  # noqa: ANN001
        self.scene, self.lo, self.hi = scene, box[0], box[1]

    def __call__(self, p: np.ndarray) -> np.ndarray:
        c, half = (self.lo + self.hi) / 2, (self.hi - self.lo) / 2
        q = np.abs(p - c) - half
        box = np.linalg.norm(np.maximum(q, 0), axis=-1) + np.minimum(q.max(axis=-1), 0)
        return np.maximum(self.scene.distance(p), box)

    def gradient(self, p: np.ndarray, eps: float) -> np.ndarray:
        e = np.eye(3) * eps
        return np.stack([(self(p + e[i]) - self(p - e[i])) / (2 * eps) for i in range(3)], axis=-1)

    def to_surface(self, p: np.ndarray, step: float, iterations: int = 12) -> np.ndarray:
        """Newton steps along the gradient; points that do not converge are dropped."""
        p = p.copy()
        for _ in range(iterations):
            f = self(p)
            g = self.gradient(p, 1e-3 * step)
            gg = np.maximum(np.einsum("ij,ij->i", g, g), 1e-24)
            d = (f / gg)[:, None] * g
            n = np.linalg.norm(d, axis=1, keepdims=True)
            p -= d * np.minimum(1.0, 4 * step / np.maximum(n, 1e-300))
        return p[np.abs(self(p)) < 1e-6 * step]

    def integrate(self, resolution: int = 48, levels: int = 3, batch: int = 1 << 18) -> float:
        """Volume of {f < 0}, adaptively: ``resolution``^3 cells, of which those the surface may
        pass through are halved ``levels`` times (effective ``resolution * 2**levels``).

        A cell is settled by the sign at its centre when |f| there exceeds twice the field's
        Lipschitz factor times the cell's half-diagonal (no surface can reach into it; the factor
        2 covers warps whose stated factor is optimistic). Fields without a finite factor
        (implicit ones) use twice the largest gradient seen on the first grid. Cells still open
        at the finest level count the inside share of a plane at f / |grad f| from the centre
        (a one-cell linear ramp), so non-distance fields are not biased by their gradient norm.
        """
        n = resolution
        h = (self.hi - self.lo) / n
        axes = [self.lo[i] + (np.arange(n) + 0.5) * h[i] for i in range(3)]
        centres = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)
        f = np.concatenate([self(centres[i:i + batch]) for i in range(0, len(centres), batch)])
        lip = float(self.scene.lipschitz)
        if not np.isfinite(lip):
            g = np.abs(np.diff(f.reshape(n, n, n), axis=0)).max() / h[0], \
                np.abs(np.diff(f.reshape(n, n, n), axis=1)).max() / h[1], \
                np.abs(np.diff(f.reshape(n, n, n), axis=2)).max() / h[2]
            lip = float(np.linalg.norm(g))
        lip = 2.0 * max(lip, 1.0)
        total = 0.0
        offsets = (np.array([[i & 1, i >> 1 & 1, i >> 2 & 1] for i in range(8)]) - 0.5) / 2
        for level in range(levels + 1):
            cell = float(np.prod(h))
            open_ = np.abs(f) < lip * 0.5 * float(np.linalg.norm(h))
            total += cell * float(np.count_nonzero((f < 0) & ~open_))
            centres = centres[open_]
            if level == levels:
                break
            centres = (centres[:, None, :] + offsets * h).reshape(-1, 3)
            h = h / 2
            f = np.concatenate([self(centres[i:i + batch]) for i in range(0, len(centres), batch)])
        width = float(np.linalg.norm(h)) / np.sqrt(3)
        f = f[open_]
        for i in range(0, len(centres), batch):
            p, fp = centres[i:i + batch], f[i:i + batch]
            g = np.linalg.norm(self.gradient(p, 1e-2 * width), axis=1)
            total += cell * float(np.clip(0.5 - fp / np.maximum(g, 1e-12) / width, 0, 1).sum())
        return total


def measure(mesh, twin_samples: int = 20000, volume_resolution: int = 48, seed: int = 0) -> MeshReport:  # noqa: ANN001
    """The report of ``mesh`` (see the module docstring)."""
    import time
    t0 = time.perf_counter()
    rng = np.random.default_rng(seed)
    twin = Twin(mesh.scene, mesh.lattice.box)
    h = mesh.step
    V, F = mesh.vertices, mesh.faces
    fv = np.abs(twin(V))
    on_mesh = sample_surface(V, F, twin_samples, rng)
    g = np.linalg.norm(twin.gradient(on_mesh, 1e-3 * h), axis=1)
    m2s = float(np.max(np.abs(twin(on_mesh)) / np.maximum(g, 1e-12)))
    lo, hi = mesh.lattice.box
    seeds = np.concatenate([lo + rng.random((twin_samples, 3)) * (hi - lo),
                            on_mesh + rng.normal(scale=h, size=on_mesh.shape)])
    surf = twin.to_surface(seeds, h)
    s2m = float(distance_to_mesh(surf, V, F).max()) if len(surf) else float("nan")
    counts, twice = edge_use(F)
    return MeshReport(len(V), len(F), h, float(fv.max()), float(np.percentile(fv, 99)), m2s, s2m, volume(V, F),
                      twin.integrate(volume_resolution), bool(np.all(counts == 2)), twice == 0,
                      time.perf_counter() - t0)

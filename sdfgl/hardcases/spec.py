"""What a hard case is: a named scene and camera, and the bounds its render must meet."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from ..camera import Camera
from ..nodes.base import Node
from ..reference import ErrorReport


@dataclass(frozen=True)
class Expect:
    """Bounds a render must meet against the reference (fractions as named)."""

    false_frac: float = 0.002       # false hits / reference hits (rays that miss every surface)
    lost_frac: float = 0.001        # reference hits the render missed / pixels
    outlier_frac: float = 0.01      # depth outliers (> 2 footprints apart: another surface) / pixels
    depth_px_median: float = 0.02   # |t - t*| in pixel footprints, where both hit the same surface
    depth_px_p99: float = 0.25
    surface_px_max: float = 0.5     # every hit within this many footprints of a sign change of the twin
    normal_deg_median: float = 0.1
    normal_deg_p99: float = 1.0
    min_hits: int = 1               # the case must actually show geometry
    max_hits: int | None = None     # for scenes that must show nothing

    def violations(self, e: ErrorReport) -> list[str]:
        """Human-readable list of the bounds ``e`` breaks (empty when it passes)."""
        out = []
        checks = [("false-hit share", e.false_hits / max(e.hits, 1), self.false_frac),
                  ("lost-hit share", e.lost_hits / e.pixels, self.lost_frac),
                  ("depth-outlier share", e.depth_outliers / e.pixels, self.outlier_frac),
                  ("depth median (px)", e.depth_px_median, self.depth_px_median),
                  ("depth p99 (px)", e.depth_px_p99, self.depth_px_p99),
                  ("hit-to-surface max (px)", e.surface_px_max, self.surface_px_max),
                  ("normal median (deg)", e.normal_deg_median, self.normal_deg_median),
                  ("normal p99 (deg)", e.normal_deg_p99, self.normal_deg_p99)]
        out += [f"{name} {val:.4g} > {lim:.4g}" for name, val, lim in checks if val > lim]
        if e.nan_count:
            out.append(f"{e.nan_count} NaN/Inf values")
        if e.hits < self.min_hits:
            out.append(f"only {e.hits} reference hits (< {self.min_hits})")
        if self.max_hits is not None and e.false_hits + e.hits > self.max_hits:
            out.append(f"{e.false_hits + e.hits} hits where at most {self.max_hits} belong")
        return out


@dataclass(frozen=True)
class HardCase:
    name: str
    what: str                       # the difficulty, in a sentence
    build: Callable[[], tuple[Node, Camera]]
    settings: dict = field(default_factory=dict)
    expect: Expect = Expect()
    max_dist: float = 1000.0
    failing: str = ""               # a known failure, said plainly: the case stays in the suite

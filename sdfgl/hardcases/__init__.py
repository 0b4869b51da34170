"""Hard cases for numerical stability: each a named scene, camera and expected behaviour.

The tests hold the default renderer to each case's bounds against the float64
reference; the benchmark reuses the same cases to put speed beside error.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..reference import ErrorReport
from .base import BASE_CASES
from .bounds import BOUNDS_CASES
from .marching import MARCHING_CASES
from .precision import PRECISION_CASES
from .spec import Expect, HardCase

if TYPE_CHECKING:  # pragma: no cover
    from ..render import RenderResult

__all__ = ["CASES", "Expect", "HardCase", "case", "run_case", "table", "document"]

CASES: tuple[HardCase, ...] = BASE_CASES + MARCHING_CASES + PRECISION_CASES + BOUNDS_CASES
_REFERENCES: dict[tuple, object] = {}  # (case, size, max_dist) -> its float64 reference trace


def case(name: str) -> HardCase:
    """The hard case called ``name``."""
    for c in CASES:
        if c.name == name:
            return c
    raise KeyError(f"no hard case '{name}'; known: {', '.join(c.name for c in CASES)}")


def run_case(c: HardCase, size: tuple[int, int] = (64, 48), surface: bool = True,
             **settings: object) -> tuple[ErrorReport, "RenderResult"]:
    """Render ``c`` (shadows and AO off: only primary rays matter) and compare with the reference;
    ``surface=False`` leaves out the hit-to-surface offsets (they search the twin along every hit ray)."""
    from dataclasses import replace

    from ..reference import compare, surface_offsets, trace
    from ..render import render
    scene, cam = c.build()
    opts = {"shadows": False, "ao": False, "max_dist": c.max_dist, **c.settings, **settings}
    res = render(scene, cam, size, outputs=("color", "depth", "normal", "steps"), **opts)
    key = (c.name, tuple(size), c.max_dist)
    ref = _REFERENCES.get(key)
    if ref is None:  # the reference does not depend on the render's settings: traced once a size
        ref = _REFERENCES[key] = trace(scene, cam, size, max_dist=c.max_dist)
    err = compare(res, ref)
    if not surface:
        return err, res
    off = surface_offsets(scene, cam, res)
    if off.size:
        err = replace(err, surface_px_p99=float(np.percentile(off, 99, method="higher")), surface_px_max=float(off.max()))
    else:
        err = replace(err, surface_px_p99=0.0, surface_px_max=0.0)
    return err, res


def table(size: tuple[int, int] = (128, 96), **settings: object) -> str:
    """A markdown table of every hard case's errors for the given settings."""
    rows = ["| case | hits | undecided | false / lost | depth outliers | depth med / p99 / max (px) | hit-to-surface max (px) "
            "| normal med / p99 / max (deg) | NaN | mean steps | bounds met |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    for c in CASES:
        e, res = run_case(c, size, **settings)
        bad = c.expect.violations(e)
        status = "yes" if not bad else ("FAILING: " if c.failing else "no: ") + "; ".join(bad)
        rows.append(f"| {c.name} | {e.hits} | {e.undecided} | {e.false_hits} / {e.lost_hits} | {e.depth_outliers} | "
                    f"{e.depth_px_median:.2g} / {e.depth_px_p99:.2g} / {e.depth_px_max:.2g} | {e.surface_px_max:.2g} | "
                    f"{e.normal_deg_median:.2g} / {e.normal_deg_p99:.2g} / {e.normal_deg_max:.2g} | {e.nan_count} | "
                    f"{float(res.steps.mean()):.1f} | {status} |")
    return "\n".join(rows)


def document(size: tuple[int, int] = (128, 96)) -> str:
    """docs/hardcases.md: what each case tests, its known failure if any, and the table."""
    lines = ["# The hard cases", "",
             f"Every case of `sdfgl.hardcases` against the float64 reference at {size[0]}x{size[1]}, default "
             "settings, shadows and AO off (`python -m sdfgl.hardcases "
             f"{size[0]}x{size[1]} --doc docs/hardcases.md`). Depth and normal figures are over pixels where "
             "render and reference hit; a false hit is a render hit where every ray of the reference misses; "
             "hit-to-surface is the distance along the ray from each render hit to the nearest sign change of "
             "the twin. Undecided rays (left out of every figure) are rays the reference could not settle, or "
             "that dip below f = 0 by less than float32 rounding and come out again (see sdfgl.reference). "
             "The tests run the same cases at 64x48 and hold each to its bounds; a case marked "
             "failing stays in the suite as an expected failure.", "", "| case | what it tests | known failure |",
             "|---|---|---|"]
    lines += [f"| {c.name} | {c.what} | {c.failing or '-'} |" for c in CASES]
    return "\n".join(lines + ["", table(size), ""])

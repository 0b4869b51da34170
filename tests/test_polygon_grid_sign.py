"""The sign of polygons kept as an edge grid, held to an independent point-in-polygon test
(a winding number written here), on outlines whose coordinates put cell centres on edges."""
import numpy as np
import pytest

import sdfgl as sg
from sdfgl.evaluate import evaluate


def _winding_inside(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    wn = np.zeros(len(q), dtype=int)
    for (ax, ay), (bx, by) in zip(v, np.roll(v, -1, axis=0)):
        cross = (bx - ax) * (q[:, 1] - ay) - (q[:, 0] - ax) * (by - ay)
        wn += ((ay <= q[:, 1]) & (by > q[:, 1]) & (cross > 0)).astype(int)
        wn -= ((ay > q[:, 1]) & (by <= q[:, 1]) & (cross < 0)).astype(int)
    return wn != 0


def _comb(teeth: int, width: float, height: float) -> np.ndarray:
    """A comb on round coordinates: a base strip 2 high and ``teeth`` teeth half a unit wide."""
    pts = [(0.0, 0.0), (width, 0.0), (width, 2.0)]
    for j in range(teeth, 0, -1):
        pts += [(j + 0.5, 2.0), (j + 0.5, height), (j, height), (j, 2.0)]
    return np.array(pts + [(0.0, 2.0)])


def _floor_plan(rng: np.random.Generator, n: int) -> np.ndarray:
    """A rectilinear outline on the integer grid: a staircase up and a staircase back."""
    steps = rng.integers(1, 4, size=(n, 2))
    up = np.cumsum(steps, axis=0)
    pts = [(0, 0)]
    for x, y in up:
        pts += [(x, pts[-1][1]), (x, y)]
    top = pts[-1][1] + 3
    pts += [(pts[-1][0], top), (0, top)]
    return np.array(pts, dtype=float)


@pytest.mark.parametrize("shape", ["comb_cells_on_edges", "comb_off_grid", "floor_plan"])
def test_edge_grid_sign_agrees_with_an_independent_winding_number(shape):
    rng = np.random.default_rng(11)
    v = {"comb_cells_on_edges": lambda: _comb(63, 64.0, 64.0),  # 256 vertices over 64 x 64: 4-unit cells
         "comb_off_grid": lambda: _comb(60, 64.0, 61.0),
         "floor_plan": lambda: _floor_plan(rng, 60)}[shape]()
    poly = sg.polygon(v)
    assert poly.grid is not None  # kept as an edge grid
    lo, hi = v.min(axis=0), v.max(axis=0)
    q = rng.uniform(lo - 1, hi + 1, size=(200000, 2))
    d = evaluate(sg.extrude(poly, 1.0), np.c_[q, np.zeros(len(q))])
    clear = np.abs(d) > 1e-3 * float((hi - lo).max())  # away from the outline, where float32 cannot tell
    wrong = ((d < 0) != _winding_inside(q, v)) & clear
    assert wrong.sum() == 0, f"{wrong.mean():.2%} of the area has the wrong sign"


def test_edge_grid_compiles_as_glsl_es_300(renderer):
    from sdfgl.compiler.generate import generate
    from sdfgl.settings import Settings
    src = generate(sg.extrude(sg.polygon(_comb(63, 64.0, 64.0) / 32.0), 0.2), Settings(), dialect="webgl2")
    assert "sdPolygonGrid" in src.text
    renderer.programs.get(src)


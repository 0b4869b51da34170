"""GPU (generated GLSL, float32) against the numpy float64 twin, and Lipschitz factors.

Tolerance: |gpu - twin| <= 16 * eps32 * (1 + |p|_inf + |d|), i.e. float32 rounding
of the coordinates and of the value, with room for a few operations' worth of error.
"""
import zlib

import numpy as np
import pytest

import sdfgl as sg

from .nodes_zoo import all_nodes, probe_points, random_scene

EPS32 = float(np.finfo(np.float32).eps)


def assert_parity(node: sg.Node, pts: np.ndarray, renderer) -> float:
    gpu = sg.evaluate(node, pts, renderer=renderer).astype(np.float64)
    ref = node.distance(pts)
    tol = 16 * EPS32 * (1 + np.abs(pts).max(axis=-1) + np.abs(ref))
    err = np.abs(gpu - ref)
    worst = int(np.argmax(err / tol))
    assert np.all(err <= tol), (f"{node.label()}: |gpu - twin| = {err[worst]:.3g} at {pts[worst]} "
                                f"(gpu {gpu[worst]:.9g}, twin {ref[worst]:.9g}, tol {tol[worst]:.3g})")
    return float(err.max())


@pytest.mark.parametrize("name", sorted(all_nodes()))
def test_gpu_matches_twin(renderer, name):
    node = all_nodes()[name]
    rng = np.random.default_rng(zlib.crc32(name.encode()))  # the same points in every process
    for where, pts in probe_points(node, rng).items():
        if len(pts):
            assert_parity(node, pts, renderer)


def test_random_compositions_match_twin(renderer):
    rng = np.random.default_rng(7)
    for _ in range(25):
        node = random_scene(rng)
        pts = np.concatenate(list(probe_points(node, rng, 1500).values()))
        assert_parity(node, pts, renderer)


def test_parity_far_from_origin_with_shifted_origin(renderer):
    c = np.array([1e5, -3e4, 2e5])
    node = (sg.box(1) - sg.sphere(0.6)).translate(c)
    pts = c + np.random.default_rng(3).uniform(-1, 1, (3000, 3))
    gpu = sg.evaluate(node, pts, origin=c, renderer=renderer).astype(np.float64)
    assert np.abs(gpu - node.distance(pts)).max() < 1e-6  # float32 relative to the origin, not 1e5


def test_evaluate_shapes_and_errors(renderer):
    s = sg.sphere(1)
    assert sg.evaluate(s, np.zeros((2, 5, 3)), renderer=renderer).shape == (2, 5)
    assert sg.evaluate(s, np.zeros((0, 3)), renderer=renderer).shape == (0,)
    with pytest.raises(sg.ParameterError, match="points must be finite"):
        sg.evaluate(s, [[np.nan, 0, 0]], renderer=renderer)


def _warp_boundary(node: sg.Node, p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Pairs that straddle a warp node's inside-box wall, where the two bounds meet with a jump."""
    lo, hi = getattr(node, "box_lo", None), getattr(node, "box_hi", None)
    if lo is None:
        return np.zeros(len(p), dtype=bool)
    ip = np.all((p >= lo) & (p <= hi), axis=-1)
    iq = np.all((q >= lo) & (q <= hi), axis=-1)
    return ip != iq


@pytest.mark.parametrize("name", sorted(all_nodes()))
def test_field_never_exceeds_its_lipschitz_factor(name):
    node = all_nodes()[name]
    rng = np.random.default_rng(11)
    lo, hi = node.bounds
    lo = np.where(np.isfinite(lo), lo, -3.0)
    hi = np.where(np.isfinite(hi), hi, 3.0)
    p = rng.uniform(lo - 1, hi + 1, size=(40000, 3))
    step = rng.normal(size=p.shape)
    step *= (10 ** rng.uniform(-4, -1, size=(len(p), 1))) / np.linalg.norm(step, axis=-1, keepdims=True)
    q = p + step
    keep = ~_warp_boundary(node, p, q)
    ratio = np.abs(node.distance(p) - node.distance(q))[keep] / np.linalg.norm(step, axis=-1)[keep]
    assert ratio.max() <= node.lipschitz * (1 + 1e-6), f"{name}: slope {ratio.max():.6f} > L = {node.lipschitz}"
    if node.exactness == sg.EXACT:  # an exact field has slope 1 almost everywhere outside
        assert ratio.max() > 0.99


def test_warps_divide_by_their_own_stretch_only():
    tw = sg.box((0.6, 1.6, 0.4)).twist(90)
    assert tw.stretch > 1.0 and tw.lipschitz == 1.0
    # a union with a plain sphere keeps the sphere's code unscaled
    src = sg.compile(tw | sg.sphere(0.3).translate((2, 0, 0)), shadows=False, ao=False)
    body = src.split("float map(vec3 p) {")[1].split("\n}")[0]
    assert body.count(sg.compiler.source.glsl_float(1 / tw.stretch)) == 1

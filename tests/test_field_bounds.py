"""Bounds that hold the solid for every combiner, on random trees, and the noise's bounds.

The solid points are found with the float64 twin on dense samples of a box well beyond each
tree's bounds; a single solid point outside the bounds fails."""
import itertools

import numpy as np
import pytest

import sdfgl as sg
from sdfgl.noise import NOISE_LIPSCHITZ, NOISE_MAX, fbm3, fbm_max, noise3

BLENDS = ("quadratic", "circular", "chamfer")


def _leaf(rng: np.random.Generator) -> sg.Node:
    kind = rng.integers(4)
    r = float(rng.uniform(0.1, 0.5))
    leaf = (sg.sphere(r), sg.box(2 * r), sg.ellipsoid((r, r / 2, r * 1.5)), sg.torus(r, r / 3))[kind]
    return leaf.translate(tuple(rng.uniform(-0.8, 0.8, 3)))


def _tree(rng: np.random.Generator, depth: int) -> sg.Node:
    if depth == 0:
        return _leaf(rng)
    op = rng.integers(7)
    if op <= 2:  # smooth unions of a few to many children, large radii (metaballs) included
        kids = [_tree(rng, depth - 1) for _ in range(int(rng.integers(2, 7)))]
        return sg.union(*kids, k=float(rng.choice([0.05, 0.3, 1.0, 2.5])), blend=str(rng.choice(BLENDS)))
    child = _tree(rng, depth - 1)
    if op == 3:
        return child.round(float(rng.uniform(0.02, 0.4)))
    if op == 4:
        return child.scale(tuple(rng.uniform(0.3, 2.5, 3)))
    if op == 5:
        return child.rotate(float(rng.uniform(0, 360)), tuple(rng.normal(size=3))).shell(0.05)
    return sg.displace(child, float(rng.uniform(0.02, 0.2)), float(rng.uniform(1, 6)), 2)


def _solid_outside(node: sg.Node, rng: np.random.Generator, n: int = 60000) -> int:
    lo, hi = node.bounds
    span = hi - lo
    pts = rng.uniform(lo - span - 1.0, hi + span + 1.0, size=(n, 3))
    solid = node.distance(pts) < 0
    held = np.all((pts >= lo - 1e-9) & (pts <= hi + 1e-9), axis=1)
    return int((solid & ~held).sum())


@pytest.mark.parametrize("seed", range(24))
def test_random_trees_keep_every_solid_point_in_their_bounds(seed):
    rng = np.random.default_rng(seed)
    node = _tree(rng, int(rng.integers(1, 4)))
    assert _solid_outside(node, rng) == 0, node.label()


@pytest.mark.parametrize("blend", BLENDS)
def test_a_blend_of_many_coincident_spheres_grows_by_every_fold(blend):
    # each fold lowers the running value again: three spheres at one place with k = 2 reach
    # well past one k/4 (a single fold's reach)
    node = sg.union(*[sg.sphere(0.3) for _ in range(3)], k=2.0, blend=blend)
    reach = max(float(r) for r in np.linspace(0, 4, 4001) if node.distance([[r, 0, 0]])[0] < 0)
    assert reach > 0.3 + 2.0 * sg.nodes.booleans.BLEND_REACH[blend]  # more than one fold's growth
    assert node.bounds[1][0] >= reach


def test_scattered_blends_grow_by_little_more_than_one_fold():
    rng = np.random.default_rng(3)
    balls = [sg.sphere(0.05).translate(tuple(c)) for c in rng.uniform(-5, 5, (400, 3))]
    node = sg.union(*balls, k=0.1)
    lo, hi = node.bounds
    centres = np.array([b.offset for b in balls])
    assert np.all(hi <= centres.max(axis=0) + 0.05 + 3 * 0.025 + 1e-9)  # not 399 folds of k/4


def test_offset_of_a_non_uniform_scale_holds_its_solid():
    node = sg.sphere(1).scale((4, 1, 1)).round(1)  # f = |p / s| - 1 scaled by 1: solid to x = 8
    assert node.distance([[7.9, 0, 0]])[0] < 0
    assert node.bounds[1][0] >= 8.0


def test_noise_gradient_bound_is_the_supremum_over_every_corner_pattern():
    # grad n(f) = sum_c A_c(f) g_c is linear in the corner gradients g_c in {-1, 1}^3, so its
    # largest norm over the 8^8 patterns is max over unit u of sum_c |A_c(f)^T u|_1
    def fade(t):
        return t * t * t * (t * (t * 6 - 15) + 10)

    def dfade(t):
        return 30 * t * t * (t - 1) ** 2

    grid = np.linspace(0.0, 0.5, 11)  # the cube's symmetries map every point into [0, 1/2]^3
    f = np.array([p for p in itertools.product(grid, repeat=3) if p[0] <= p[1] <= p[2]])
    i = np.arange(1500) + 0.5
    phi, th = np.arccos(1 - 2 * i / len(i)), np.pi * (1 + 5 ** 0.5) * i
    u = np.stack([np.cos(th) * np.sin(phi), np.sin(th) * np.sin(phi), np.cos(phi)], -1)
    u = np.vstack([u, np.eye(3)])  # the axes, where the largest slope lies
    w1, dw1 = np.stack([1 - fade(f), fade(f)], -1), np.stack([-dfade(f), dfade(f)], -1)
    total = np.zeros((len(f), len(u)))
    for o in itertools.product((0, 1), repeat=3):
        wx, wy, wz = (w1[:, a, o[a]] for a in range(3))
        grad_w = np.stack([dw1[:, 0, o[0]] * wy * wz, wx * dw1[:, 1, o[1]] * wz, wx * wy * dw1[:, 2, o[2]]], -1)
        a_c = (wx * wy * wz)[:, None, None] * np.eye(3) + grad_w[:, :, None] * (f - np.array(o))[:, None, :]
        total += np.abs(np.einsum("mij,ki->mkj", a_c, u)).sum(-1)
    assert total.max() <= NOISE_LIPSCHITZ * (1 + 1e-12)
    assert total.max() == pytest.approx(NOISE_LIPSCHITZ, rel=1e-9)  # attained at the centre: no slack


def test_noise_never_exceeds_its_value_and_slope_bounds_on_samples():
    rng = np.random.default_rng(7)
    p = rng.uniform(-50, 50, (200000, 3))
    assert np.abs(noise3(p)).max() <= NOISE_MAX
    assert np.abs(fbm3(p, 4)).max() <= fbm_max(4)
    h = 1e-6
    d = rng.normal(size=(len(p), 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    slope = np.abs(noise3(p + h * d) - noise3(p - h * d)) / (2 * h)
    assert slope.max() <= NOISE_LIPSCHITZ
    centre = np.floor(p[:4]) + 0.5  # the value bound is reached at a cell centre for some patterns
    assert np.abs(noise3(centre)).max() <= NOISE_MAX

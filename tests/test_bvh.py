"""The bounding volume hierarchy over a big union (setting grid="bvh", sdfgl/compiler/data/bvh.py):
the measured alternative to the cell grid draws the same scene."""
import numpy as np
import pytest

import sdfgl as sg
from sdfgl import bench_big
from sdfgl.compiler.data import bvh


def test_every_instance_is_in_one_leaf_inside_its_boxes():
    s, _ = bench_big.mixed(150, seed=3)
    tree = bvh.of(s.grid)
    leaves = np.concatenate(tree.leaves)
    assert sorted(leaves.tolist()) == list(range(len(s.grid.children)))
    assert max(len(leaf) for leaf in tree.leaves) <= bvh.LEAF and tree.depth < bvh.STACK

    def box(k):  # the box over a subtree's instances
        if k < 0:
            idx = tree.leaves[-1 - k]
            return s.grid.los[idx].min(axis=0), s.grid.his[idx].max(axis=0)
        a, b = box(tree.nodes[k][2]), box(tree.nodes[k][5])
        return np.minimum(a[0], b[0]), np.maximum(a[1], b[1])
    for lo_a, hi_a, a, lo_b, hi_b, b in tree.nodes:
        for lo, hi, k in ((lo_a, hi_a, a), (lo_b, hi_b, b)):
            blo, bhi = box(k)
            assert np.all(lo <= blo) and np.all(hi >= bhi)


def test_bvh_draws_what_the_grid_draws_with_shadows_and_ao(renderer):
    s, cam = bench_big.mixed(60, seed=1)
    a = renderer.render(s, cam, (64, 48), outputs=("color", "depth", "steps"), shadows="soft", ao=True)
    b = renderer.render(s, cam, (64, 48), outputs=("color", "depth", "steps"), shadows="soft", ao=True, grid="bvh")
    assert "Children(" in sg.compile(s, grid="bvh") and "Children(" not in sg.compile(s)
    hit_a, hit_b = np.isfinite(a.depth), np.isfinite(b.depth)
    assert hit_a.mean() > 0.05 and np.mean(hit_a != hit_b) < 0.005
    both = hit_a & hit_b
    assert np.median(np.abs(a.depth[both] - b.depth[both])) < 1e-3
    assert np.mean(np.abs(a.color.astype(float) - b.color.astype(float)).max(axis=-1) > 24) < 0.01
    assert b.steps.mean() <= a.steps.mean()  # no cap inside the scene: steps of the exact union


def test_grid_setting_names_its_values():
    with pytest.raises(sg.ParameterError, match="setting 'grid' must be True or False or 'bvh'"):
        sg.compile(sg.sphere(1), grid="octree")

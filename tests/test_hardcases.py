"""The hard-case suite: the default renderer against the float64 reference on each case."""
import numpy as np
import pytest

from sdfgl.hardcases import CASES, run_case


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_hard_case_within_bounds(case):
    err, res = run_case(case, (64, 48))
    assert err.nan_count == 0
    assert not np.isnan(res.depth).any() and np.isfinite(res.normal).all()
    problems = case.expect.violations(err)
    assert not problems, f"{case.name}: {problems}\n{err}"


def test_camera_inside_solid_hits_at_zero():
    case = next(c for c in CASES if c.name == "camera_inside")
    err, res = run_case(case, (16, 12))
    assert np.all(res.depth == 0.0)
    assert np.allclose(np.linalg.norm(res.normal, axis=-1), 1.0)  # the zero gradient falls back, no NaN


def test_tunnel_pixel_cone_needs_fewer_steps_than_fixed_epsilon():
    # seed Exp. 2: shallow rays along planes. The footprint-relative hit test stops as soon
    # as the pixel cannot resolve more, a fixed epsilon keeps stepping at every distance.
    case = next(c for c in CASES if c.name == "tunnel")
    cone, res_cone = run_case(case, (64, 48))
    fixed, res_fixed = run_case(case, (64, 48), hit="absolute", hit_scale=1e-4)
    assert cone.lost_hits == 0 and fixed.lost_hits == 0
    assert res_cone.steps.mean() < 0.7 * res_fixed.steps.mean()
    assert cone.depth_px_median < 1e-3

"""Marching methods: each one compiles, renders and meets its documented behaviour."""
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import sdfgl as sg
from sdfgl.hardcases import case, run_case
from sdfgl.settings import METHODS

ALL = ("color", "depth", "normal", "steps")
ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("method", METHODS)
def test_method_hits_unit_sphere_exactly(renderer, method):
    cam = sg.OrbitCamera(distance=4, yaw=0, pitch=0, fov=40)
    res = renderer.render(sg.sphere(1), cam, (33, 33), method=method, outputs=ALL, shadows="hard", ao=True,
                          analytic=False)
    assert abs(float(res.depth[16, 16]) - 3.0) < 2e-4
    assert not np.isnan(res.depth).any() and np.isfinite(res.normal).all()
    assert res.steps[16, 16] >= 1


def test_reference_march_resolves_what_its_step_resolves():
    coarse, _ = run_case(case("thin_shell"), (40, 30), method="reference")  # step 2/512 > the 1e-3 shell
    fine, _ = run_case(case("thin_shell"), (40, 30), method="reference", ref_step=5e-4)
    assert coarse.lost_hits > 50 and fine.lost_hits == 0


def test_newton_takes_wrong_roots_on_staggered_spheres_as_the_seed_reports():
    newton, _ = run_case(case("five_spheres"), (64, 48), method="newton", newton_cap=None)
    enhanced, _ = run_case(case("five_spheres"), (64, 48), method="enhanced")
    assert newton.lost_hits + newton.depth_outliers > enhanced.lost_hits + enhanced.depth_outliers


def test_newton_on_planes_and_forward_newton_cost():
    newton, rn = run_case(case("tunnel"), (64, 48), method="newton")
    sphere, rs = run_case(case("tunnel"), (64, 48), method="sphere")
    fwd, rf = run_case(case("tunnel"), (64, 48), method="forward_newton")
    assert newton.lost_hits == 0 and newton.depth_px_median < 1e-3
    assert rn.steps.mean() < rs.steps.mean() < rf.steps.mean()


@pytest.mark.parametrize("method", ["newton", "forward_newton", "reference"])
def test_implicit_product_renders_with_root_finding_methods(method):
    err, res = run_case(case("product_union"), (48, 36), method=method)
    assert err.hits > 100 and err.lost_hits <= 0.02 * err.hits
    assert err.depth_px_median < 0.05  # |f| < eps on a field whose slope is not 1
    assert not np.isnan(res.depth).any()


def test_implicit_scene_with_distance_method_is_refused():
    s = sg.product(sg.sphere(1), sg.box(1))
    with pytest.raises(sg.ParameterError, match=r"implicit field, not a distance bound: method 'enhanced'"):
        sg.compile(s, method="enhanced")
    src = sg.compile(s, method="newton", ao=True, shadows="soft")  # AO on a clamped, safe estimate
    assert "improved penumbra" not in src and "march(ro, rd, tmin, tmax, ignored)" in src
    assert "#define IMPLICIT_FIELD" in src and "d = clamp(d, 0.0, h);" in src


def test_default_method_is_resolved_per_exactness_class():
    res = sg.render(sg.implicit("x**2 + y**2 + z**2 - 1"), size=(24, 18), outputs=("color", "depth"))
    assert res.settings.method == "newton" and np.isfinite(res.depth).sum() > 50
    res = sg.render(sg.product(sg.sphere(0.6), sg.box(0.8).translate((0.6, 0, 0))), size=(24, 18), outputs=("depth",))
    assert res.settings.method == "newton" and np.isfinite(res.depth).any()
    assert sg.render(sg.sphere(1), size=(8, 6)).settings.method == "enhanced"
    assert "#define ENHANCED" in sg.compile(sg.box(1)) and "rayDerivative" in sg.compile(sg.product(sg.sphere(1), sg.box(1)))


def test_only_the_chosen_loop_is_compiled():
    src = sg.compile(sg.sphere(1), method="enhanced", analytic=False)
    assert "#define OMEGA 0.899999976" in src and "#define ENHANCED" in src and "over-relaxed" in src
    assert "Newton" not in src and "rayDerivative" not in src and "REF_STEP" not in src
    assert "rayDerivative" in sg.compile(sg.sphere(1), method="newton", analytic=False)


def test_bad_method_settings():
    with pytest.raises(sg.ParameterError, match="setting 'method' must be one of"):
        sg.compile(sg.sphere(1), method="magic")
    with pytest.raises(sg.ParameterError, match=r"setting 'omega' for 'relaxed' must lie in \(1, 2\)"):
        sg.compile(sg.sphere(1), method="relaxed", omega=2.5)
    with pytest.raises(sg.ParameterError, match="applies to methods 'relaxed' and 'enhanced'"):
        sg.compile(sg.sphere(1), method="newton", omega=0.5)


@pytest.mark.slow
def test_bench_quick_writes_reports(tmp_path):
    # the methods and feature sections; the other sections' rows have tests of their own
    r = subprocess.run([sys.executable, "-m", "sdfgl.cli", "bench", "--quick", "--size", "48x36", "--no-progress",
                        "--scenes", "rounded_box", "product_union", "--sections", "methods", "features",
                        "--out", str(tmp_path)],
                       capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert r.returncode == 0, r.stderr
    assert "## Summary: default settings of each method" in r.stdout and "tables of Monzón González" in r.stdout
    data = json.loads((tmp_path / "bench.json").read_text())
    labels = {(v["scene"], v["label"]) for v in data["variants"]}
    assert ("rounded_box", "enhanced") in labels and ("product_union", "newton") in labels
    assert ("product_union", "sphere") not in labels  # distance methods skip implicit scenes
    v = data["variants"][0]
    for key in ("frame_ms_median", "frame_ms_p95", "compile_s", "steps_mean", "steps_p95", "out_of_steps",
                "depth_px_median", "depth_px_p99", "silhouette_mismatch", "normal_deg_median"):
        assert key in v
    assert (tmp_path / "pareto.png").stat().st_size > 1000
    assert len(data["features"]) == 13  # aa, shadows, AO, all; then lights, materials, alpha, fog
    feats = {f["label"]: f for f in data["features"]}
    assert "materials (metallic, roughness, emission)" in feats
    four = feats["4 lights (soft, hard, 2 unshadowed)"]
    assert [lt["kind"] for lt in four["settings"]["lights"]] == ["directional", "directional", "point", "directional"]
    assert four["frame_ms_median"] > 0
    assert "## Big scenes" not in r.stdout and "mesh" not in data  # sections not asked for are not run


def test_bench_refuses_an_unknown_section(tmp_path):
    r = subprocess.run([sys.executable, "-m", "sdfgl.cli", "bench", "--quick", "--sections", "speed",
                        "--out", str(tmp_path)], capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert r.returncode == 2 and "invalid choice: 'speed'" in r.stderr and "methods" in r.stderr


@pytest.mark.slow
def test_capped_newton_keeps_the_roots_of_an_implicit_surface():
    from sdfgl import reference as R
    t = sg.implicit("x**4 - 5*x**2 + y**4 - 5*y**2 + z**4 - 5*z**2 + 11.8",
                    bounds=((-2.8, -2.8, -2.8), (2.8, 2.8, 2.8)))
    cam = sg.OrbitCamera(distance=9, yaw=25, pitch=25)
    ref = R.trace(t, cam, (64, 48), step=0.002)
    lost = {}
    for cap in (None, 2.0):
        res = sg.render(t, cam, (64, 48), method="newton", newton_cap=cap, ao=False, outputs=("color", "depth", "normal"))
        lost[cap] = R.compare(res, ref).lost_hits
    assert lost[2.0] < 0.25 * lost[None] and lost[2.0] < 0.02 * np.isfinite(ref.t).sum()


def test_bench_mesh_field_rows_at_quick_sizes():
    from sdfgl.bench_mesh_field import QUICK, run_mesh_field
    md, data = run_mesh_field(True)
    assert data["triangles"] == 2 * QUICK["nu"] * QUICK["nv"]
    d, f = data["distance"], data["frame"]
    assert d["points"] == QUICK["points"] and d["gpu_s"] > 0 and d["igl_s"] > 0
    assert d["ratio"] == pytest.approx(d["gpu_s"] / d["igl_s"])
    assert d["max_diff_diag"] < 1e-5 and d["sign_agreement"] > 0.999
    assert f["size"] == list(QUICK["size"]) and f["ratio"] == pytest.approx(f["field_s"] / f["raster_s"])
    assert "| signed distance at 10000 points |" in md and "| frame 64x48" in md
    json.dumps(data)  # bench.json holds it

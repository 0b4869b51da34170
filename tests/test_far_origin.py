"""Scenes far from the world origin whose shader origin moves (unbounded scenes follow the
eye, scenes with live parameters follow their box): exact to float32 rounding at any
offset, and moving the camera or a parameter never recompiles. Closed-form ground truth."""
import numpy as np
import pytest

import sdfgl as sg

from . import closed_form as cf

SIZE = (48, 36)
OUTS = ("depth", "normal")


def _errors(res, cam, t, n):
    """(depth p99 in footprints, normal p99 in degrees, lost, false) against closed form."""
    d = res.depth.reshape(-1).astype(np.float64)
    both = np.isfinite(d) & np.isfinite(t)
    fp = t[both] * cam.pixel_angle(SIZE[1])
    cos = np.sum(res.normal.reshape(-1, 3)[both] * n[both], axis=1)
    ang = np.degrees(np.arccos(np.clip(cos, -1, 1)))
    lost = int((~np.isfinite(d) & np.isfinite(t)).sum())
    false = int((np.isfinite(d) & ~np.isfinite(t)).sum())
    return float(np.percentile(np.abs(d[both] - t[both]) / fp, 99)), float(np.percentile(ang, 99)), lost, false


def _plane_and_cube(o, pn, c, cam):
    """Closed-form first hits of a tilted plane through ``o`` (normal ``pn``) and the cube of
    edge ``c`` resting on it."""
    ob, db = (a.reshape(-1, 3) for a in cam.rays(*SIZE))
    centre = o + pn * c * 0.9
    tb, nb = cf.box(ob, db, centre, np.full(3, c / 2))
    den = db @ pn
    tp = np.where(den < 0, ((o - ob) @ pn) / np.where(den < 0, den, -1.0), np.inf)
    return np.where(tb <= tp, tb, tp), np.where((tb <= tp)[:, None], nb, pn)


@pytest.mark.parametrize("offset", [1.234567e5, 3.3333337e6, 9.87654321e6])
def test_tilted_ground_and_a_small_cube_far_out(offset):
    # an unbounded scene (a tilted ground plane) with a cube 1:1e4 of the usual 200-wide floor,
    # at offsets on no power-of-two grid; before the moving origin: up to 86 degrees, 25 footprints
    pn = np.array([0.12, 1.0, 0.07]) / np.linalg.norm([0.12, 1.0, 0.07])
    o = np.array([offset, 0.37 * offset, -0.77 * offset])
    c = 0.02
    centre = o + pn * c * 0.9
    scene = sg.plane(tuple(pn), tuple(o)) | sg.box(c).translate(tuple(centre))
    cam = sg.Camera.look_at(tuple(centre + c * np.array([1.3, 1.6, 2.0])), tuple(centre - pn * c * 0.3), fov=60)
    res = sg.render(scene, cam, SIZE, outputs=OUTS, shadows=False, ao=False)
    assert res.source.origin_offsets is not None  # the origin is a uniform here
    d99, n99, lost, false = _errors(res, cam, *_plane_and_cube(o, pn, c, cam))
    assert n99 <= 1.0 and d99 <= 0.25 and lost == 0 and false == 0, (d99, n99, lost, false)


def test_moving_camera_and_live_translation_far_out_never_recompile():
    renderer = sg.Renderer()
    # unbounded: the origin follows the eye, so each view is exact and none recompiles
    o = np.array([7.654321e6, 12.5, -2.345678e6])
    pn = np.array([0.0, 1.0, 0.0])
    scene = sg.plane((0, 1, 0), tuple(o)) | sg.box(0.05).translate(tuple(o + pn * 0.045))
    views = [sg.Camera.look_at(tuple(o + e), tuple(o + (0, 0.02, 0)), fov=50)
             for e in ((0.11, 0.09, 0.13), (-0.07, 0.12, 0.1), (0.2, 0.05, -0.15))]
    for _ in range(2):  # a second frame links the other tile programs
        renderer.render(scene, views[0], SIZE, outputs=OUTS, shadows=False, ao=False)
    compiles = renderer.programs.compiles
    for cam in views:
        res = renderer.render(scene, cam, SIZE, outputs=OUTS, shadows=False, ao=False)
        d99, n99, lost, false = _errors(res, cam, *_plane_and_cube(o, pn, 0.05, cam))
        assert n99 <= 1.0 and d99 <= 0.25 and lost <= 1 and false <= 1, (d99, n99, lost, false)
    assert renderer.programs.compiles == compiles
    # a live translation far out: summed with the origin in float64 on the CPU per frame
    where = sg.param((5.4321e6, 1.0, 3.21e5), "where")
    box = sg.box(0.01).translate(where)
    for value in ((5.4321e6, 1.0, 3.21e5), (5.4321e6 + 0.123456, 1.007, 3.21e5 - 0.0031)):
        where.value = value
        c = np.asarray(value)
        cam = sg.Camera.look_at(tuple(c + (0.02, 0.015, 0.03)), tuple(c), fov=50)
        res = renderer.render(box, cam, SIZE, outputs=OUTS, shadows=False, ao=False)
        if value[0] == 5.4321e6:
            res = renderer.render(box, cam, SIZE, outputs=OUTS, shadows=False, ao=False)  # a second frame links the other tile programs
            compiles = renderer.programs.compiles
        ob, db = (a.reshape(-1, 3) for a in cam.rays(*SIZE))
        d99, n99, lost, false = _errors(res, cam, *cf.box(ob, db, c, np.full(3, 0.005)))
        assert n99 <= 1.0 and d99 <= 0.25 and lost <= 1 and false <= 1, (value, d99, n99, lost, false)
    assert renderer.programs.compiles == compiles


def test_grid_union_far_out_matches_the_same_union_at_the_origin():
    # a union kept as data (>= 128 instances) beside a ground plane: its data are relative to
    # its own centre and the point reaches it through one float64-summed origin offset, so far
    # out it renders as it does at the origin (before: 10 footprints, 93 degrees at 9.9e6)
    rng = np.random.default_rng(1)
    rel = np.c_[rng.uniform(-0.5, 0.5, 150), np.full(150, 0.011), rng.uniform(-0.5, 0.5, 150)]
    out = []
    for offset in (0.0, 9.87654321e6):
        o = np.array([offset, 3.0, -0.61 * offset])
        scene = sg.plane((0, 1, 0), tuple(o)) | sg.union(*[sg.box(0.02).translate(tuple(o + c)) for c in rel])
        cam = sg.Camera.look_at(tuple(o + rel[0] + (0.05, 0.04, 0.07)), tuple(o + rel[0]), fov=50)
        res = sg.render(scene, cam, SIZE, outputs=OUTS, shadows=False, ao=False)
        assert res.source.data_unions == 1
        out.append(res)
    near, far = out
    assert np.array_equal(np.isfinite(near.depth), np.isfinite(far.depth))
    hit = np.isfinite(near.depth)
    fp = near.depth[hit] * sg.Camera.look_at((0, 0, 1), (0, 0, 0), fov=50).pixel_angle(SIZE[1])
    assert np.percentile(np.abs(far.depth[hit] - near.depth[hit]) / fp, 99) <= 0.05
    cos = np.sum(near.normal[hit] * far.normal[hit], axis=-1)
    assert np.percentile(np.degrees(np.arccos(np.clip(cos, -1, 1))), 99) <= 1.0


def test_point_lights_follow_the_shader_origin():
    # a point light is placed relative to the shader origin (a constant for a bounded scene
    # centred away from 0, a uOrg uniform where the origin moves): far out, the image is the
    # one at the origin (before, the light was displaced by the origin: a bounded scene at
    # 5 units lit from the wrong side, an unbounded one lit from the eye's offset)
    def image(c, unbounded):
        c = np.asarray(c, dtype=np.float64)
        s = sg.sphere(0.5).translate(tuple(c))
        if unbounded:
            s = s | sg.plane((0, 1, 0), tuple(c - (0, 0.5, 0)))
        light = sg.point_light(tuple(c + (0.8, 1.2, 0.4)), "white", 1.0, range=1.5, shadow=False)
        cam = sg.Camera.look_at(tuple(c + (0.4, 0.9, 2.2)), tuple(c), fov=50)
        return sg.render(s, cam, (32, 24), lights=[light], ambient="black", ao=False).color.astype(int)
    for unbounded in (False, True):
        at0 = image((0, 0, 0), unbounded)
        for c in ((5.0, 0.0, 0.0), (4.321e5, -1.5, 2.5e5)):
            assert np.abs(image(c, unbounded) - at0).max() <= 3, (c, unbounded)

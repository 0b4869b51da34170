"""Everything a browser view of a scene needs, as JSON: the WebGL2 shaders, parameters, data.

The browser has no code generator, so the shaders of every toggle state (A: AA 1..4,
S: shadows off / hard / soft, O: AO, D: debug views) are generated here, by the same
``generate()`` as the desktop renderer with the "webgl2" dialect. They share almost all
their text, so each source is stored as a list of indices into a table of unique blocks
(runs of lines written by the same owner): the map() of the scene is stored once.

A scene with live parameters reads its box (ray clip, ground height, scene scale) from
uniforms that the desktop renderer recomputes from the nodes' bounds. The browser
cannot, so each parameter is swept over its slider range here and the view
interpolates the frame; with several parameters moved at once, their changes are added
(the clip box then gets a margin). The notebook widget sends the exact frame instead.
"""
from __future__ import annotations

import base64
import math
from dataclasses import replace
from typing import Any

import numpy as np

from ..camera import Camera, OrbitCamera
from ..compiler.generate import generate
from ..compiler.analysis import GLSL_FAR
from ..errors import ParameterError
from ..gl.dialect import WEBGL2
from ..nodes.base import IMPLICIT, Node
from ..params import Param
from ..render import shader_origin
from ..uniforms import live_frame
from ..settings import Settings
from .. import shaderlib

SHADOW_NAMES = {False: "off", "hard": "hard", "soft": "soft"}
DEBUG_VIEWS = ("steps", "normal", "depth")
# the uniforms viewer.js sets besides parameters, scene-box frame and data samplers
# (render.camera_uniforms' perspective set); the page refuses a shader that reads others
VIEWER_UNIFORMS = ("uResolution", "uEye", "uRight", "uUp", "uForward", "uTanHalfFov", "uJitter", "uZero")
SWEEP_SAMPLES = 17  # parameter values per slider at which the scene box is tabulated
RANGE_PROBES = 64   # values tried when a slider's default range is narrowed to valid ones


def variant_key(aa: int, shadows: Any, ao: bool, debug: str | None) -> str:
    """The name of one toggle state's shader (viewer.js builds the same string)."""
    if debug:
        return f"1|off|0|{debug}"
    return f"{aa}|{SHADOW_NAMES[shadows]}|{int(ao)}|none"


def _blocks(text: str, owners: tuple[str, ...]) -> list[str]:
    out: list[str] = []
    lines = text.rstrip("\n").split("\n")
    start = 0
    for i in range(1, len(lines) + 1):
        if i == len(lines) or owners[i] != owners[start]:
            out.append("\n".join(lines[start:i]) + "\n")
            start = i
    return out


def orbit_state(cam: OrbitCamera) -> dict[str, Any]:
    """The orbit camera as the page and widget keep it: target, distance, yaw, pitch, fov."""
    return {"target": [float(x) for x in cam.target], "distance": float(cam.distance), "yaw": float(cam.yaw),
            "pitch": float(cam.pitch), "fov": float(cam.fov)}


def camera_from_state(state: dict[str, Any]) -> OrbitCamera:
    """The OrbitCamera a view's camera state describes."""
    try:
        return OrbitCamera(state["target"], state["distance"], state["yaw"], state["pitch"], state["fov"])
    except (KeyError, TypeError) as exc:
        raise ParameterError(f"camera state needs target, distance, yaw, pitch and fov: {exc}") from None


def _valid(prm: Param, value: Any) -> bool:
    old = prm.value
    try:
        prm.value = value
    except ParameterError:
        return False
    prm.value = old
    return True


def slider_range(prm: Param) -> tuple[float, float]:
    """The slider range of ``prm``: its own, else around its value narrowed to values its nodes (and an
    open-ended range of its own) accept."""
    if prm.range is not None and all(math.isfinite(x) for x in prm.range):
        return prm.range
    v = np.asarray(prm.value, dtype=np.float64)
    mag = float(np.max(np.abs(v))) or 1.0
    lo, hi = float(np.min(v)) - mag, float(np.max(v)) + mag
    probes = np.linspace(lo, hi, RANGE_PROBES + 1)
    ok = [_valid(prm, np.full(v.shape, x) if v.ndim else x) for x in probes]
    # the run of valid probes around the value (for a vector: around its smallest component)
    centre = int(np.argmin(np.abs(probes - float(np.min(v)))))
    a = b = centre
    while a > 0 and ok[a - 1]:
        a -= 1
    while b < len(probes) - 1 and ok[b + 1]:
        b += 1
    if not ok[centre] or a == b:
        if prm.range is not None:
            lo, hi = max(lo, prm.range[0]), min(hi, prm.range[1])
        return lo, hi
    return float(probes[a]), float(probes[b])


def _frame_json(frame: dict[str, object]) -> dict[str, Any]:
    return {k: list(v) if isinstance(v, tuple) else v for k, v in frame.items()}


def _sweeps(scene: Node, params: tuple[Param, ...], ranges: list[tuple[float, float]],
            origin: np.ndarray) -> list[dict[str, Any]]:
    """The scene frame at SWEEP_SAMPLES values of each parameter component, the others unchanged."""
    sweeps = []
    for i, (prm, (lo, hi)) in enumerate(zip(params, ranges)):
        start = prm.value
        for comp in range(prm.dims):
            values, frames = [], []
            for x in np.linspace(lo, hi, SWEEP_SAMPLES):
                v: Any = float(x)
                if prm.dims == 3:
                    v = np.array(start, dtype=np.float64)
                    v[comp] = x
                if _valid(prm, v):
                    prm.value = v
                    values.append(float(x))
                    frames.append(_frame_json(live_frame(scene, origin)))
                    prm.value = start
            sweeps.append({"param": i, "component": comp, "values": values, "frames": frames})
    return sweeps


def estimate(frame: dict[str, Any], params: tuple[Param, ...], start: list[Any], values: list[Any]) -> dict[str, Any]:
    """The frame the browser assumes at ``values``: the base frame plus each swept component's
    change from its starting value (viewer.js computes the same, before adding the margin)."""
    out = {k: np.array(v, dtype=np.float64) for k, v in frame["base"].items()}
    for sw in frame["sweeps"]:
        comp = (lambda v: np.asarray(v, dtype=np.float64)[sw["component"]]) if params[sw["param"]].dims == 3 \
            else (lambda v: float(v))
        v, v0 = comp(values[sw["param"]]), comp(start[sw["param"]])
        if v == v0 or not sw["values"]:
            continue
        for key in out:
            col = np.array([f[key] for f in sw["frames"]], dtype=np.float64).reshape(len(sw["values"]), -1)
            at = [np.interp(x, sw["values"], col[:, j]) for x in (v, v0) for j in range(col.shape[1])]
            half = len(at) // 2
            out[key] = out[key] + (np.array(at[:half]) - np.array(at[half:])).reshape(out[key].shape)
    return out


MARGIN_PROBES = 24  # random combinations of slider values checked against the estimate


def _margin(scene: Node, params: tuple[Param, ...], ranges: list[tuple[float, float]], origin: np.ndarray,
            frame: dict[str, Any]) -> float:
    """How far the estimated clip box may fall short of the true one: twice the largest
    shortfall at random slider values (0 where the sweeps add up exactly, e.g. one parameter
    that moves the box linearly)."""
    start = [p.value for p in params]
    rng = np.random.default_rng(0)
    worst = 0.0
    try:
        for _ in range(MARGIN_PROBES):
            values = [rng.uniform(lo, hi, np.shape(v)) if np.ndim(v) else float(rng.uniform(lo, hi))
                      for v, (lo, hi) in zip(start, ranges)]
            try:
                for p, v in zip(params, values):
                    p.value = v
            except ParameterError:
                continue
            exact = live_frame(scene, origin)
            est = estimate(frame, params, start, values)
            short = max(float(np.max(est["uBoundsLo"] - np.asarray(exact["uBoundsLo"]))),
                        float(np.max(np.asarray(exact["uBoundsHi"]) - est["uBoundsHi"])), 0.0)
            worst = max(worst, short)
    finally:
        for p, v in zip(params, start):
            p.value = v
    return 2.0 * worst


def _data_json(data: tuple[tuple[str, np.ndarray], ...]) -> list[dict[str, Any]]:
    out = []
    for name, arr in data:
        a = np.ascontiguousarray(arr, dtype="<f4")
        out.append({"name": name, "width": int(a.shape[1]), "height": int(a.shape[0]),
                    "b64": base64.b64encode(a.tobytes()).decode("ascii")})
    return out


def build_spec(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (640, 400),
               **settings: Any) -> dict[str, Any]:
    """The JSON-ready description of a browser view of ``scene`` (see the module docstring)."""
    return build(scene, camera, size, **settings)[0]


def build(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (640, 400), toggles: bool = True,
          **settings: Any) -> tuple[dict[str, Any], tuple[Param, ...]]:
    """:func:`build_spec`, and the parameters behind the uniforms uP0, uP1, ... of its shaders.
    With ``toggles`` False only the shader of the given settings is generated (a view without
    the A, S, O, D toggles: the studio's node previews)."""
    if not isinstance(scene, Node):
        raise ParameterError(f"scene must be an sdfgl node, got {type(scene).__name__} {scene!r}")
    w, h = (int(x) for x in size)
    if not (16 <= w <= 8192 and 16 <= h <= 8192):
        raise ParameterError(f"view size must be two integers in 16..8192, got {size!r}")
    implicit = scene.exactness == IMPLICIT
    base = {"shadows": "soft", "ao": not implicit, **({"method": "newton"} if implicit else {}), **settings}
    start = Settings.build(**base)
    cam = OrbitCamera.of(camera, *scene.bounds)
    origin = shader_origin(scene, cam.eye)

    blocks: list[str] = []
    index: dict[str, int] = {}
    variants: dict[str, list[int]] = {}
    states = [(aa, sh, ao, None) for aa in (1, 2, 3, 4) for sh in (False, "hard", "soft")
              for ao in ((False,) if implicit else (False, True))]
    states += [(1, False, False, d) for d in DEBUG_VIEWS]
    if not toggles:
        states = [(start.aa, start.shadows, start.ao, start.debug)]
    first = None
    for aa, sh, ao, debug in states:
        st = replace(start, aa=aa, shadows=sh, ao=ao, debug=debug, outputs=("color",))
        src = generate(scene, st, origin, dialect=WEBGL2.name)
        if first is None:
            first = src
        ids = []
        for block in _blocks(src.text, src.owners):
            if block not in index:
                index[block] = len(blocks)
                blocks.append(block)
            ids.append(index[block])
        variants[variant_key(aa, sh, ao, debug)] = ids
    assert first is not None
    ranges = [slider_range(p) for p in first.params]
    frame: dict[str, Any] = {"live": first.live_bounds}
    if first.live_bounds:
        frame["base"] = _frame_json(live_frame(scene, origin))
        frame["sweeps"] = _sweeps(scene, first.params, ranges, origin)
        frame["margin"] = _margin(scene, first.params, ranges, origin, frame)
    return {
        "version": 1,
        "title": scene.label()[:120],
        "size": [w, h],
        "vertex": WEBGL2.convert(shaderlib.read("mains/fullscreen.vert")),
        "uniforms": list(VIEWER_UNIFORMS),
        "blocks": blocks,
        "variants": variants,
        "settings": {"aa": start.aa, "shadows": start.shadows, "ao": start.ao, "debug": start.debug},
        "toggles": {"aa": [1, 2, 3, 4], "shadows": [False, "hard", "soft"], "ao": [False] if implicit else [False, True],
                    "debug": [None, *DEBUG_VIEWS]} if toggles else
                   {"aa": [start.aa], "shadows": [start.shadows], "ao": [start.ao], "debug": [start.debug]},
        "origin": [float(x) for x in origin],
        "bounds": [[float(x) if np.isfinite(x) else (-GLSL_FAR if i == 0 else GLSL_FAR) for x in b]
                   for i, b in enumerate(scene.bounds)],
        "camera": orbit_state(cam),
        "params": [{"uniform": f"uP{i}", "label": p.label, "dims": p.dims,
                    "value": p.value.tolist() if p.dims == 3 else float(p.value),
                    "min": lo, "max": hi} for i, (p, (lo, hi)) in enumerate(zip(first.params, ranges))],
        "frame": frame,
        "data": _data_json(first.data),
    }, first.params

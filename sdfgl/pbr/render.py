"""render_pbr() and to_mitsuba(): path-traced renders of sdfgl scenes through Mitsuba 3."""
from __future__ import annotations

import time
from typing import Any, Callable, Mapping, Sequence

import numpy as np

from ..camera import Camera
from ..errors import ParameterError, SdfglError
from ..nodes.base import Node
from .backend import mitsuba
from .field_grid import Progress
from .image import PBRImage
from .lighting import Sky, Sun
from .materials import Look
from .scene import build

PASS_SPP = 16  # samples per pixel per pass (a power of four): progress is reported between passes
SCENE_OPTIONS = ("resolution", "quality", "bounds", "material", "sky", "sun", "ground", "max_depth", "extra",
                 "progress", "variant", "geometry")  # what to_mitsuba takes besides size and spp
RENDER_OPTIONS = SCENE_OPTIONS + ("seed",)


def check_options(func: str, options: Mapping[str, Any], known: Sequence[str]) -> None:
    """Refuse option names ``func`` does not take, naming them and listing the ones it does."""
    unknown = sorted(set(options) - set(known))
    if unknown:
        raise ParameterError(f"{func}: unknown option{'s' if len(unknown) > 1 else ''} "
                             f"{', '.join(repr(u) for u in unknown)}; it takes size, spp, {', '.join(known)}")


def passes(spp: int) -> list[int]:
    """Samples per pixel of each pass: PASS_SPP while that many remain, then the rest in
    powers of four, the counts the low-discrepancy sampler takes (it renders a pass of 1 as 4)."""
    rest, out, p = spp % PASS_SPP, [], 1
    while rest:
        out += [p] * (rest % 4)
        rest, p = rest // 4, p * 4
    return [PASS_SPP] * (spp // PASS_SPP) + out[::-1]


def to_mitsuba(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (640, 480), spp: int = 64,
               **options: Any) -> dict[str, Any]:
    """The Mitsuba 3 scene dictionary that :func:`render_pbr` renders (for ``mi.load_dict``),
    to extend by hand: keys ``integrator``, ``sensor``, ``sdf_bsdf`` (the material), the
    geometry, ``sky``, ``sun`` and ``ground`` when asked for. The geometry is ``sdf_0``,
    ``sdf_1``, ... (one ``sdfgrid`` per cubic tile the surface passes through) on the grid
    path, and on the mesh path ``sdf_mesh`` and ``sdf_emitter_0``, ... (in-memory
    ``mi.Mesh`` objects, the emitters one per emitted colour), which carry ``sdf_bsdf``
    already loaded: to change their material call their ``set_bsdf``. Takes the same
    options as render_pbr.
    """
    check_options("to_mitsuba", options, SCENE_OPTIONS)
    variant = options.pop("variant", None)
    mi, _, _ = mitsuba(variant)
    return build(mi, scene, camera, size, spp, **options).scene


def render_pbr(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (640, 480), spp: int = 64, *,
               resolution: int | None = None, quality: float = 1.0, bounds: object = None,
               material: Look | None = None, sky: Sky | None = None, sun: Sun | None = None, ground: bool = False,
               max_depth: int = 8, extra: dict[str, Any] | None = None, seed: int = 0,
               variant: str | None = None, progress: Callable[[str, float], None] | None = None,
               geometry: str = "auto") -> PBRImage:
    """Path-trace ``scene`` with Mitsuba 3 (extra ``sdfgl[pbr]``); returns a :class:`PBRImage`.

    camera: an sdfgl camera (default: the same framing as ``render()``).
    size: (width, height) in pixels; spp: samples per pixel.
    geometry: what Mitsuba intersects. "mesh": sdfgl's own mesh export (:func:`sdfgl.mesh`,
        dual contouring, every vertex moved onto the surface to 0.001 of a cell) at three
        lattice cells per pixel footprint, with the scene's colours and node materials per
        vertex; sharp edges stay sharp, features down to a third of a pixel footprint
        render, and emissive materials are area lights (up to 16 emitted colours). "grid":
        the field sampled onto Mitsuba's ``sdfgrid`` at two cells per footprint (the
        trilinear interpolant rounds edges off by about a cell and loses features thinner
        than a cell; no emission). "auto" (default): "mesh" for a bounded scene whose
        lattice has at most 512 cells along its longest side, else "grid" (an unbounded
        field: a mesh would close where ``bounds`` cuts it). ``settings["geometry"]`` says
        which was used and ``settings["geometry_choice"]`` why.
    resolution: cells of the SDF grid (or of the mesh lattice) along the longest side of
        the scene box (16..1024); default: from the pixel footprint at the scene, times ``quality``.
    bounds: (lo, hi) box to sample, required for unbounded scenes.
    material: a pbr ``Material`` (default: diffuse, the scene's own colours) or a
        ``Blend`` of two across another field's zero set.
    sky, sun: the environment and the directional light (defaults match the real-time look).
    ground: the real-time renderer's checkered ground plane under the scene.
    max_depth: longest light path; seed: the sampler's seed.
    extra: more Mitsuba objects by name, added to the scene dictionary (an area light,
        another shape; in world coordinates minus ``settings["offset"]``, which is zero
        unless the scene lies far from the origin); a name of the defaults ("sky", "sun",
        "ground") replaces it, None removes it.
    variant: a Mitsuba variant; default: chosen automatically (an LLVM variant when it
        renders here, else ``scalar_rgb``), reported in ``settings["variant"]``.
    progress: called with (stage, fraction done) while sampling and rendering.

    Example::

        img = sg.render_pbr(sg.sphere(1) & sg.box(1.5), size=(320, 240), spp=32)
        img.save("pbr.png")
    """
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed < 1 << 16:
        raise ParameterError(f"render_pbr: 'seed' must be an integer in 0..65535, got {seed!r}")
    tv = time.perf_counter()
    mi, chosen, how = mitsuba(variant)
    t0 = time.perf_counter()
    built = build(mi, scene, camera, size, spp, resolution=resolution, quality=quality, bounds=bounds,
                  material=material, sky=sky, sun=sun, ground=ground, max_depth=max_depth, extra=extra, progress=progress,
                  geometry=geometry)
    t1 = time.perf_counter()
    try:
        loaded = mi.load_dict(built.scene)
    except RuntimeError as exc:  # Mitsuba reports plugin errors as RuntimeError
        raise SdfglError(f"pbr: Mitsuba could not build the scene: {str(exc).strip().splitlines()[-1]}") from exc
    t2 = time.perf_counter()
    w, h = built.scene["sensor"]["film"]["width"], built.scene["sensor"]["film"]["height"]
    acc = np.zeros((h, w, 4), dtype=np.float64)
    done = 0
    level = mi.log_level()
    mi.set_log_level(mi.LogLevel.Error)  # Mitsuba warns of each NaN sample it discards (see README)
    try:
        for k, n in enumerate(passes(spp)):
            img = np.asarray(mi.render(loaded, spp=n, seed=seed * 65536 + k), dtype=np.float64)
            acc += img[..., :4] * n
            done += n
            if progress is not None:
                progress("path tracing", done / spp)
    finally:
        mi.set_log_level(level)
    t3 = time.perf_counter()
    rgba = np.nan_to_num(acc / spp).astype(np.float32)
    rgba[..., 3] = np.clip(rgba[..., 3], 0.0, 1.0)
    sky = sky if sky is not None else Sky()
    background = sky.radiance(built.camera.rays(w, h)[1]).astype(np.float32)
    if built.sky_seen:  # rays that missed saw the sky: take it out, leaving the scene's radiance
        rgba[..., :3] = np.maximum(rgba[..., :3] - (1.0 - rgba[..., 3:]) * background, 0.0)
    settings = {"variant": chosen, "variant_choice": how, "offset": built.offset.tolist(), **built.info}
    timings = {"variant_s": t0 - tv, "sample_s": t1 - t0, "load_s": t2 - t1, "trace_s": t3 - t2, "total_s": time.perf_counter() - tv}
    return PBRImage(rgba, background, settings, timings)


__all__ = ["render_pbr", "to_mitsuba", "PBRImage", "Progress"]

"""sdfgl: signed-distance-function scenes in Python, rendered by generated GLSL.

    import sdfgl as sg
    s = sg.sphere(1) & sg.box(1.5)
    sg.render(s, camera=sg.OrbitCamera(distance=5), size=(800, 600), aa=2).save("out.png")
"""
from collections.abc import Sequence as _Sequence

import numpy as _np

from .camera import Camera, OrbitCamera
from .compiler.generate import compile
from .errors import (ContextError, MeshError, ParameterError, SceneDocumentError, SceneFileError, SdfglError,
                     ShaderCompileError)
from .look import directional_light, point_light
from .evaluate import evaluate
from .gl.cache import CacheBudget, cache_budget
from . import mesh  # the package is callable: sg.mesh(scene, step=0.01)
from .mesh import Mesh
from .meshin import from_mesh, load_mesh
from .nodes import (BOUND, EXACT, IMPLICIT, Node, bend, box, box_frame, capsule, circle, displace, elongate, extrude,
                    displace_expr, implicit, noise, parametric,
                    mirror, polygon, rectangle, repeat_polar, revolve, rounded, shell, sierpinski, symmetric, tree, cone, cylinder, difference, ellipsoid,
                    hex_prism, intersection, octahedron, plane, product, repeat, rounded_box, sphere, torus, twist,
                    union, Shape2D, arc, capsule2, ellipse, regular_polygon, star, triangle, slice, text,
                    bezier_tube, capped_torus, dodecahedron, gyroid, icosahedron, pyramid, slab, tetrahedron, tube,
                    morph, taper, glsl)
from .evaluate import evaluate
from .params import Param, param, time
from .functions import (abs, clamp, cos, exp, floor, fract, log, max, min, mix, mod, pow, radians, sign, sin,
                        smoothstep, sqrt, step, tan)
from .animate import animate, camera_path, keyframes, turntable
from .raster import RasterMesh, raster
from .render import RenderResult, Renderer, render
from .version import __version__

# Imported on first use, so that `import sdfgl` stays fast: name -> module. A heavy new
# public name adds one line here (a name must differ from its module's, or importing the
# module would replace it).
_LAZY = {
    "save_scene": "scene_io", "load_scene": "scene_io", "from_dict": "scene_io",
    "save_3mf": "mesh.multipart", "save_parts": "mesh.multipart",
    "live_control": "live",
}
# Subpackages imported on first use that are called like functions: sg.studio(scene).
_CALLABLE_PACKAGES = ("studio",)


def __getattr__(name: str) -> object:
    if name in _CALLABLE_PACKAGES:
        import importlib
        return importlib.import_module(f".{name}", __name__)  # the import binds sdfgl.<name>
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'sdfgl' has no attribute {name!r}")
    import importlib
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY) | set(_CALLABLE_PACKAGES))


def show(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (960, 540), *,
         window: bool | None = None, meshes: _Sequence[RasterMesh] = (), **settings: object) -> object:
    """Open an interactive window on ``scene``; returns when it is closed.

    In a Jupyter kernel a window would block the kernel, so ``show`` returns the notebook
    widget instead (:func:`widget`; it displays as the cell's result).

    Args:
        scene: the scene node.
        camera: the starting camera (default: one framing the scene).
        size: window size (width, height) in pixels.
        window: True opens the window even in a kernel; False returns the widget; None
            (default) picks by where the code runs.
        meshes: triangle meshes made by :func:`raster`, drawn by rasterisation in the window
            as in ``render(scene, meshes=...)`` (the notebook widget does not draw them).
        settings: render settings, as for :func:`render`.

    The window needs a display (glfw). Mouse: orbit, pan, zoom; keys toggle AA, shadows,
    AO, method, ground and debug views (``sdfgl view --help`` lists them).

    Example:
        >>> sg.show(sg.sphere(1) | sg.box(1.5))  # doctest: +SKIP
    """
    from .web.notebook import in_kernel
    if window is None:
        window = not in_kernel()
    if not window:
        if meshes:
            raise ParameterError("show: raster meshes are drawn in the native window only; pass window=True")
        return widget(scene, camera, size, **settings)
    from .viewer import show as _show
    _show(scene, camera, size, meshes=meshes, **settings)
    return None


def widget(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (640, 400), **settings: object):
    """An interactive Jupyter view of ``scene``, synced with Python (see :func:`sdfgl.web.widget.widget`).

    Orbit, pan and zoom with the mouse, toggle AA, shadows, AO and debug views with keys,
    and move a slider per ``sg.param`` (spanning its ``range``). ``w.camera`` is the current
    view; setting it, or a parameter's ``.value``, updates the view. Needs the ``web``
    extra (anywidget).

    Args:
        scene: the scene node.
        camera: the starting camera (default: one framing the scene).
        size: view size (width, height) in pixels.
        settings: render settings, as for :func:`render` (``aa``, ``shadows``, ``ao`` and
            ``debug`` are the toggles' starting states).

    Example:
        >>> r = sg.param(1.0, "r", range=(0.5, 1.5))
        >>> w = sg.widget(sg.sphere(r), size=(320, 200))  # doctest: +SKIP
        >>> w  # doctest: +SKIP
    """
    from .web.widget import widget as _widget
    return _widget(scene, camera, size, **settings)


def save_html(scene: Node, path: str, camera: Camera | None = None, size: tuple[int, int] = (800, 500),
              **settings: object):
    """Write a one-file interactive WebGL2 view of ``scene`` (see :func:`sdfgl.web.html.save_html`).

    The page needs no network and no Python: it draws the same generated shader in GLSL
    ES 3.00, with the mouse, keys and sliders of :func:`widget`.

    Args:
        scene: the scene node.
        path: the HTML file to write.
        camera: the starting camera (default: one framing the scene).
        size: view size (width, height) in pixels.
        settings: render settings, as for :func:`render`; ``title=`` sets the page title.

    Returns the path written.

    Example:
        >>> import pathlib, tempfile
        >>> out = pathlib.Path(tempfile.mkdtemp()) / "ball.html"
        >>> sg.save_html(sg.sphere(1), out, size=(200, 120)).stat().st_size > 10_000
        True
    """
    from .web.html import save_html as _save_html
    return _save_html(scene, path, camera, size, **settings)


def set_preview(enabled: bool = True, size: tuple[int, int] | None = None) -> None:
    """Turn the inline notebook preview of nodes on or off (see :func:`sdfgl.web.notebook.set_preview`).

    A node shown as a notebook cell's result is a small render (``_repr_png_``);
    ``SDFGL_PREVIEW=0`` in the environment starts with it off.

    Args:
        enabled: True shows nodes as images, False as text.
        size: the preview's (width, height) in pixels, 16..2048 (None keeps it).

    Example:
        >>> sg.set_preview(False)
        >>> sg.sphere(1)._repr_png_() is None
        True
        >>> sg.set_preview(True, size=(256, 160))
    """
    from .web.notebook import set_preview as _set_preview
    _set_preview(enabled, size)


def render_pbr(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (640, 480), spp: int = 64,
               **options: object):  # -> sdfgl.pbr.PBRImage
    """Path-trace ``scene`` through Mitsuba 3 (extra ``sdfgl[pbr]``); see :func:`sdfgl.pbr.render_pbr`.

    Args:
        scene: the node to render; by ``geometry=`` meshed by sdfgl's mesh export ("mesh",
            the default for bounded scenes) or sampled by the generated map() into Mitsuba
            ``sdfgrid`` tiles ("grid"; any exactness class works: only the sign matters).
        camera: an sdfgl camera (default: the framing ``render()`` uses); perspective or
            orthographic.
        size: (width, height) in pixels.
        spp: samples per pixel.
        options: ``geometry`` ("auto", "mesh" or "grid"), ``resolution``, ``quality``,
            ``bounds``, ``material``, ``sky``, ``sun``, ``ground``, ``max_depth``, ``extra``,
            ``seed``, ``variant``, ``progress``.

    Example:
        >>> img = sg.render_pbr(sg.sphere(1), size=(16, 12), spp=1)
        >>> img.alpha.shape, img.settings["geometry"]
        ((12, 16), 'mesh')
    """
    from .pbr import render_pbr as _render_pbr
    from .pbr.render import RENDER_OPTIONS, check_options
    check_options("render_pbr", options, RENDER_OPTIONS)
    return _render_pbr(scene, camera, size, spp, **options)  # type: ignore[arg-type]


def to_mitsuba(scene: Node, camera: Camera | None = None, **options: object) -> dict:
    """The Mitsuba 3 scene dictionary of ``scene`` (``mi.load_dict`` it, extend it by hand);
    see :func:`sdfgl.pbr.to_mitsuba`.

    Args:
        scene: the node to convert.
        camera: an sdfgl camera (default: the framing ``render()`` uses).
        options: as :func:`render_pbr` (``size``, ``spp``, ``material``, ...).

    Example:
        >>> d = sg.to_mitsuba(sg.sphere(1), size=(8, 8), spp=1, geometry="grid")
        >>> d["sdf_0"]["type"], d["sdf_bsdf"]["type"]
        ('sdfgrid', 'diffuse')
    """
    from .pbr import to_mitsuba as _to_mitsuba
    return _to_mitsuba(scene, camera, **options)  # type: ignore[arg-type]


X = _np.array([1.0, 0.0, 0.0])
Y = _np.array([0.0, 1.0, 0.0])
Z = _np.array([0.0, 0.0, 1.0])

__all__ = [
    "Camera", "OrbitCamera", "compile", "directional_light", "point_light", "render", "show", "widget", "save_html",
    "set_preview", "param", "Param", "Renderer", "RenderResult", "Node",
    "sphere", "box", "rounded_box", "plane", "torus", "capsule", "cylinder", "cone", "ellipsoid",
    "octahedron", "hex_prism", "box_frame", "product", "twist", "bend", "repeat", "evaluate", "union",
    "circle", "rectangle", "polygon", "extrude", "revolve", "mirror", "symmetric", "repeat_polar", "elongate",
    "rounded", "shell", "sierpinski", "tree", "displace", "noise", "implicit", "parametric", "displace_expr", "intersection", "difference", "X", "Y", "Z",
    "EXACT", "BOUND", "IMPLICIT", "SdfglError", "ParameterError", "MeshError", "ShaderCompileError", "ContextError",
    "render_pbr", "to_mitsuba",
    "SceneFileError", "SceneDocumentError", "save_scene", "load_scene", "from_dict",
    "load_mesh", "from_mesh", "raster", "RasterMesh",
    "Shape2D", "arc", "capsule2", "ellipse", "regular_polygon", "star", "triangle", "slice", "text",
    "bezier_tube", "capped_torus", "dodecahedron", "gyroid", "icosahedron", "pyramid", "slab", "tetrahedron", "tube",
    "morph", "taper", "glsl",
    "time", "keyframes", "turntable", "camera_path", "animate", "sin", "cos", "tan", "abs", "sqrt", "exp", "log",
    "sign", "floor", "fract", "radians", "min", "max", "pow", "mod", "step", "clamp", "mix", "smoothstep",
    "mesh", "Mesh", "save_3mf", "save_parts", "cache_budget", "CacheBudget", "live_control",
]

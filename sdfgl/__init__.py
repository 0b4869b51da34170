"""sdfgl: signed-distance-function scenes in Python, rendered by generated GLSL.

    import sdfgl as sg
    s = sg.sphere(1) & sg.box(1.5)
    sg.render(s, camera=sg.OrbitCamera(distance=5), size=(800, 600), aa=2).save("out.png")
"""
import numpy as _np

from .camera import Camera, OrbitCamera
from .codegen import compile
from .errors import ContextError, ParameterError, SceneFileError, SdfglError, ShaderCompileError
from .evaluate import evaluate
from .look import directional_light, point_light
from . import mesh  # the package is callable: sg.mesh(scene, step=0.01)
from .mesh import Mesh
from .nodes import (BOUND, EXACT, IMPLICIT, Node, bend, box, box_frame, capsule, circle, displace, elongate, extrude,
                    displace_expr, implicit, noise, parametric,
                    mirror, polygon, rectangle, repeat_polar, revolve, rounded, shell, sierpinski, symmetric, tree, cone, cylinder, difference, ellipsoid,
                    hex_prism, intersection, octahedron, plane, product, repeat, rounded_box, sphere, torus, twist,
                    union, Shape2D, arc, capsule2, ellipse, regular_polygon, star, triangle, slice,
                    bezier_tube, capped_torus, dodecahedron, gyroid, icosahedron, pyramid, slab, tetrahedron, tube,
                    morph, taper, glsl)
from .params import Param, param, time
from .functions import (abs, clamp, cos, exp, floor, fract, log, max, min, mix, mod, pow, radians, sign, sin,
                        smoothstep, sqrt, step, tan)
from .animate import animate, camera_path, keyframes, turntable
from .render import RenderResult, Renderer, render


def show(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (960, 540), *,
         window: bool | None = None, **settings: object) -> object:
    """Open an interactive window on ``scene`` (needs a display); returns when it is closed.

    In a Jupyter kernel a window would block the kernel, so ``show`` returns the notebook
    widget instead (``sg.widget``; it displays as the cell's result); ``window=True``
    opens the window anyway.
    """
    from .web.notebook import in_kernel
    if window is None:
        window = not in_kernel()
    if not window:
        return widget(scene, camera, size, **settings)
    from .viewer import show as _show
    _show(scene, camera, size, **settings)
    return None


def widget(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (640, 400), **settings: object):
    """An interactive Jupyter view of ``scene``, synced with Python (see :func:`sdfgl.web.widget.widget`);
    needs the ``web`` extra (anywidget)."""
    from .web.widget import widget as _widget
    return _widget(scene, camera, size, **settings)


def save_html(scene: Node, path: str, camera: Camera | None = None, size: tuple[int, int] = (800, 500),
              **settings: object):
    """Write a one-file interactive WebGL2 view of ``scene`` (see :func:`sdfgl.web.html.save_html`)."""
    from .web.html import save_html as _save_html
    return _save_html(scene, path, camera, size, **settings)


def set_preview(enabled: bool = True, size: tuple[int, int] | None = None) -> None:
    """Turn the inline notebook preview of nodes on or off (see :func:`sdfgl.web.notebook.set_preview`)."""
    from .web.notebook import set_preview as _set_preview
    _set_preview(enabled, size)


def render_pbr(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (640, 480), spp: int = 64,
               **options: object):  # -> sdfgl.pbr.PBRImage
    """Path-trace ``scene`` through Mitsuba 3 (extra ``sdfgl[pbr]``); see :func:`sdfgl.pbr.render_pbr`."""
    from .pbr import render_pbr as _render_pbr
    return _render_pbr(scene, camera, size, spp, **options)  # type: ignore[arg-type]


def to_mitsuba(scene: Node, camera: Camera | None = None, **options: object) -> dict:
    """The Mitsuba 3 scene dictionary of ``scene``; see :func:`sdfgl.pbr.to_mitsuba`."""
    from .pbr import to_mitsuba as _to_mitsuba
    return _to_mitsuba(scene, camera, **options)  # type: ignore[arg-type]


X = _np.array([1.0, 0.0, 0.0])
Y = _np.array([0.0, 1.0, 0.0])
Z = _np.array([0.0, 0.0, 1.0])

__version__ = "0.1.0"

__all__ = [
    "Camera", "OrbitCamera", "compile", "directional_light", "point_light", "render", "show", "widget", "save_html",
    "set_preview", "param", "Param", "Renderer", "RenderResult", "Node",
    "sphere", "box", "rounded_box", "plane", "torus", "capsule", "cylinder", "cone", "ellipsoid",
    "octahedron", "hex_prism", "box_frame", "product", "twist", "bend", "repeat", "evaluate", "union",
    "circle", "rectangle", "polygon", "extrude", "revolve", "mirror", "symmetric", "repeat_polar", "elongate",
    "rounded", "shell", "sierpinski", "tree", "displace", "noise", "implicit", "parametric", "displace_expr", "intersection", "difference", "X", "Y", "Z",
    "EXACT", "BOUND", "IMPLICIT", "SdfglError", "ParameterError", "ShaderCompileError", "ContextError",
    "render_pbr", "to_mitsuba",
    "SceneFileError", "Shape2D", "arc", "capsule2", "ellipse", "regular_polygon", "star", "triangle", "slice",
    "bezier_tube", "capped_torus", "dodecahedron", "gyroid", "icosahedron", "pyramid", "slab", "tetrahedron", "tube",
    "morph", "taper", "glsl",
    "time", "keyframes", "turntable", "camera_path", "animate", "sin", "cos", "tan", "abs", "sqrt", "exp", "log",
    "sign", "floor", "fract", "radians", "min", "max", "pow", "mod", "step", "clamp", "mix", "smoothstep",
    "mesh", "Mesh",
]

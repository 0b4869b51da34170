"""sdfgl: signed-distance-function scenes in Python, rendered by generated GLSL.

    import sdfgl as sg
    s = sg.sphere(1) & sg.box(1.5)
    sg.render(s, camera=sg.OrbitCamera(distance=5), size=(800, 600), aa=2).save("out.png")
"""
import numpy as _np

from .camera import Camera, OrbitCamera
from .codegen import compile
from .errors import (ContextError, ParameterError, SceneDocumentError, SceneFileError, SdfglError,
                     ShaderCompileError)
from .nodes import (BOUND, EXACT, IMPLICIT, Node, bend, box, box_frame, capsule, circle, displace, elongate, extrude,
                    displace_expr, implicit, noise, parametric,
                    mirror, polygon, rectangle, repeat_polar, revolve, rounded, shell, sierpinski, symmetric, tree, cone, cylinder, difference, ellipsoid,
                    hex_prism, intersection, octahedron, plane, product, repeat, rounded_box, sphere, torus, twist,
                    union)
from .evaluate import evaluate
from .params import Param, param
from .render import RenderResult, Renderer, render
from .version import __version__

# Imported on first use, so that `import sdfgl` stays fast: name -> module. A heavy new
# public name adds one line here (a name must differ from its module's, or importing the
# module would replace it).
_LAZY = {
    "save_scene": "scene_io", "load_scene": "scene_io", "from_dict": "scene_io",
}


def __getattr__(name: str) -> object:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'sdfgl' has no attribute {name!r}")
    import importlib
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


def show(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (960, 540), **settings: object) -> None:
    """Open an interactive window on ``scene``; returns when it is closed.

    Args:
        scene: the scene node.
        camera: the starting camera (default: one framing the scene).
        size: window size (width, height) in pixels.
        settings: render settings, as for :func:`render`.

    Needs a display (glfw). Mouse: orbit, pan, zoom; keys toggle AA, shadows, AO, method,
    ground and debug views (``sdfgl view --help`` lists them).

    Example:
        >>> sg.show(sg.sphere(1) | sg.box(1.5))  # doctest: +SKIP
    """
    from .viewer import show as _show
    _show(scene, camera, size, **settings)


X = _np.array([1.0, 0.0, 0.0])
Y = _np.array([0.0, 1.0, 0.0])
Z = _np.array([0.0, 0.0, 1.0])

__all__ = [
    "Camera", "OrbitCamera", "compile", "render", "show", "param", "Param", "Renderer", "RenderResult", "Node",
    "sphere", "box", "rounded_box", "plane", "torus", "capsule", "cylinder", "cone", "ellipsoid",
    "octahedron", "hex_prism", "box_frame", "product", "twist", "bend", "repeat", "evaluate", "union",
    "circle", "rectangle", "polygon", "extrude", "revolve", "mirror", "symmetric", "repeat_polar", "elongate",
    "rounded", "shell", "sierpinski", "tree", "displace", "noise", "implicit", "parametric", "displace_expr", "intersection", "difference", "X", "Y", "Z",
    "EXACT", "BOUND", "IMPLICIT", "SdfglError", "ParameterError", "ShaderCompileError", "ContextError",
    "SceneFileError", "SceneDocumentError", "save_scene", "load_scene", "from_dict",
]

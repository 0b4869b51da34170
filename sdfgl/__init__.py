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
from .gl.cache import CacheBudget, cache_budget
from .nodes import (BOUND, EXACT, IMPLICIT, Node, bend, box, box_frame, capsule, circle, displace, elongate, extrude,
                    displace_expr, implicit, noise, parametric,
                    mirror, polygon, rectangle, repeat_polar, revolve, rounded, shell, sierpinski, symmetric, tree, cone, cylinder, difference, ellipsoid,
                    hex_prism, intersection, octahedron, plane, product, repeat, rounded_box, sphere, torus, twist,
                    union)
from .params import Param, param
from .render import RenderResult, Renderer, render


def show(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (960, 540), **settings: object) -> None:
    """Open an interactive window on ``scene`` (needs a display); returns when it is closed."""
    from .viewer import show as _show
    _show(scene, camera, size, **settings)


X = _np.array([1.0, 0.0, 0.0])
Y = _np.array([0.0, 1.0, 0.0])
Z = _np.array([0.0, 0.0, 1.0])

__version__ = "0.1.0"

__all__ = [
    "Camera", "OrbitCamera", "compile", "render", "show", "param", "Param", "Renderer", "RenderResult", "Node",
    "sphere", "box", "rounded_box", "plane", "torus", "capsule", "cylinder", "cone", "ellipsoid",
    "octahedron", "hex_prism", "box_frame", "product", "twist", "bend", "repeat", "evaluate", "union",
    "circle", "rectangle", "polygon", "extrude", "revolve", "mirror", "symmetric", "repeat_polar", "elongate",
    "rounded", "shell", "sierpinski", "tree", "displace", "noise", "implicit", "parametric", "displace_expr", "intersection", "difference", "X", "Y", "Z",
    "EXACT", "BOUND", "IMPLICIT", "SdfglError", "ParameterError", "ShaderCompileError", "ContextError",
    "SceneFileError", "cache_budget", "CacheBudget",
]

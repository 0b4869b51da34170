"""The scene graph: one module per family of nodes."""
from . import material, transforms  # noqa: F401 - they register Node.translate, .rotate, .color, .material, ...
from .base import BOUND, EXACT, IMPLICIT, Node, Primitive
from .booleans import difference, intersection, product, union
from .deform import bend, twist
from .domain import repeat
from .fractals import sierpinski, tree
from .implicit import displace_expr, implicit, parametric
from .noise import displace, noise
from .shapes2d import Shape2D, circle, extrude, polygon, rectangle, revolve
from .shapes2d_figures import arc, capsule2, ellipse, regular_polygon, star, triangle
from .shapes2d_ops import slice
from .text import text
from .gyroid import gyroid
from .polyhedra import dodecahedron, icosahedron, pyramid, slab, tetrahedron
from .sweeps import bezier_tube, capped_torus, tube
from .operators import morph
from .deform import taper
from .user_glsl import glsl
from .shaping import elongate, mirror, repeat_polar, rounded, shell, symmetric
from .primitives import (box, box_frame, capsule, cone, cylinder, ellipsoid, hex_prism, octahedron, plane,
                         rounded_box, sphere, torus)

__all__ = ["Node", "Primitive", "EXACT", "BOUND", "IMPLICIT", "sphere", "box", "rounded_box", "plane",
           "torus", "capsule", "cylinder", "cone", "ellipsoid", "octahedron", "hex_prism", "union",
           "intersection", "difference", "box_frame", "product", "twist", "bend", "repeat",
           "sierpinski", "tree", "circle", "rectangle", "polygon", "extrude", "revolve", "mirror", "symmetric",
           "repeat_polar", "elongate", "rounded", "shell", "displace", "noise", "implicit", "parametric", "displace_expr",
           "Shape2D", "arc", "capsule2", "ellipse", "regular_polygon", "star", "triangle", "slice", "text",
           "bezier_tube", "capped_torus", "dodecahedron", "gyroid", "icosahedron", "pyramid", "slab",
           "tetrahedron", "tube", "morph", "taper", "glsl"]

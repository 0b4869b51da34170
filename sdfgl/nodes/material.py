"""Surface materials: colour, specular, roughness or shininess, metallic, emission.

A material node is free in map(): like ``.color()``, it only changes what the colour
passes return at the hit, and like colour each field is carried through booleans (the
innermost node that sets a field wins) and mixed continuously by smooth blends.
"""
from __future__ import annotations

from typing import Any

from ..errors import ParameterError
from ..values import validate as v
from .base import Node, Unary, fluent
from .transforms import Material, fold_material

SHININESS_RANGE = (1.0, 10000.0)
ROUGHNESS_MIN = 0.05


def roughness_to_shininess(roughness: float) -> float:
    """Blinn-Phong exponent of a roughness in [0.05, 1]: 2 / r^4 - 2 (Beckmann alpha = r^2),
    at least 1."""
    return max(2.0 / roughness ** 4 - 2.0, SHININESS_RANGE[0])


class SurfaceMaterial(Material):
    """Colour plus surface fields for every part of the child that does not set them itself."""

    kind = "material"

    def __init__(self, child: Node, color: Any = None, *, specular: Any = None, roughness: Any = None,
                 shininess: Any = None, metallic: Any = None, emission: Any = None) -> None:
        k = self.kind
        if roughness is not None and shininess is not None:
            raise ParameterError(f"{k}: give 'roughness' or 'shininess', not both")
        params: dict[str, Any] = {}
        fields: dict[str, Any] = {}
        if color is not None:
            params["color"] = fields["albedo"] = v.color(k, color)
        if specular is not None:
            params["specular"] = fields["specular"] = v.scalar(k, "specular", specular, nonnegative=True)
        if roughness is not None:
            v.fixed(k, "it is turned into a shininess exponent when the node is built", roughness=roughness)
            r = v.scalar(k, "roughness", roughness)
            if not ROUGHNESS_MIN <= r <= 1.0:
                raise ParameterError(f"{k}: parameter 'roughness' must lie in [{ROUGHNESS_MIN:g}, 1], got {r:g}")
            params["roughness"] = r
            fields["shininess"] = roughness_to_shininess(r)
        if shininess is not None:
            sh = params["shininess"] = fields["shininess"] = v.scalar(k, "shininess", shininess)
            lo, hi = SHININESS_RANGE
            v.watch(lambda: _in_range(k, "shininess", float(sh), lo, hi), sh)
        if metallic is not None:
            m = params["metallic"] = fields["metallic"] = v.scalar(k, "metallic", metallic)
            v.watch(lambda: _in_range(k, "metallic", float(m), 0.0, 1.0), m)
        if emission is not None:
            params["emission"] = fields["emission"] = v.color(k, emission, "emission")
        if not params:
            raise ParameterError(f"{k}: give at least one of color, specular, roughness, shininess, metallic, "
                                 f"emission")
        Unary.__init__(self, child, **params)
        self.rgb = fields.get("albedo")
        self.fields = fields
        self.surface = any(n != "albedo" for n in fields)


def _in_range(node: str, name: str, x: float, lo: float, hi: float) -> None:
    if not lo <= x <= hi:
        raise ParameterError(f"{node}: parameter '{name}' must lie in [{lo:g}, {hi:g}], got {x:g}")


@fluent()
def material(node: Node, color: object = None, *, specular: object = None, roughness: object = None,
             shininess: object = None, metallic: object = None, emission: object = None) -> Node:
    """Give every part of ``node`` that does not set them itself these material fields.

    ``color`` as for :meth:`sdfgl.Node.color`; ``specular`` (>= 0, default 0.25) scales the
    highlight; ``roughness`` in [0.05, 1] or ``shininess`` (the Blinn-Phong exponent,
    1..10000, default 48) sets its size; ``metallic`` in [0, 1] tints the highlight by
    the colour and removes the diffuse part; ``emission`` a colour added unlit. Fields
    left out keep what an outer node (or the default) says.
    """
    return fold_material(SurfaceMaterial(node, color, specular=specular, roughness=roughness, shininess=shininess,
                                         metallic=metallic, emission=emission))


__all__ = ["SurfaceMaterial", "material", "roughness_to_shininess"]

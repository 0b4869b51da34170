"""Surface terms of a path-traced render, and their Mitsuba BSDFs.

A :class:`Material` chooses among Mitsuba's ``diffuse``, ``roughplastic``,
``roughconductor`` / ``conductor`` and ``roughdielectric`` / ``dielectric`` by its terms;
its colour is either given or taken from the scene's colour field (sampled on a grid
by the same generated ``mapColor()`` that shades the real-time image). A :class:`Blend`
is an SDF material in the manner of the Mitsuba plug-in thesis (see the docs' sources): two materials mixed across the zero set of another
field (``boundary``), continuously over ``width`` — rock below a plane and snow above it,
or a painted and a bare metal split by noise.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Union

import numpy as np

from ..errors import ParameterError
from ..nodes.base import Node

SMOOTH_ROUGHNESS = 0.02  # below this a material is a perfectly smooth interface


def _unit(name: str, value: float, lo: float = 0.0, hi: float = 1.0) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"pbr material: parameter '{name}' must be a number, got {value!r}") from None
    if not (lo <= x <= hi):
        raise ParameterError(f"pbr material: parameter '{name}' must lie in [{lo:g}, {hi:g}], got {value!r}")
    return x


@dataclass(frozen=True)
class Material:
    """Physically based surface terms.

    color: linear albedo (r, g, b) in [0, 1], or None for the scene's own colours.
    roughness: 0 (polished) .. 1 (matte); Mitsuba's microfacet alpha is roughness ** 2.
    specular: 0 for a purely diffuse surface; above 0 a dielectric coating
        (``roughplastic`` whose strength follows ``ior``; ``principled`` with this
        specular weight when the colour comes from the scene).
    metallic: 1 for metal (``roughconductor`` tinted by the colour); 0 otherwise.
    transmission: 1 for glass (``roughdielectric`` with ``ior``); 0 otherwise.
    ior: index of refraction of coatings and glass (1 .. 3).

    Example: ``Material(color=(0.9, 0.6, 0.2), metallic=1, roughness=0.3)`` is brushed gold.
    """

    color: tuple[float, float, float] | None = None
    roughness: float = 0.5
    specular: float = 0.0
    metallic: float = 0.0
    transmission: float = 0.0
    ior: float = 1.5

    def __post_init__(self) -> None:
        if self.color is not None:
            try:
                rgb = tuple(float(c) for c in self.color)  # type: ignore[union-attr]
            except (TypeError, ValueError):
                rgb = ()
            if len(rgb) != 3 or not all(0.0 <= c <= 1.0 for c in rgb):
                raise ParameterError(f"pbr material: parameter 'color' must be three numbers in [0, 1], "
                                     f"got {self.color!r}")
            object.__setattr__(self, "color", rgb)
        for name in ("roughness", "specular", "metallic", "transmission"):
            object.__setattr__(self, name, _unit(name, getattr(self, name)))
        object.__setattr__(self, "ior", _unit("ior", self.ior, 1.0, 3.0))

    @property
    def kind(self) -> str:
        """The Mitsuba BSDF family: "dielectric", "conductor", "plastic" or "diffuse"."""
        if self.transmission >= 0.5:
            return "dielectric"
        if self.metallic >= 0.5:
            return "conductor"
        if self.specular > 0.0:
            return "plastic"
        return "diffuse"


@dataclass(frozen=True)
class Blend:
    """``inside`` where ``boundary`` is negative, ``outside`` where it is positive, mixed
    smoothly (smoothstep) over ``width`` either side of its zero set."""

    inside: "Look"
    outside: "Look"
    boundary: Node
    width: float = 0.05
    kind = "blend"

    def __post_init__(self) -> None:
        for name in ("inside", "outside"):
            if not isinstance(getattr(self, name), (Material, Blend, SceneMaterial)):
                raise ParameterError(f"pbr blend: '{name}' must be a Material or Blend, got "
                                     f"{type(getattr(self, name)).__name__}")
        if not isinstance(self.boundary, Node):
            raise ParameterError(f"pbr blend: 'boundary' must be an sdfgl node, got {type(self.boundary).__name__}")
        w = float(self.width) if isinstance(self.width, (int, float)) else float("nan")
        if not (w > 0 and math.isfinite(w)):
            raise ParameterError(f"pbr blend: parameter 'width' must be a finite number > 0, got {self.width!r}")


@dataclass(frozen=True)
class SceneMaterial:
    """The scene's own node materials (``.material(...)``): a ``principled`` BSDF whose base
    colour, roughness and metallic vary over the surface as the generated mapColor() and
    mapSurface() give them (the default when some node sets specular, shininess or metallic)."""

    kind: str = "principled"


Look = Union[Material, Blend, SceneMaterial]

# texture factories the scene builder supplies: the scene's albedo field, a blend weight
# field, and the scene's (roughness texture, metallic texture, specular) from its materials
AlbedoTexture = Callable[[], dict]
WeightTexture = Callable[[Node, float], dict]
SurfaceTextures = Callable[[], tuple[dict, dict, float]]


def surface_terms(fields: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """(roughness, metallic, specular) from mapSurface() samples (..., 3) of (specular,
    shininess, metallic): Blinn-Phong shininess n -> Beckmann alpha sqrt(2 / (n + 2)) ->
    roughness sqrt(alpha); specular is twice the median weight (the real-time default 0.25
    becomes the principled default 0.5)."""
    rough = np.clip((2.0 / (np.maximum(fields[..., 1], 0.0) + 2.0)) ** 0.25, 0.0, 1.0)
    return rough, np.clip(fields[..., 2], 0.0, 1.0), float(np.clip(2 * np.median(fields[..., 0]), 0, 1))


def blend_weight(values: np.ndarray, width: float) -> np.ndarray:
    """A Blend's weight of its ``outside`` material from its boundary field's values:
    smoothstep over ``width`` either side of the zero set, float32."""
    t = np.clip((np.asarray(values, np.float64) + width) / (2 * width), 0, 1)
    return (t * t * (3 - 2 * t)).astype(np.float32)


def bsdf(look: Look, albedo: AlbedoTexture, weight: WeightTexture, surface: SurfaceTextures) -> dict[str, Any]:
    """The Mitsuba BSDF dictionary of ``look``."""
    if isinstance(look, Blend):
        return {"type": "blendbsdf", "weight": weight(look.boundary, look.width),
                "bsdf_0": bsdf(look.inside, albedo, weight, surface),
                "bsdf_1": bsdf(look.outside, albedo, weight, surface)}
    if isinstance(look, SceneMaterial):
        rough, metal, spec = surface()
        return {"type": "principled", "base_color": albedo(), "roughness": rough, "metallic": metal, "specular": spec}
    color: Any = {"type": "rgb", "value": list(look.color)} if look.color is not None else albedo()
    alpha = look.roughness ** 2
    smooth = look.roughness < SMOOTH_ROUGHNESS
    kind = look.kind
    if kind == "dielectric":
        out: dict[str, Any] = {"type": "dielectric" if smooth else "roughdielectric", "int_ior": look.ior,
                               "ext_ior": 1.0}
        if look.color is not None:
            out["specular_transmittance"] = color
        if not smooth:
            out["alpha"] = alpha
        return out
    if kind == "conductor":
        out = {"type": "conductor" if smooth else "roughconductor", "material": "none",
               "specular_reflectance": color}
        if not smooth:
            out["alpha"] = alpha
        return out
    if kind == "plastic":
        if look.color is None:  # Mitsuba's plastics need a texture's mean, which a volume texture lacks
            return {"type": "principled", "base_color": color, "roughness": look.roughness,
                    "specular": look.specular, "metallic": 0.0}
        return {"type": "roughplastic", "diffuse_reflectance": color, "alpha": max(alpha, 1e-4),
                "int_ior": 1.0 + (look.ior - 1.0) * look.specular, "nonlinear": True}
    return {"type": "diffuse", "reflectance": color}

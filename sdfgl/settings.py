"""Render settings: validated once, turned into #defines by the code generator."""
from __future__ import annotations

from dataclasses import dataclass, field, fields, replace
from typing import Any

from .errors import ParameterError

OUTPUTS = ("color", "depth", "normal", "steps")
SHADOWS = (False, "hard", "soft")
METHODS = ("auto", "sphere", "relaxed", "enhanced", "newton", "forward_newton", "reference")
# methods that step by the field value and so need a distance bound
DISTANCE_METHODS = ("auto", "sphere", "relaxed", "enhanced")
DEFAULT_OMEGA = {"relaxed": 1.6, "enhanced": 0.9}
HIT_MODES = ("cone", "relative", "absolute")
DEBUG_VIEWS = (None, "steps", "normal", "depth", "select")
COARSE_TILES = (4, 8, 16)  # pixels a side of the coarse pass's tiles
DEFAULT_COARSE_TILE = 8
# Settings become float32 literals and uniforms: magnitudes must stay inside what float32
# holds (3.4e38) with room for the shader's arithmetic, and below its stand-in for infinity
# (sdfgl.compiler.analysis.GLSL_FAR, 1e30); positive ones must not round to zero (float32's smallest normal is 1.2e-38).
F32_SETTING_MAX = 1e29
F32_SETTING_MIN = 1e-30


def float32_setting(name: str, val: Any, lo: float = 0.0, inclusive: bool = False) -> float:
    """``val`` as a float if it is a real number above ``lo`` that float32 arithmetic can hold."""
    if isinstance(val, bool) or not isinstance(val, (int, float)):
        raise ParameterError(f"setting '{name}' must be a number, got {type(val).__name__} {val!r}")
    v = float(val)
    if v != v or v in (float("inf"), float("-inf")):
        raise ParameterError(f"setting '{name}' must be finite, got {val!r}")
    if not (v >= lo if inclusive else v > lo):
        raise ParameterError(f"setting '{name}' must be {'>=' if inclusive else '>'} {lo:g}, got {val!r}")
    if abs(v) > F32_SETTING_MAX:
        raise ParameterError(f"setting '{name}' must be at most {F32_SETTING_MAX:g} (the shader computes in float32, "
                             f"which holds up to 3.4e38, and uses 1e30 as infinity), got {val!r}")
    if v != 0 and abs(v) < F32_SETTING_MIN:
        raise ParameterError(f"setting '{name}' must be at least {F32_SETTING_MIN:g} (smaller values round to 0 or "
                             f"lose all precision in float32), got {val!r}")
    return v


@dataclass(frozen=True)
class Settings:
    """Everything that changes the generated shader besides the scene itself.

    aa: samples per pixel side (1..4, so 1 to 16 rays a pixel).
    shadows: False, "hard" or "soft" (Inigo Quilez's improved penumbra).
    ao: 5-tap ambient occlusion along the normal.
    ground: an analytic ground plane under the scene (intersected, not marched).
    method: the marching algorithm: "auto" (the default: "enhanced" for exact and bound
        fields, "newton" for implicit ones; resolved per scene, and the result's settings
        show the choice), "sphere" (Hart), "relaxed" (Keinert et al.),
        "enhanced" (Balint & Valasek), "newton", "forward_newton" (Monzón González's thesis) or
        "reference" (fixed small steps and bisection, for validation).
    omega: relaxation of "relaxed" (in (1, 2), default 1.6) or "enhanced" (in (0, 1],
        default 0.9); None for the default.
    ref_step: the step of "reference" (default: the scene size / 512).
    newton_cap: the Newton methods' step is at most this many times the field value
        (default 2; None for the uncapped Newton step of Monzón González's thesis).
    max_steps: the marching budget of a primary ray: loop rounds away from surfaces (one
        map() call each, a few more with a probe); the rounds that settle a ray near a
        surface (near misses) are counted apart, up to 2 max_steps rounds in all.
    hit: "cone" (distance below hit_scale pixel footprints), "relative" (below
        hit_scale * t) or "absolute" (below hit_scale).
    hit_scale: the factor of the hit test.
    max_dist: far limit along a ray where the scene is unbounded (a bounded scene is
        marched to the far side of its box, whatever max_dist says).
    outputs: which images the draw writes (color always).
    debug: None, or a debug view shown instead of the shaded image: "steps" (heat map of
        map() calls), "normal", "depth" or "select" (grey, tinted where the subtree given to
        generate() as ``highlight`` is the nearest surface; the viewer's scene tree uses it).
    grid: keep big unions of simple primitives as data with a cell grid (False writes
        them out as code, to compare; "bvh" traverses a bounding volume hierarchy instead
        of the cells: the measured alternative, slower here, see the benchmark).
    analytic: intersect a lone sphere or plane in closed form instead of marching it.
    free_way: where the scene is a union kept as data or one triangle mesh, sphere tracing
        and its relaxed variants also step the way its lists (or a cast through the mesh's
        triangles) prove empty along the ray (False: their own steps only, to compare).
    grid_min: the fewest instances a hard union keeps as data (None: automatic, 32, or 8
        once the scene's code passes code_budget; the result's settings say which).
    code_budget: characters of generated scene code (map(), mapColor() and their
        functions) past which unions and big constant tables become data by themselves.
    lights: None (the default rig: key light, back light) or a list of up to 8
        sg.directional_light / sg.point_light; each casts the shadow it names, or the
        ``shadows`` setting's where it names none.
    ambient: hemisphere light, a (sky, ground) pair of colours or one colour; None for
        the default (a blue sky, no ground bounce).
    background: None or "sky" (the default environment), a colour, or a (top, bottom)
        pair of colours (a vertical gradient over the image).
    alpha: an RGBA image whose alpha is the share of each pixel's samples that hit
        (colour un-premultiplied), so anti-aliased edges composite over anything.
    fog: None, or a distance d: surfaces fade into the background by 1 - exp(-t / d)
        (with alpha, they fade out).
    coarse: a coarse pass before the image: one cone a tile of pixels (True: 8 x 8, or
        4, 8 or 16 pixels a side) is sphere-traced to the depth before which no surface
        lies in it, where the tile's rays start marching (a tile the cone crosses empty
        skips the march); False: every ray marches from the scene box. Only sphere tracing
        and its relaxed variants use it (a distance bound is needed), never a closed form.
    """

    aa: int = 1
    shadows: Any = "soft"
    ao: bool = True
    ground: bool = False
    method: str = "auto"
    omega: Any = None
    ref_step: Any = None
    newton_cap: Any = 2.0
    max_steps: int = 256
    hit: str = "cone"
    hit_scale: float = 0.25
    max_dist: float = 1000.0
    outputs: tuple[str, ...] = field(default=("color",))
    debug: Any = None
    grid: bool = True
    analytic: bool = True
    free_way: bool = True
    grid_min: Any = None
    code_budget: int = 60000
    lights: Any = None
    ambient: Any = None
    background: Any = None
    alpha: bool = False
    fog: Any = None
    coarse: Any = True

    def __post_init__(self) -> None:
        if isinstance(self.aa, bool) or not isinstance(self.aa, int) or not 1 <= self.aa <= 4:
            raise ParameterError(f"setting 'aa' must be an integer 1..4, got {self.aa!r}")
        if self.shadows is True:
            object.__setattr__(self, "shadows", "soft")
        if self.shadows is None:
            object.__setattr__(self, "shadows", False)
        if self.shadows not in SHADOWS:
            raise ParameterError(f"setting 'shadows' must be False, 'hard' or 'soft', got {self.shadows!r}")
        for name in ("ao", "ground", "grid", "analytic", "free_way", "alpha"):
            if not isinstance(getattr(self, name), bool) and (name, getattr(self, name)) != ("grid", "bvh"):
                also = " or 'bvh'" if name == "grid" else ""
                raise ParameterError(f"setting '{name}' must be True or False{also}, got {getattr(self, name)!r}")
        if self.method not in METHODS:
            raise ParameterError(f"setting 'method' must be one of {', '.join(METHODS)}, got {self.method!r}")
        if self.omega is not None:
            lo_hi = {"relaxed": (1.0, 2.0), "enhanced": (0.0, 1.0), "auto": (0.0, 1.0)}.get(self.method)
            if lo_hi is None:
                raise ParameterError(f"setting 'omega' applies to methods 'relaxed' and 'enhanced', not {self.method!r}")
            ok = isinstance(self.omega, (int, float)) and not isinstance(self.omega, bool)
            if not ok or not (lo_hi[0] < float(self.omega) <= lo_hi[1]) or (self.method == "relaxed" and self.omega == 2):
                raise ParameterError(f"setting 'omega' for {self.method!r} must lie in ({lo_hi[0]:g}, {lo_hi[1]:g}"
                                     f"{')' if self.method == 'relaxed' else ']'}, got {self.omega!r}")
            object.__setattr__(self, "omega", float(self.omega))
        if self.ref_step is not None:
            object.__setattr__(self, "ref_step", float32_setting("ref_step", self.ref_step))
        if self.newton_cap is not None:
            object.__setattr__(self, "newton_cap", float32_setting("newton_cap", self.newton_cap, 1.0, inclusive=True))
        if isinstance(self.max_steps, bool) or not isinstance(self.max_steps, int) or not 1 <= self.max_steps <= 100000:
            raise ParameterError(f"setting 'max_steps' must be an integer 1..100000, got {self.max_steps!r}")
        if self.hit not in HIT_MODES:
            raise ParameterError(f"setting 'hit' must be one of {', '.join(HIT_MODES)}, got {self.hit!r}")
        for name in ("hit_scale", "max_dist"):
            object.__setattr__(self, name, float32_setting(name, getattr(self, name)))
        if self.debug not in DEBUG_VIEWS:
            raise ParameterError(f"setting 'debug' must be None, 'steps', 'normal', 'depth' or 'select', "
                                 f"got {self.debug!r}")
        for name, low in (("grid_min", 2), ("code_budget", 1000)):
            val = getattr(self, name)
            if (val is not None or name == "code_budget") and (isinstance(val, bool) or not isinstance(val, int)
                                                               or val < low):
                raise ParameterError(f"setting '{name}' must be an integer >= {low}"
                                     f"{' or None' if name == 'grid_min' else ''}, got {val!r}")
        if not isinstance(self.outputs, (str, list, tuple)):
            raise ParameterError(f"setting 'outputs' must be a name or a sequence of names from {', '.join(OUTPUTS)}, "
                                 f"got {self.outputs!r}")
        outs = (self.outputs,) if isinstance(self.outputs, str) else tuple(self.outputs)
        bad = [o for o in outs if o not in OUTPUTS]
        if bad:
            raise ParameterError(f"setting 'outputs' has unknown entries {bad}; choose from {', '.join(OUTPUTS)}")
        object.__setattr__(self, "outputs", tuple(o for o in OUTPUTS if o in outs or o == "color"))
        from .look.background import check_background
        from .look.lights import check_ambient, check_lights
        object.__setattr__(self, "lights", check_lights(self.lights))
        object.__setattr__(self, "ambient", None if self.ambient is None else check_ambient(self.ambient))
        object.__setattr__(self, "background", check_background(self.background))
        if self.fog is not None:
            if isinstance(self.fog, bool) or not isinstance(self.fog, (int, float)) or not 0 < self.fog < float("inf"):
                raise ParameterError(f"setting 'fog' must be None or a positive distance, got {self.fog!r}")
            object.__setattr__(self, "fog", float(self.fog))
        if self.coarse is True:
            object.__setattr__(self, "coarse", DEFAULT_COARSE_TILE)
        if self.coarse is not False and (not isinstance(self.coarse, int) or isinstance(self.coarse, bool)
                                         or self.coarse not in COARSE_TILES):
            raise ParameterError(f"setting 'coarse' must be True, False or a tile side of "
                                 f"{', '.join(map(str, COARSE_TILES))} pixels, got {self.coarse!r}")

    def resolved(self, exactness: str) -> "Settings":
        """These settings with method "auto" replaced by the method a scene of the given
        exactness class ("exact", "bound" or "implicit") renders with."""
        if self.method != "auto":
            return self
        if exactness == "implicit":
            if self.omega is not None:
                raise ParameterError("setting 'omega' applies to methods 'relaxed' and 'enhanced'; method 'auto' "
                                     "picks 'newton' for this implicit field")
            return replace(self, method="newton")
        return replace(self, method="enhanced")

    @classmethod
    def build(cls, **kwargs: Any) -> "Settings":
        """Settings from keyword arguments, naming any keyword that is not a setting."""
        names = {f.name for f in fields(cls)}
        unknown = sorted(set(kwargs) - names)
        if unknown:
            raise ParameterError(f"unknown setting(s) {', '.join(unknown)}; known: {', '.join(sorted(names))}")
        return cls(**kwargs)

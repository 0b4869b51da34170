"""Render settings: validated once, turned into #defines by the code generator."""
from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any

from .errors import ParameterError

OUTPUTS = ("color", "depth", "normal", "steps")
SHADOWS = (False, "hard", "soft")
METHODS = ("sphere", "relaxed", "enhanced", "newton", "forward_newton", "reference")
# methods that step by the field value and so need a distance bound
DISTANCE_METHODS = ("sphere", "relaxed", "enhanced")
DEFAULT_OMEGA = {"relaxed": 1.6, "enhanced": 0.9}
HIT_MODES = ("cone", "relative", "absolute")
DEBUG_VIEWS = (None, "steps", "normal", "depth", "select")


@dataclass(frozen=True)
class Settings:
    """Everything that changes the generated shader besides the scene itself.

    aa: samples per pixel side (1..4, so 1 to 16 rays a pixel).
    shadows: False, "hard" or "soft" (Inigo Quilez's improved penumbra).
    ao: 5-tap ambient occlusion along the normal.
    ground: an analytic ground plane under the scene (intersected, not marched).
    method: the marching algorithm: "sphere" (Hart), "relaxed" (Keinert et al.),
        "enhanced" (Balint & Valasek), "newton", "forward_newton" (the seed thesis) or
        "reference" (fixed small steps and bisection, for validation).
    omega: relaxation of "relaxed" (in (1, 2), default 1.6) or "enhanced" (in (0, 1],
        default 0.9); None for the default.
    ref_step: the step of "reference" (default: the scene size / 512).
    newton_cap: the Newton methods' step is at most this many times the field value
        (default 2; None for the seed thesis's uncapped Newton step).
    max_steps: map() evaluations a primary ray may spend.
    hit: "cone" (distance below hit_scale pixel footprints), "relative" (below
        hit_scale * t) or "absolute" (below hit_scale).
    hit_scale: the factor of the hit test.
    max_dist: far limit along a ray where the scene is unbounded.
    outputs: which images the draw writes (color always).
    debug: None, or a debug view shown instead of the shaded image: "steps" (heat map of
        map() calls), "normal", "depth" or "select" (grey, tinted where the subtree given to
        generate() as ``highlight`` is the nearest surface; the viewer's scene tree uses it).
    grid: keep big unions of simple primitives as data with a cell grid (False writes
        them out as code, to compare).
    analytic: intersect a lone sphere or plane in closed form instead of marching it.
    """

    aa: int = 1
    shadows: Any = "soft"
    ao: bool = True
    ground: bool = False
    method: str = "enhanced"
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

    def __post_init__(self) -> None:
        if isinstance(self.aa, bool) or not isinstance(self.aa, int) or not 1 <= self.aa <= 4:
            raise ParameterError(f"setting 'aa' must be an integer 1..4, got {self.aa!r}")
        if self.shadows is True:
            object.__setattr__(self, "shadows", "soft")
        if self.shadows is None:
            object.__setattr__(self, "shadows", False)
        if self.shadows not in SHADOWS:
            raise ParameterError(f"setting 'shadows' must be False, 'hard' or 'soft', got {self.shadows!r}")
        for name in ("ao", "ground", "grid", "analytic"):
            if not isinstance(getattr(self, name), bool):
                raise ParameterError(f"setting '{name}' must be True or False, got {getattr(self, name)!r}")
        if self.method not in METHODS:
            raise ParameterError(f"setting 'method' must be one of {', '.join(METHODS)}, got {self.method!r}")
        if self.omega is not None:
            lo_hi = {"relaxed": (1.0, 2.0), "enhanced": (0.0, 1.0)}.get(self.method)
            if lo_hi is None:
                raise ParameterError(f"setting 'omega' applies to methods 'relaxed' and 'enhanced', not {self.method!r}")
            ok = isinstance(self.omega, (int, float)) and not isinstance(self.omega, bool)
            if not ok or not (lo_hi[0] < float(self.omega) <= lo_hi[1]) or (self.method == "relaxed" and self.omega == 2):
                raise ParameterError(f"setting 'omega' for {self.method!r} must lie in ({lo_hi[0]:g}, {lo_hi[1]:g}"
                                     f"{')' if self.method == 'relaxed' else ']'}, got {self.omega!r}")
            object.__setattr__(self, "omega", float(self.omega))
        if self.ref_step is not None:
            if isinstance(self.ref_step, bool) or not isinstance(self.ref_step, (int, float)) or not self.ref_step > 0:
                raise ParameterError(f"setting 'ref_step' must be a positive number, got {self.ref_step!r}")
            object.__setattr__(self, "ref_step", float(self.ref_step))
        if self.newton_cap is not None:
            ok = isinstance(self.newton_cap, (int, float)) and not isinstance(self.newton_cap, bool)
            if not ok or not self.newton_cap >= 1:
                raise ParameterError(f"setting 'newton_cap' must be None or a number >= 1, got {self.newton_cap!r}")
            object.__setattr__(self, "newton_cap", float(self.newton_cap))
        if isinstance(self.max_steps, bool) or not isinstance(self.max_steps, int) or not 1 <= self.max_steps <= 100000:
            raise ParameterError(f"setting 'max_steps' must be an integer 1..100000, got {self.max_steps!r}")
        if self.hit not in HIT_MODES:
            raise ParameterError(f"setting 'hit' must be one of {', '.join(HIT_MODES)}, got {self.hit!r}")
        for name in ("hit_scale", "max_dist"):
            val = getattr(self, name)
            if isinstance(val, bool) or not isinstance(val, (int, float)) or not (0 < float(val) < float("inf")):
                raise ParameterError(f"setting '{name}' must be a positive finite number, got {val!r}")
            object.__setattr__(self, name, float(val))
        if self.debug not in DEBUG_VIEWS:
            raise ParameterError(f"setting 'debug' must be None, 'steps', 'normal', 'depth' or 'select', "
                                 f"got {self.debug!r}")
        outs = (self.outputs,) if isinstance(self.outputs, str) else tuple(self.outputs)
        bad = [o for o in outs if o not in OUTPUTS]
        if bad:
            raise ParameterError(f"setting 'outputs' has unknown entries {bad}; choose from {', '.join(OUTPUTS)}")
        object.__setattr__(self, "outputs", tuple(o for o in OUTPUTS if o in outs or o == "color"))

    @classmethod
    def build(cls, **kwargs: Any) -> "Settings":
        """Settings from keyword arguments, naming any keyword that is not a setting."""
        names = {f.name for f in fields(cls)}
        unknown = sorted(set(kwargs) - names)
        if unknown:
            raise ParameterError(f"unknown setting(s) {', '.join(unknown)}; known: {', '.join(sorted(names))}")
        return cls(**kwargs)

"""The escape hatch: a node whose GLSL the user writes, with an optional numpy twin.

The code is the body of ``float f(vec3 p)`` (or one expression). It is checked when
the node is built for what would break the shader around it (preprocessor lines,
uniforms, unbalanced braces), and compiled with the scene: a driver error names the
node and the line of the user's code. Without a twin the node renders, but the float64
accuracy tools (``distance``, the reference tracer, parity) say they cannot check it.

Named parameters (``params``) are arguments of the node's function, ``float f(vec3 p,
float r, ...)``: a live one is passed its uniform, so moving it needs no recompile.

Without a twin the node is a scene-document kind (``glsl``): the document holds the
code, checked as above when it is loaded; the code runs only in the shader (GLSL, never
Python or JavaScript). A node with a twin (a Python function) cannot be saved.
"""
from __future__ import annotations

import hashlib
import re
from typing import TYPE_CHECKING, Any, Callable, Sequence

import numpy as np

from ..errors import ParameterError, SdfglError
from ..values import validate as v
from .base import BOUND, EXACT, IMPLICIT, INF, Primitive

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter

# "#" anywhere (a comment before a directive would hide it from a line-start check) and "\\"
# (a line continuation can join lines) are refused outright: GLSL has no other use for them
_FORBIDDEN = re.compile(r"#|\\|\b(uniform|layout|main|gl_FragColor|discard)\b")


def _check_code(code: Any) -> str:
    if not isinstance(code, str) or not code.strip():
        raise ParameterError(f"glsl: 'code' must be GLSL text (a function body of p, or one expression), got {code!r}")
    m = _FORBIDDEN.search(code)
    if m:
        line = code[:m.start()].count("\n") + 1
        raise ParameterError(f"glsl: line {line} of the code uses {m.group(0).strip()!r}, which the node's function "
                             f"cannot contain (no '#' or preprocessor lines, no backslashes, uniforms, layouts, main or discard)")
    depth = 0
    for i, line in enumerate(code.split("\n"), start=1):
        for ch in line:
            depth += {"{": 1, "}": -1}.get(ch, 0)
            if depth < 0:
                raise ParameterError(f"glsl: line {i} of the code closes a brace it did not open")
    if depth:
        raise ParameterError(f"glsl: the code leaves {depth} brace(s) open")
    return code


class UserGLSL(Primitive):
    """A field written in GLSL: ``float f(vec3 p) { <code> }`` (named parameters are more arguments).

    A document kind when it has no twin; with one (a Python function) it is not
    serializable and saving a scene with it names it. Pickle works either way (it calls
    the class itself)."""

    kind = "glsl"
    costly = True
    unsaved_reason = ("its float64 twin is a Python function, which a scene document cannot hold; pickle the scene, "
                      "keep it in a Python scene file, or save the node without its twin")

    def __init__(self, code: str, twin: Callable[[np.ndarray], Any] | None = None, lipschitz: float = 1.0,
                 bounds: Sequence[Sequence[float]] | None = None, exact: bool = False, implicit: bool = False,
                 params: Any = None) -> None:
        from .named_params import named_params
        code = _check_code(code)
        if twin is not None and not callable(twin):
            raise ParameterError(f"glsl: 'twin' must be a function of (N, 3) float64 points, got {type(twin).__name__}")
        named = named_params(self.kind, params, glsl=True)
        lip = v.scalar(self.kind, "lipschitz", lipschitz, positive=True)
        v.fixed(self.kind, "it is compiled into the node's step factor", lipschitz=lip)
        if not isinstance(exact, bool) or not isinstance(implicit, bool):
            raise ParameterError("glsl: 'exact' and 'implicit' must be True or False")
        if exact and (implicit or lip > 1):
            raise ParameterError("glsl: an exact field has Lipschitz factor 1 and is not implicit")
        lo_hi = None
        if bounds is not None:
            try:
                lo, hi = bounds
            except (TypeError, ValueError):
                raise ParameterError(f"glsl: 'bounds' must be (lo, hi), two 3-vectors, got {bounds!r}") from None
            lo_hi = (v.vector(self.kind, "bounds[0]", lo), v.vector(self.kind, "bounds[1]", hi))
            if np.any(lo_hi[0] > lo_hi[1]):
                raise ParameterError(f"glsl: 'bounds' lo {tuple(lo_hi[0])} exceeds hi {tuple(lo_hi[1])}")
        fields: dict[str, object] = {"code": code, "lipschitz": float(lip)}
        if lo_hi is not None:
            fields["bounds"] = np.concatenate(lo_hi)
        if exact or implicit:
            fields["class"] = EXACT if exact else IMPLICIT
        fields.update({f"param {n}": val for n, val in named})
        super().__init__(**fields)
        self.code, self.twin, self.declared = code, twin, float(lip)
        self.named = named
        self.serializable = twin is None  # type: ignore[misc]  # a document holds no Python function
        self.box = lo_hi
        self.fclass = EXACT if exact else IMPLICIT if implicit else BOUND
        # divide by the declared factor (only this node's field) to make it a 1-Lipschitz bound
        self.divide = 1.0 if implicit else max(1.0, float(lip))
        # the function depends on the code and the parameters' names, not their values
        signature = "".join(f", float {n}" for n, _ in named)
        digest = hashlib.sha1((code + signature).encode()).hexdigest()[:10]
        self.fn, self.signature = f"userGlsl_{digest}", signature

    def label(self) -> str:
        lines = self.code.strip().split("\n")
        more = len(lines[0]) > 40 or len(lines) > 1
        return f"glsl({lines[0][:40] + ('...' if more else '')!r})"

    @property
    def exactness(self) -> str:
        return self.fclass

    @property
    def lipschitz(self) -> float:
        return INF if self.fclass == IMPLICIT else 1.0

    def _expr(self, em: "Emitter", p: str) -> str:
        body = self.code if re.search(r"\breturn\b", self.code) else f"return ({self.code.strip()});"
        lines = [(f"float {self.fn}(vec3 p{self.signature}) {{  // sg.glsl: {self.label()}", "(codegen)")]
        lines += [(line, f"{self.label()}, line {i} of its code") for i, line in enumerate(body.split("\n"), 1)]
        lines.append(("}", "(codegen)"))
        em.helper(self.fn, lines)
        call = f"{self.fn}({p}{''.join(f', {em.num(val)}' for _, val in self.named)})"
        return call if self.divide == 1.0 else f"({call} * {em.num(1.0 / self.divide)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        if self.twin is None:
            raise SdfglError(f"{self.label()} has no float64 twin, so the accuracy tools (distance, the reference "
                             f"tracer, parity) cannot check it; pass twin=numpy_function to sg.glsl")
        try:
            out = np.asarray(self.twin(p.reshape(-1, 3)), dtype=np.float64)
        except Exception as exc:  # the user's function: name it, whatever it raised
            raise SdfglError(f"{self.label()}: its twin raised {type(exc).__name__}: {exc}") from None
        if out.shape != (p.reshape(-1, 3).shape[0],):
            raise SdfglError(f"{self.label()}: its twin must return one value per point, shape "
                             f"({p.reshape(-1, 3).shape[0]},), got {out.shape}")
        return out.reshape(p.shape[:-1]) / self.divide

    @property
    def _bounds(self) -> tuple[Any, Any]:
        if self.box is None:
            return np.full(3, -INF), np.full(3, INF)
        return self.box


def glsl(code: str, twin: Callable[[np.ndarray], Any] | None = None, lipschitz: float = 1.0,
         bounds: Sequence[Sequence[float]] | None = None, exact: bool = False, implicit: bool = False,
         params: Any = None) -> UserGLSL:
    """A node written in GLSL: ``code`` is the body of ``float f(vec3 p)`` (or one expression).

    Args:
        code: GLSL: the body of ``float f(vec3 p)`` with a ``return``, or one expression of ``p``.
        twin: a numpy function of (N, 3) float64 points giving the same field (without it
            the accuracy tools cannot check the node).
        lipschitz: the field's Lipschitz factor, > 0 (above 1, this node alone is divided by it).
        bounds: (lo, hi), two 3-vectors holding the solid (None: unbounded).
        exact: True if the field is the Euclidean distance.
        implicit: True if the field is no distance bound at all (render with a Newton method).
        params: named parameters, (name, value) pairs or a dict: each is a ``float``
            argument of the function (``float f(vec3 p, float r)``), a number or a live
            scalar (``sg.param``: moving it needs no recompile). Names are GLSL identifiers
            other than p, x, y, z, s, t, u and GLSL's keywords, types and functions.

    Without a twin the node can be saved in a JSON scene document (kind ``glsl``: the
    document holds the code, checked again on load); with one it cannot (pickle or a
    Python scene file keeps it).

    Example:
        >>> import numpy as np
        >>> ball = sg.glsl("length(p) - 1.0", twin=lambda p: np.linalg.norm(p, axis=-1) - 1.0)
        >>> float(ball.distance((2, 0, 0)))
        1.0
        >>> r = sg.param(0.5, "r", range=(0.1, 2.0))
        >>> from sdfgl.scene_io import to_dict
        >>> to_dict(sg.glsl("length(p) - r", params={"r": r}))["scene"]["params"]
        [['r', {'param': 'r'}]]
    """
    kw: dict[str, Any] = {}  # what was given: a document holds no twin, and no defaults it need not
    if twin is not None:
        kw["twin"] = twin
    for name, value, default in (("lipschitz", lipschitz, 1.0), ("bounds", bounds, None), ("exact", exact, False),
                                 ("implicit", implicit, False)):
        if value is not default and not (isinstance(value, float) and value == default):
            kw[name] = value
    if params is not None:
        kw["params"] = [[k, val] for k, val in params.items()] if isinstance(params, dict) else params
    return UserGLSL(code, **kw)

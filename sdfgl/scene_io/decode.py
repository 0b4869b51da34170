"""JSON document -> scene graph, without running code and without recursion.

Every value is checked where it is read, and the first problem raises one
:class:`~sdfgl.errors.SceneDocumentError` naming its JSON path, e.g.
``scene.children[2].radius: sphere: parameter 'radius' must be a number, got str 'x'``.
Nodes are built by calling their registered class with the document's arguments (the
classes validate them as they do for Python callers); expression strings go through the
safe parser (:mod:`sdfgl.expr`).
"""
from __future__ import annotations

import inspect
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import ParameterError, SceneDocumentError, SdfglError
from ..nodes.record import Recorded, registry
from ..params import Live, Param
from ..values.float32 import FLOAT32_MAX
from .encode import signature
from .limits import FORMAT, MAX_ARRAY, MAX_NODES, MAX_PARAMS, VERSION
from .mesh_nodes import KIND as MESH_KIND
from .mesh_nodes import decode_mesh

TOP_KEYS = ("format", "version", "params", "nodes", "scene", "camera", "settings", "metadata")
_TYPE = {bool: "a boolean", int: "a number", float: "a number", str: "a string", list: "an array",
         dict: "an object", type(None): "null"}


def _what(v: Any) -> str:
    if isinstance(v, str):
        return repr(v) if len(v) < 40 else repr(v[:37] + "...")
    return _TYPE.get(type(v), type(v).__name__)


def fail(path: str, msg: str) -> SceneDocumentError:
    return SceneDocumentError(f"{path}: {msg}")


@dataclass
class Document:
    """What a scene document holds."""

    scene: Any
    camera: Any = None
    settings: dict[str, Any] = field(default_factory=dict)
    params: dict[str, Param] = field(default_factory=dict)


class Decoder:
    """Reads one document; relative mesh files are looked for in folder ``base`` (the
    document's; None: the working directory)."""

    def __init__(self, doc: Any, base: Path | None = None) -> None:
        if not isinstance(doc, dict):
            raise fail("(document)", f"expected an object, got {_what(doc)}")
        self.doc, self.base = doc, base
        self.kinds = registry()
        self.params: dict[str, Param] = {}
        self.shared: dict[str, Any] = {}
        self.count = 0

    # -- the document ---------------------------------------------------------------------
    def document(self) -> Document:
        d = self.doc
        unknown = sorted(set(d) - set(TOP_KEYS))
        if unknown:
            raise fail(unknown[0], f"unknown top-level key; known: {', '.join(TOP_KEYS)}")
        if d.get("format") != FORMAT:
            raise fail("format", f"expected {FORMAT!r}, got {_what(d.get('format'))}")
        ver = d.get("version")
        if isinstance(ver, bool) or not isinstance(ver, int) or not 1 <= ver <= VERSION:
            raise fail("version", f"this sdfgl reads versions 1..{VERSION}, got {_what(ver) if not isinstance(ver, int) else ver}")
        self._params(d.get("params", {}))
        self._table(d.get("nodes", {}))
        if "scene" not in d:
            raise fail("scene", "missing: a document must have a scene")
        scene = self.value(d["scene"], "scene")
        if not isinstance(scene, Recorded) or not hasattr(scene, "distance"):
            raise fail("scene", f"expected a node (an object with 'kind'), got {_what(d['scene'])}")
        camera = self._camera(d["camera"]) if d.get("camera") is not None else None
        settings = self._settings(d.get("settings", {}))
        return Document(scene, camera, settings, self.params)

    def _params(self, table: Any) -> None:
        if not isinstance(table, dict):
            raise fail("params", f"expected an object of named parameters, got {_what(table)}")
        if len(table) > MAX_PARAMS:
            raise fail("params", f"{len(table)} parameters (limit {MAX_PARAMS})")
        for name, entry in table.items():
            path = f"params.{name}"
            if not isinstance(entry, dict):
                raise fail(path, f"expected an object with 'value', got {_what(entry)}")
            extra = sorted(set(entry) - {"value", "min", "max"})
            if extra:
                raise fail(f"{path}.{extra[0]}", "unknown key; known: value, min, max")
            if "value" not in entry:
                raise fail(f"{path}.value", "missing")
            value = self._number_or_vector(entry["value"], f"{path}.value")
            rng = None
            if "min" in entry or "max" in entry:
                rng = (self._number(entry["min"], f"{path}.min") if "min" in entry else -math.inf,
                       self._number(entry["max"], f"{path}.max") if "max" in entry else math.inf)
            try:
                p = Param(value, name, rng)
            except SdfglError as exc:
                raise fail(path, str(exc)) from None
            self.params[name] = p

    def _table(self, table: Any) -> None:
        """Build the shared-node table in dependency order (refs may point at each other)."""
        if not isinstance(table, dict):
            raise fail("nodes", f"expected an object of named nodes, got {_what(table)}")
        if len(table) > MAX_NODES:
            raise fail("nodes", f"{len(table)} entries (limit {MAX_NODES})")
        for name in table_order(table):
            self.shared[name] = self.value(table[name], f"nodes.{name}")
            if not isinstance(self.shared[name], Recorded):
                raise fail(f"nodes.{name}", f"expected a node (an object with 'kind'), got {_what(table[name])}")

    # -- values (iterative) ---------------------------------------------------------------
    def value(self, root: Any, path: str) -> Any:
        """Decode ``root`` (found at ``path``): scalars, arrays, nodes, refs, params, live values."""
        out: list[Any] = [None]
        stack: list[tuple] = [("visit", root, path, out, 0)]
        while stack:
            op, v, p, target, idx = stack.pop()
            if op == "build":
                target[idx] = v(p)
                continue
            if isinstance(v, list):
                if len(v) > MAX_ARRAY:
                    raise fail(p, f"array of {len(v)} items (limit {MAX_ARRAY})")
                res: list[Any] = [None] * len(v)
                target[idx] = res
                stack.extend(("visit", x, f"{p}[{i}]", res, i) for i, x in reversed(list(enumerate(v))))
            elif isinstance(v, dict):
                self._object(v, p, target, idx, stack)
            elif v is None or isinstance(v, (bool, str, int)):
                target[idx] = v
            elif isinstance(v, float):
                if not math.isfinite(v):
                    raise fail(p, "expected a finite number; write infinity as {\"float\": \"inf\"}")
                target[idx] = v
            else:
                raise fail(p, f"{type(v).__name__} is not a JSON value")
        return out[0]

    def _object(self, v: dict, p: str, target: list, idx: int, stack: list) -> None:
        if "kind" in v:
            self._node(v, p, target, idx, stack)
        elif set(v) == {"ref"}:
            name = v["ref"]
            if not isinstance(name, str) or name not in self.shared:
                raise fail(f"{p}.ref", f"no node named {name!r} in 'nodes'")
            target[idx] = self.shared[name]
        elif set(v) == {"param"}:
            name = v["param"]
            if not isinstance(name, str) or name not in self.params:
                raise fail(f"{p}.param", f"no parameter named {_what(name)} in 'params'")
            target[idx] = self.params[name]
        elif set(v) == {"expr"}:
            from ..expr import parse_live
            if not isinstance(v["expr"], str):
                raise fail(f"{p}.expr", f"expected a string, got {_what(v['expr'])}")
            try:
                target[idx] = parse_live(v["expr"], self.params, "live expression")
            except SdfglError as exc:
                raise fail(f"{p}.expr", str(exc)) from None
        elif set(v) == {"live", "args"}:
            self._live(v, p, target, idx, stack)
        elif set(v) == {"float"}:
            if v["float"] not in ("inf", "-inf"):
                raise fail(f"{p}.float", f"expected \"inf\" or \"-inf\", got {_what(v['float'])}")
            target[idx] = math.inf if v["float"] == "inf" else -math.inf
        else:
            raise fail(p, "expected a node ('kind'), {\"ref\"}, {\"param\"}, {\"expr\"}, {\"live\", \"args\"} or "
                          f"{{\"float\"}}, got an object with keys {', '.join(sorted(v)) or '(none)'}")

    def _node(self, v: dict, p: str, target: list, idx: int, stack: list) -> None:
        kind = v["kind"]
        cls = self.kinds.get(kind) if isinstance(kind, str) else None
        if cls is None:
            known = ", ".join(sorted(self.kinds))
            raise fail(f"{p}.kind", f"unknown node kind {_what(kind)}; known: {known}")
        self.count += 1
        if self.count > MAX_NODES:
            raise fail(p, f"more than {MAX_NODES} nodes in the document")
        if kind == MESH_KIND:  # a file reference or inline triangles, not constructor arguments
            target[idx] = decode_mesh(v, p, self.base, fail)
            return
        sig = signature(cls)
        names = [k for k in v if k != "kind"]
        for k in names:
            par = sig.parameters.get(k)
            if par is None or par.kind == inspect.Parameter.VAR_KEYWORD:
                known = ", ".join(n for n in sig.parameters) or "none"
                raise fail(f"{p}.{k}", f"unknown parameter of {kind}; known: {known}")
        args: dict[str, Any] = {}

        def build(path: str) -> Any:
            return self._construct(cls, sig, args, path)
        stack.append(("build", build, p, target, idx))
        for k in reversed(names):
            holder = [None]
            args[k] = holder
            stack.append(("visit", v[k], f"{p}.{k}", holder, 0))

    def _construct(self, cls: type, sig: inspect.Signature, holders: dict[str, list], p: str) -> Any:
        values = {k: h[0] for k, h in holders.items()}
        pos: list[Any] = []
        kw: dict[str, Any] = {}
        for name, par in sig.parameters.items():
            if par.kind == inspect.Parameter.VAR_POSITIONAL:
                extra = values.get(name, [])
                if not isinstance(extra, list):
                    raise fail(f"{p}.{name}", f"expected an array, got {_what(extra)}")
                pos += extra
            elif name in values:
                if par.kind == inspect.Parameter.POSITIONAL_ONLY or (
                        par.kind == inspect.Parameter.POSITIONAL_OR_KEYWORD and any(
                            q.kind == inspect.Parameter.VAR_POSITIONAL for q in sig.parameters.values())):
                    pos.append(values[name])
                else:
                    kw[name] = values[name]
            elif par.default is inspect.Parameter.empty and par.kind not in (inspect.Parameter.VAR_KEYWORD,):
                raise fail(f"{p}.{name}", f"missing: {cls.kind} needs '{name}'")
        try:
            return cls(*pos, **kw)
        except SdfglError as exc:
            raise fail(p, str(exc)) from None
        except (TypeError, ValueError, ArithmeticError, IndexError, KeyError) as exc:
            raise fail(p, f"{cls.kind}: {exc}") from None

    def _live(self, v: dict, p: str, target: list, idx: int, stack: list) -> None:
        op, args = v["live"], v["args"]
        if not isinstance(op, str) or not isinstance(args, list) or not args:
            raise fail(p, "a live expression is {\"live\": \"add\" | \"sub\" | \"mul\" | \"div\" | \"neg\", "
                          "\"args\": [...]}")
        holder: list[Any] = [None] * len(args)

        def build(path: str) -> Any:
            if not all(isinstance(a, (Live, int, float)) and not isinstance(a, bool) for a in holder):
                raise fail(f"{path}.args", "expected live values and numbers")
            live = Live(op, *holder)
            try:
                live.value  # an unknown op or a wrong count of arguments fails here, not at render
            except SdfglError as exc:
                raise fail(path, str(exc)) from None
            except Exception:  # noqa: BLE001 - whatever Live raises, the message says what is wrong
                raise fail(f"{path}.live", f"unknown live operation {op!r} with {len(args)} argument(s)") from None
            return live
        stack.append(("build", build, p, target, idx))
        stack.extend(("visit", a, f"{p}.args[{i}]", holder, i) for i, a in reversed(list(enumerate(args))))

    # -- camera and settings ------------------------------------------------------------------
    def _camera(self, c: Any) -> Any:
        from ..camera import Camera, OrbitCamera
        if not isinstance(c, dict):
            raise fail("camera", f"expected an object, got {_what(c)}")
        kinds = {"orbit": (OrbitCamera, ("target", "distance", "yaw", "pitch", "fov", "projection", "ortho_height")),
                 "look_at": (Camera, ("eye", "target", "up", "fov", "projection", "ortho_height"))}
        t = c.get("type")
        if not isinstance(t, str) or t not in kinds:
            raise fail("camera.type", f"expected \"orbit\" or \"look_at\", got {_what(t)}")
        cls, keys = kinds[t]
        extra = sorted(set(c) - set(keys) - {"type"})
        if extra:
            raise fail(f"camera.{extra[0]}", f"unknown key for a {t} camera; known: {', '.join(keys)}")
        kw = {}
        for k in keys:
            if k in c:
                val = c[k]
                if k == "projection":
                    if val not in ("perspective", "orthographic"):
                        raise fail("camera.projection", f"expected \"perspective\" or \"orthographic\", got {_what(val)}")
                    kw[k] = val
                else:
                    kw[k] = self._vector(val, f"camera.{k}") if k in ("eye", "target", "up") else \
                        self._number(val, f"camera.{k}")
        if t == "look_at" and "eye" not in kw:
            raise fail("camera.eye", "missing")
        try:
            return cls(**kw)
        except SdfglError as exc:
            raise fail("camera", str(exc)) from None

    @staticmethod
    def _settings(s: Any) -> dict[str, Any]:
        from ..settings import Settings
        if not isinstance(s, dict):
            raise fail("settings", f"expected an object, got {_what(s)}")
        out = {k: (tuple(v) if isinstance(v, list) else v) for k, v in s.items()}
        if isinstance(out.get("lights"), tuple):
            out["lights"] = tuple(_light(x, f"settings.lights[{i}]") for i, x in enumerate(out["lights"]))
        try:
            Settings.build(**out)
        except SdfglError as exc:
            raise fail("settings", str(exc)) from None
        return out

    # -- small typed readers -------------------------------------------------------------------
    @staticmethod
    def _number(v: Any, path: str) -> float:
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise fail(path, f"expected a number, got {_what(v)}")
        if not abs(v) <= FLOAT32_MAX:  # NaN, infinity and an integer too big for a float too
            raise fail(path, f"expected a finite number of at most {FLOAT32_MAX:.3g} in magnitude (the shader "
                             f"computes in float32), got {_number_text(v)}")
        return float(v)

    def _vector(self, v: Any, path: str) -> list[float]:
        if not isinstance(v, list) or len(v) != 3:
            raise fail(path, f"expected 3 numbers, got {_what(v) if not isinstance(v, list) else f'{len(v)} items'}")
        return [self._number(x, f"{path}[{i}]") for i, x in enumerate(v)]

    def _number_or_vector(self, v: Any, path: str) -> Any:
        return self._vector(v, path) if isinstance(v, list) else self._number(v, path)


def _number_text(v: float) -> str:
    """A number for a message (an integer of hundreds of digits is shown by its length)."""
    text = repr(v)
    return text if len(text) <= 24 else f"an integer of {len(text.lstrip('-'))} digits"


def table_order(table: dict[str, Any]) -> list[str]:
    """The names of a document's shared-node table (``nodes``), each after the names its entry
    refers to; a reference to a missing name or a cycle of references is an error naming the
    entry's JSON path."""
    order: list[str] = []
    state: dict[str, int] = {}  # 1: in progress, 2: placed
    for start in table:
        stack = [start]
        while stack:
            name = stack[-1]
            if state.get(name) == 2:
                stack.pop()
                continue
            pending = [r for r in _refs(table[name]) if state.get(r) != 2]
            for r in pending:
                if r not in table:
                    raise fail(f"nodes.{name}", f"refers to {r!r}, which is not in 'nodes'")
                if state.get(r) == 1:
                    raise fail(f"nodes.{name}", f"the references through {r!r} form a cycle")
            if pending:
                state[name] = 1
                stack.extend(pending)
                continue
            order.append(name)
            state[name] = 2
            stack.pop()
    return order


def _refs(value: Any) -> list[str]:
    """Names referenced by {"ref": name} anywhere inside ``value`` (iteratively)."""
    out, stack = [], [value]
    while stack:
        v = stack.pop()
        if isinstance(v, dict):
            if set(v) == {"ref"} and isinstance(v["ref"], str):
                out.append(v["ref"])
            else:
                stack.extend(v.values())
        elif isinstance(v, list):
            stack.extend(v)
    return out


LIGHT_KEYS = {"directional": ("direction", "color", "intensity", "shadow", "fill"),
              "point": ("position", "color", "intensity", "shadow", "range", "fill")}


def _light(d: Any, path: str) -> Any:
    """A light from its document object, validated by its factory (a saved unit direction is kept
    as written, so the generated GLSL is the same)."""
    import dataclasses

    from ..look.lights import directional_light, point_light
    if not isinstance(d, dict):
        raise fail(path, f"expected a light object, got {_what(d)}")
    t = d.get("type")
    if not isinstance(t, str) or t not in LIGHT_KEYS:
        raise fail(f"{path}.type", f"expected \"directional\" or \"point\", got {_what(t)}")
    keys = LIGHT_KEYS[t]
    extra = sorted(set(d) - set(keys) - {"type"})
    if extra:
        raise fail(f"{path}.{extra[0]}", f"unknown key for a {t} light; known: {', '.join(keys)}")
    if keys[0] not in d:
        raise fail(f"{path}.{keys[0]}", "missing")
    if not isinstance(d[keys[0]], list) or len(d[keys[0]]) != 3:
        raise fail(f"{path}.{keys[0]}", f"expected 3 numbers, got {_what(d[keys[0]])}")
    kw = {k: (tuple(d[k]) if isinstance(d[k], list) else d[k]) for k in keys if k in d}
    try:
        light = (directional_light if t == "directional" else point_light)(**kw)
    except (SdfglError, TypeError, ValueError) as exc:
        raise fail(path, str(exc)) from None
    saved = tuple(float(x) for x in kw[keys[0]])
    if t == "directional" and abs(math.hypot(*saved) - 1.0) < 1e-12:
        light = dataclasses.replace(light, vector=saved)  # a saved unit vector, kept to the bit
    return light


def from_document(doc: Any, base: Path | None = None) -> Document:
    """Decode a document dict (as json.load returns it) into scene, camera, settings and params;
    relative mesh files are looked for in folder ``base`` (None: the working directory)."""
    return Decoder(doc, base).document()

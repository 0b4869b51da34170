"""A scene document as Python code that rebuilds the same graph ("copy as Python").

Each node becomes one line that calls its registered class with the document's arguments,
in the order the document decoder passes them, so the code builds the same nodes and the
same generated GLSL. The document is decoded first: a document the decoder refuses gets no
code.
"""
from __future__ import annotations

import keyword
import math
import re
from typing import Any

from ..errors import ParameterError
from ..nodes.record import registry
from ..scene_io.decode import from_document, table_order
from ..scene_io.encode import signature

_WORD = re.compile(r"[^0-9a-zA-Z_]")


def _name(prefix: str, text: str, taken: set[str]) -> str:
    base = _WORD.sub("_", f"{prefix}{text}")
    name, i = base, 1
    while name in taken or keyword.iskeyword(name):
        i += 1
        name = f"{base}_{i}"
    taken.add(name)
    return name


class _Writer:
    def __init__(self, doc: dict[str, Any]) -> None:
        self.doc = doc
        self.kinds = registry()
        self.lines: list[str] = []
        self.imports: dict[str, set[str]] = {}
        self.taken: set[str] = {"sg", "math", "scene", "camera", "settings", "params"}
        self.params: dict[str, str] = {}
        self.refs: dict[str, str] = {}
        self.count = 0

    def need(self, module: str, name: str) -> str:
        self.imports.setdefault(module, set()).add(name)
        return name

    def write(self) -> str:
        d = self.doc
        if d.get("params"):
            self.need("sdfgl.params", "Param")
            for name, entry in d["params"].items():
                var = _name("p_", name, self.taken)
                self.params[name] = var
                rng = ""
                if "min" in entry or "max" in entry:
                    lo = self.value(entry["min"]) if "min" in entry else "-math.inf"
                    hi = self.value(entry["max"]) if "max" in entry else "math.inf"
                    rng = f", ({lo}, {hi})"
                self.lines.append(f"{var} = Param({self.value(entry['value'])}, {name!r}{rng})")
            self.lines.append("params = {" + ", ".join(f"{k!r}: {v}" for k, v in self.params.items()) + "}")
        for name in table_order(d.get("nodes", {})):
            self.refs[name] = self.node(d["nodes"][name])
        root = self.value(d["scene"])
        self.lines.append(f"scene = {root}")
        if d.get("camera") is not None:
            cam = dict(d["camera"])
            cls = {"orbit": "OrbitCamera", "look_at": "Camera"}[cam.pop("type")]
            self.need("sdfgl.camera", cls)
            args = ", ".join(f"{k}={self.value(v)}" for k, v in cam.items())
            self.lines.append(f"camera = {cls}({args})")
        else:
            self.lines.append("camera = None")
        settings = dict(d.get("settings", {}))
        lights = settings.pop("lights", None)
        text = repr(settings)
        if lights:
            text = text[:-1] + (", " if settings else "") + f"'lights': [{', '.join(map(light_call, lights))}]}}"
        self.lines.append(f"settings = {text}")
        self.lines.append("# sg.render(scene, camera, **settings)")
        head = ["import math", "", "import sdfgl as sg"]
        for module in sorted(self.imports):
            head.append(f"from {module} import {', '.join(sorted(self.imports[module]))}")
        return "\n".join([*head, "", *self.lines]) + "\n"

    def node(self, v: dict[str, Any]) -> str:
        cls = self.kinds[v["kind"]]
        self.need(cls.__module__, cls.__name__)
        sig = signature(cls)
        var_names = {n for n, q in sig.parameters.items() if q.kind == q.VAR_POSITIONAL}
        values = {k: self.value(x) for k, x in v.items() if k != "kind" and not (k in var_names and isinstance(x, list))}
        has_var = bool(var_names)
        pos: list[str] = []
        kw: list[str] = []
        for name, par in sig.parameters.items():  # the argument order of the document decoder
            if par.kind == par.VAR_POSITIONAL:
                if isinstance(v.get(name), list):
                    pos += [self.value(x) for x in v[name]]
                elif name in values:
                    pos.append(f"*{values[name]}")
            elif name in values:
                if par.kind == par.POSITIONAL_ONLY or (par.kind == par.POSITIONAL_OR_KEYWORD and has_var):
                    pos.append(values[name])
                else:
                    kw.append(f"{name}={values[name]}")
        var = _name("n", str(self.count), self.taken)
        self.count += 1
        self.lines.append(f"{var} = {cls.__name__}({', '.join(pos + kw)})")
        return var

    def value(self, v: Any) -> str:
        if isinstance(v, list):
            return "[" + ", ".join(self.value(x) for x in v) + "]"
        if isinstance(v, dict):
            if "kind" in v:
                return self.node(v)
            if set(v) == {"ref"}:
                return self.refs[v["ref"]]
            if set(v) == {"param"}:
                return self.params[v["param"]]
            if set(v) == {"expr"}:
                self.need("sdfgl.expr", "parse_live")
                return f"parse_live({v['expr']!r}, params, 'live expression')"
            if set(v) == {"live", "args"}:
                self.need("sdfgl.params", "Live")
                return f"Live({v['live']!r}, {', '.join(self.value(a) for a in v['args'])})"
            if set(v) == {"float"}:
                return "math.inf" if v["float"] == "inf" else "-math.inf"
        if isinstance(v, float) and not math.isfinite(v):  # pragma: no cover - the decoder refuses these
            raise ParameterError(f"copy as Python: {v!r} is not a document value")
        return repr(v)


def to_python(doc: dict[str, Any]) -> str:
    """Python source that rebuilds the scene of the document dict ``doc`` as ``scene`` (and
    ``camera``, ``settings``); the document is decoded first, so a bad one raises
    :class:`~sdfgl.errors.SceneDocumentError` naming its JSON path."""
    from_document(doc)
    return _Writer(doc).write()


def light_call(light: dict[str, Any]) -> str:
    """The ``sg.directional_light(...)`` / ``sg.point_light(...)`` call of a (decoded, so
    checked) document light object: numbers, 3-vectors, strings and flags only."""
    kw = {k: (tuple(v) if isinstance(v, list) else v) for k, v in light.items() if k != "type"}
    return f"sg.{light['type']}_light(" + ", ".join(f"{k}={v!r}" for k, v in kw.items()) + ")"

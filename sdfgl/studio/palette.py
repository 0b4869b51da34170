"""The studio's node palette, generated from the node registry (no second list of nodes in JS).

Each registered kind becomes one palette entry: its input slots (parameters that take a
node or a 2D shape; a ``*children`` parameter takes any number of inputs) and its fields
(every other constructor parameter, with its default and a slider range for numbers).
"""
from __future__ import annotations

import inspect
import math
from typing import Any

from ..nodes.record import registry
from ..scene_io.encode import signature

NODE_TYPES = ("Node", "Shape2D")
NUMBER_TYPES = ("float", "int")
COLOUR_FIELDS = ("rgb", "color", "emission")  # fields of colour nodes and materials: the page adds a colour picker
NAMED_FIELD, NAMED_KINDS = "params", ("implicit", "glsl")  # named parameters: the page shows a slider for each
MAX_LIGHTS = 4  # the lights the output node's controls offer (the renderer takes more)


def slider_range(default: Any) -> tuple[float, float]:
    """The slider range the studio offers for a number field whose default is ``default``:
    1/8 .. 4 x a positive default (sizes stay positive), symmetric about 0 for a negative or
    zero one."""
    if isinstance(default, (int, float)) and not isinstance(default, bool) and math.isfinite(default) and default:
        mag = 4.0 * abs(float(default))
        return (abs(float(default)) / 8.0, mag) if default > 0 else (-mag, mag)
    return (-2.0, 2.0)


def _json_default(value: Any) -> Any:
    if isinstance(value, tuple):
        return [_json_default(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return {"float": "inf" if value > 0 else "-inf"}
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    return None


def entry(kind: str, cls: type) -> dict[str, Any]:
    """The palette entry of one node kind."""
    inputs: list[dict[str, Any]] = []
    fields: list[dict[str, Any]] = []
    for p in signature(cls).parameters.values():
        annotation = str(p.annotation)
        if p.kind == p.VAR_KEYWORD or "Callable" in annotation:  # a Python function: no document value
            continue
        required = p.default is inspect.Parameter.empty
        if any(t in annotation for t in NODE_TYPES) and "|" not in annotation.replace("| None", ""):
            inputs.append({"name": p.name, "many": p.kind == p.VAR_POSITIONAL, "shape2d": "Shape2D" in annotation})
            continue
        default = None if required else _json_default(p.default)
        number = (isinstance(default, (int, float)) and not isinstance(default, bool)) or \
            annotation.replace(" | None", "") in NUMBER_TYPES
        field: dict[str, Any] = {"name": p.name, "required": required, "default": default, "number": number}
        if number:
            field["min"], field["max"] = slider_range(default)
        if p.name in COLOUR_FIELDS:
            field["colour"] = True
        if p.name == NAMED_FIELD and kind in NAMED_KINDS:
            field["named"] = True
        fields.append(field)
    doc = inspect.cleandoc(cls.__doc__ or "").split("\n\n")[0]
    return {"kind": kind, "group": cls.__module__.rsplit(".", 1)[-1], "inputs": inputs, "fields": fields,
            "doc": " ".join(doc.split())}


OUTPUT = "output"
"""The studio's scene-output node: its input is the document's ``scene``, its fields the
document's ``camera`` and ``settings`` (not a node kind: no document names it)."""


def output_entry() -> dict[str, Any]:
    """The palette entry of the scene-output node; ``controls`` lists what its settings
    controls offer (render methods, AA levels, how many lights), from :mod:`sdfgl.settings`."""
    from ..settings import METHODS, Settings
    fields = [{"name": key, "required": False, "default": None, "number": False} for key in ("camera", "settings")]
    start = Settings()
    controls = {"methods": list(METHODS), "aa": [1, 2, 3, 4], "max_lights": MAX_LIGHTS,
                "defaults": {"method": start.method, "aa": start.aa, "shadows": start.shadows, "ao": start.ao}}
    return {"kind": OUTPUT, "group": "scene", "inputs": [{"name": "scene", "many": False, "shape2d": False}],
            "fields": fields, "controls": controls,
            "doc": "The scene: the document's root, camera (an object) and render settings "
                   "(an object, e.g. {\"background\": \"#223\", \"method\": \"enhanced\"})."}


def palette() -> list[dict[str, Any]]:
    """The scene-output node, then every node kind of the registry sorted by group and kind."""
    items = sorted((entry(kind, cls) for kind, cls in registry().items()), key=lambda e: (e["group"], e["kind"]))
    return [output_entry(), *items]

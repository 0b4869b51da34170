"""Scene graph -> JSON-ready dict (the format is described in docs/scene-format.md).

Generic over node classes: a node is written as its kind plus the arguments of the call
that built it (see :mod:`sdfgl.nodes.record`), bound to the constructor's parameter
names. Shared subtrees and subtrees deeper than ``INLINE_HEIGHT`` go to the document's
``nodes`` table and are referenced, so the JSON nesting stays bounded however deep the
scene is. No recursion over the scene graph.
"""
from __future__ import annotations

import inspect
import json
import math
from functools import lru_cache
from typing import Any

from pathlib import Path

import numpy as np

from ..errors import ParameterError
from ..nodes.mesh_field import MeshField
from ..nodes.record import Recorded, recorded_in
from ..nodes.traverse import walk
from ..params import Live, Param
from .limits import FORMAT, INLINE_HEIGHT, VERSION
from .mesh_nodes import encode_mesh

_MAX_VALUE_DEPTH = 16


@lru_cache(maxsize=None)
def signature(cls: type) -> inspect.Signature:
    """The constructor's signature without ``self``."""
    sig = inspect.signature(cls.__init__)
    return sig.replace(parameters=list(sig.parameters.values())[1:])


def bound_arguments(obj: Recorded) -> dict[str, Any]:
    """The constructor arguments of ``obj`` by parameter name (defaults not included)."""
    cls, args, kwargs = obj.constructor
    try:
        return dict(signature(cls).bind(*args, **kwargs).arguments)
    except TypeError as exc:  # pragma: no cover - the call succeeded, so it binds
        raise ParameterError(f"{obj.kind}: cannot name the constructor arguments: {exc}") from None


class Encoder:
    """Writes one document: nodes, the parameter table and the shared-node table; mesh files
    inside folder ``base`` (the document's) are referenced relative to it."""

    def __init__(self, base: Path | None = None) -> None:
        self.base = base
        self.params: dict[str, dict[str, Any]] = {}
        self._param_keys: dict[int, str] = {}
        self.table: dict[str, dict[str, Any]] = {}
        self._done: dict[int, Any] = {}  # id(node) -> its inline dict or {"ref": name}
        self._height: dict[int, int] = {}

    # -- nodes --------------------------------------------------------------------------
    def scene(self, root: Recorded) -> Any:
        if not isinstance(root, Recorded):
            raise ParameterError(f"to_dict: expected an sdfgl node, got {type(root).__name__}")
        order, uses = self._postorder(root)
        for node in order:
            self._encode_node(node, shared=uses[id(node)] > 1)
        return self._done[id(root)]

    @staticmethod
    def _postorder(root: Recorded) -> tuple[list[Recorded], dict[int, int]]:
        """Nodes children first (in argument order) and how often each is referenced."""
        return walk(root, lambda n: [c for v in bound_arguments(n).values() for c in recorded_in(v)])

    def _encode_node(self, node: Recorded, shared: bool) -> None:
        if isinstance(node, MeshField):
            self._place(node, encode_mesh(node, self.base), 1, shared)
            return
        if not node.serializable:
            why = f": {node.unsaved_reason}" if node.unsaved_reason else ""
            raise ParameterError(f"{node.label()}: a {node.kind!r} node cannot be saved in a scene document{why}")
        if not node.made_by_call:
            raise ParameterError(f"{node.kind}: this node was not made by calling its class, so its arguments are "
                                 f"unknown and it cannot be saved")
        out: dict[str, Any] = {"kind": node.kind}
        height = [0]
        for name, value in bound_arguments(node).items():
            out[name] = self._value(value, f"{node.kind}.{name}", height, 0)
        self._place(node, out, height[0] + 1, shared)

    def _place(self, node: Recorded, out: dict[str, Any], h: int, shared: bool) -> None:
        """Keep ``out`` (of height ``h``) inline, or in the shared-node table if it is shared or deep."""
        if shared or h > INLINE_HEIGHT:
            ref = f"n{len(self.table) + 1}"
            self.table[ref] = out
            self._done[id(node)], self._height[id(node)] = {"ref": ref}, 0
        else:
            self._done[id(node)], self._height[id(node)] = out, h

    # -- values -------------------------------------------------------------------------
    def _value(self, v: Any, where: str, height: list[int], depth: int) -> Any:
        if depth > _MAX_VALUE_DEPTH:
            raise ParameterError(f"{where}: value nested more than {_MAX_VALUE_DEPTH} deep")
        if isinstance(v, Recorded):
            height[0] = max(height[0], self._height[id(v)])
            return self._done[id(v)]
        if v is None or isinstance(v, (bool, str, int)) and not isinstance(v, np.bool_):
            return v
        if isinstance(v, np.bool_):
            return bool(v)
        if isinstance(v, np.integer):
            return int(v)
        if isinstance(v, (float, np.floating)):
            return _float(float(v), where)
        if isinstance(v, np.ndarray):
            return self._value(v.tolist(), where, height, depth)
        if isinstance(v, (list, tuple)):
            return [self._value(x, where, height, depth + 1) for x in v]
        if isinstance(v, Live):
            return self._live(v, where, height, depth)
        if type(v).__module__.split(".")[0] == "sympy":
            return str(v)  # sympy expressions are kept as text and read back by the safe parser
        raise ParameterError(f"{where}: a {type(v).__name__} cannot be saved in a scene document")

    def _live(self, v: Live, where: str, height: list[int], depth: int) -> Any:
        if isinstance(v, Param):
            return {"param": self._param(v)}
        if type(v) is not Live:
            raise ParameterError(f"{where}: a live {type(v).__name__} cannot be saved in a scene document")
        return {"live": v.op, "args": [self._value(a, where, height, depth + 1) for a in v.args]}

    def _param(self, p: Param) -> str:
        key = self._param_keys.get(id(p))
        if key is not None:
            return key
        key = p.name or p.label
        if key in self.params:
            raise ParameterError(f"two different live parameters are both named {key!r}; give them distinct names "
                                 f"to save the scene")
        entry: dict[str, Any] = {"value": self._value(p.value, f"param {key}", [0], 0)}
        if p.range is not None:  # an open (infinite) end is left out
            lo, hi = p.range
            entry.update({k: x for k, x in (("min", lo), ("max", hi)) if math.isfinite(x)})
        self.params[key] = entry
        self._param_keys[id(p)] = key
        return key


def _float(x: float, where: str) -> Any:
    if math.isnan(x):
        raise ParameterError(f"{where}: NaN cannot be saved")
    if math.isinf(x):
        return {"float": "inf" if x > 0 else "-inf"}
    return x


def camera_to_dict(camera: Any) -> dict[str, Any]:
    """An OrbitCamera or a look-at Camera as a document's ``camera`` object."""
    from ..camera import Camera, OrbitCamera
    if type(camera) is OrbitCamera:
        out = {"type": "orbit", "target": [float(x) for x in camera.target], "distance": float(camera.distance),
               "yaw": float(camera.yaw), "pitch": float(camera.pitch), "fov": float(camera.fov)}
    elif type(camera) is Camera:
        out = {"type": "look_at", "eye": [float(x) for x in camera.eye], "target": [float(x) for x in camera.target],
               "up": [float(x) for x in camera.up_hint], "fov": float(camera.fov)}
    else:
        raise ParameterError(f"save_scene: a camera of type {type(camera).__name__} cannot be saved "
                         f"(OrbitCamera and Camera can)")
    if camera.orthographic:  # perspective is the default and is left out
        out["projection"] = "orthographic"
        if camera._ortho_height is not None:
            out["ortho_height"] = float(camera._ortho_height)
    return out


def light_to_dict(light: Any) -> dict[str, Any]:
    """A light (``sg.directional_light`` / ``sg.point_light``) as a document's object."""
    out: dict[str, Any] = {"type": light.kind, "direction" if light.kind == "directional" else "position":
                           list(light.vector), "color": list(light.color), "intensity": light.intensity}
    if light.shadow is not None:
        out["shadow"] = light.shadow
    if light.fill:
        out["fill"] = True
    if light.range is not None:
        out["range"] = light.range
    return out


def settings_to_dict(settings: dict[str, Any]) -> dict[str, Any]:
    """Render settings, validated, as JSON values (only those given)."""
    from ..settings import Settings
    if not isinstance(settings, dict):
        raise ParameterError(f"save_scene: 'settings' must be a dict, got {type(settings).__name__}")
    Settings.build(**settings)
    out = {k: (list(v) if isinstance(v, tuple) else v) for k, v in settings.items()}
    if out.get("lights") is not None:
        from ..look.lights import check_lights
        out["lights"] = [light_to_dict(lt) for lt in check_lights(out["lights"])]
    for k, v in out.items():
        try:
            json.dumps(v, allow_nan=False)
        except (TypeError, ValueError):
            raise ParameterError(f"save_scene: setting {k!r} ({type(v).__name__}) cannot be saved in a scene document; "
                                 f"pass it to render() instead") from None
    return out


def to_document(scene: Recorded, camera: Any = None, settings: dict[str, Any] | None = None,
                base: Path | None = None) -> dict[str, Any]:
    """The whole document: format, version, params, shared nodes, scene, camera, settings;
    mesh files inside folder ``base`` (the document's) are referenced relative to it."""
    enc = Encoder(base)
    root = enc.scene(scene)
    doc: dict[str, Any] = {"format": FORMAT, "version": VERSION}
    if enc.params:
        doc["params"] = enc.params
    if enc.table:
        doc["nodes"] = enc.table
    doc["scene"] = root
    if camera is not None:
        doc["camera"] = camera_to_dict(camera)
    if settings:
        doc["settings"] = settings_to_dict(settings)
    return doc

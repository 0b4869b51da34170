"""Bindings: which controller message drives which live parameter, and how a message becomes a value.

A binding names a parameter (``sg.param(..., name=...)``) and one source: a MIDI control
change (``cc`` 0..127 on ``channel`` 0..15, as mido counts them, or any channel) or an OSC
address. A CC's 0..127 spans the binding's range (default: the parameter's own); an OSC
float is taken as it is (``normalized``: 0..1 spans the range instead). Every value is
clamped to the range. ``smooth`` (seconds) eases the parameter towards each new value.

A set of bindings is saved as a small JSON document, checked on load with the JSON path
of anything wrong::

    {"version": 1, "bindings": [
        {"param": "radius", "cc": 21, "channel": null, "smooth": 0.05},
        {"param": "radius", "osc": "/radius"},
        {"param": "offset", "osc": "/offset/y", "component": 1, "normalized": true, "range": [-1, 1]}]}
"""
from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from ..params import Param
from .errors import LiveBindingError

VERSION = 1
KEYS = ("param", "cc", "channel", "osc", "component", "range", "normalized", "smooth")


@dataclass(frozen=True)
class Binding:
    """One controller source bound to one live parameter (by its name).

    Exactly one of ``cc`` (a MIDI control number 0..127) and ``osc`` (an address starting
    with "/") is set. ``channel`` (0..15) limits a CC to one MIDI channel (None: any).
    ``component`` (0..2) drives one component of a 3-vector parameter. ``range`` overrides
    the parameter's range for mapping and clamping. ``smooth`` is a time constant in seconds
    (0: each value is set at once)."""

    param: str
    cc: int | None = None
    channel: int | None = None
    osc: str | None = None
    component: int | None = None
    range: tuple[float, float] | None = None
    normalized: bool = False
    smooth: float = 0.0

    def __post_init__(self) -> None:
        check_fields(asdict(self), "binding")
        if self.range is not None:  # a list (from JSON or a caller) is kept as a tuple of floats
            object.__setattr__(self, "range", (float(self.range[0]), float(self.range[1])))

    @property
    def source(self) -> str:
        """The source for messages: "CC21", "CC21/ch0" or the OSC address."""
        if self.cc is None:
            return str(self.osc)
        return f"CC{self.cc}" + (f"/ch{self.channel}" if self.channel is not None else "")

    def to_dict(self) -> dict[str, Any]:
        """The binding as it is written in a bindings file (fields at their defaults left out)."""
        out: dict[str, Any] = {"param": self.param}
        if self.cc is not None:
            out["cc"], out["channel"] = self.cc, self.channel
        else:
            out["osc"] = self.osc
        if self.component is not None:
            out["component"] = self.component
        if self.range is not None:
            out["range"] = list(self.range)
        if self.normalized:
            out["normalized"] = True
        if self.smooth:
            out["smooth"] = self.smooth
        return out


def _is_int(x: Any) -> bool:
    return isinstance(x, int) and not isinstance(x, bool)


def _is_number(x: Any) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def check_fields(f: dict[str, Any], where: str) -> None:
    """Raise LiveBindingError, naming ``where`` and the field, unless the binding fields ``f`` are valid."""
    def bad(key: str, what: str) -> LiveBindingError:
        return LiveBindingError(f"{where}.{key}: {what}, got {f.get(key)!r}")
    cc, osc, channel = f.get("cc"), f.get("osc"), f.get("channel")
    if not isinstance(f.get("param"), str) or not f["param"]:
        raise bad("param", "must be the name of a live parameter (a non-empty string)")
    if (cc is None) == (osc is None):
        raise LiveBindingError(f"{where}: give exactly one source, 'cc' (MIDI) or 'osc' (an OSC address)")
    if cc is not None and not (_is_int(cc) and 0 <= cc <= 127):
        raise bad("cc", "must be a MIDI control number, an integer 0..127")
    if channel is not None and not (_is_int(channel) and 0 <= channel <= 15):
        raise bad("channel", "must be a MIDI channel 0..15 (as mido counts) or null for any")
    if channel is not None and cc is None:
        raise LiveBindingError(f"{where}.channel: a channel belongs to a MIDI 'cc' binding, not an OSC one")
    if osc is not None and not (isinstance(osc, str) and osc.startswith("/") and " " not in osc):
        raise bad("osc", "must be an OSC address starting with '/' (no spaces)")
    comp = f.get("component")
    if comp is not None and not (_is_int(comp) and 0 <= comp <= 2):
        raise bad("component", "must be 0, 1 or 2 (x, y, z of a 3-vector parameter)")
    r = f.get("range")
    if r is not None and not (isinstance(r, (tuple, list)) and len(r) == 2 and all(_is_number(x) for x in r)
                              and r[0] < r[1]):
        raise bad("range", "must be two finite numbers [low, high] with low < high")
    if not isinstance(f.get("normalized", False), bool):
        raise bad("normalized", "must be true or false")
    if f.get("normalized") and osc is None:
        raise LiveBindingError(f"{where}.normalized: only an OSC binding is normalized (a CC always spans its range)")
    smooth = f.get("smooth", 0.0)
    if not (_is_number(smooth) and smooth >= 0):
        raise bad("smooth", "must be a number of seconds >= 0")


def binding_range(b: Binding, p: Param) -> tuple[float, float] | None:
    """The (low, high) a binding maps onto and clamps to: its own range, else the parameter's, else None."""
    if b.range is not None:
        return float(b.range[0]), float(b.range[1])
    rng = getattr(p, "range", None)
    return None if rng is None else (float(rng[0]), float(rng[1]))


def check_target(b: Binding, p: Param) -> None:
    """Raise LiveBindingError unless ``b`` can drive ``p`` (a CC needs a finite range, a vector a component
    or 3 OSC values)."""
    vector = np.ndim(p.value) > 0
    if b.component is not None and not vector:
        raise LiveBindingError(f"binding {b.source} -> {b.param}: 'component' is for a 3-vector parameter; "
                               f"{b.param} is a number")
    if b.cc is not None:
        rng = binding_range(b, p)
        if rng is None or not all(math.isfinite(x) for x in rng):
            raise LiveBindingError(f"binding {b.source} -> {b.param}: a MIDI CC spans a range, and {b.param} has "
                                   f"no finite one: give the binding a range, e.g. range=(0.5, 2.0)")
        if vector and b.component is None:
            raise LiveBindingError(f"binding {b.source} -> {b.param}: one CC drives one number; {b.param} is a "
                                   f"3-vector: give component=0, 1 or 2")


def clamp(x: Any, rng: tuple[float, float] | None) -> Any:
    """``x`` (a number or array) clamped to ``rng`` (None: unchanged)."""
    if rng is None:
        return x
    out = np.clip(np.asarray(x, dtype=np.float64), rng[0], rng[1])
    return float(out) if out.ndim == 0 else out


def cc_value(b: Binding, p: Param, value: int) -> float:
    """The parameter value of CC ``value`` (0..127) for binding ``b`` on ``p``: linear over the range."""
    rng = binding_range(b, p)
    assert rng is not None  # check_target made sure
    lo, hi = rng
    return lo + (hi - lo) * min(max(int(value), 0), 127) / 127.0


def osc_value(b: Binding, p: Param, args: Sequence[Any], base: Any = None) -> Any:
    """The new value of ``p`` from an OSC message's arguments, or None when they do not fit.

    One number sets a scalar parameter (or ``b.component`` of a vector); three numbers set a
    whole vector. With ``b.normalized`` each number 0..1 spans the range. The result is
    clamped to the range; for a component, it is the whole new vector (the other components
    from ``base``, default the parameter's value)."""
    nums = [float(a) for a in args if _is_number(a)]
    if len(nums) != len(args) or not nums:
        return None
    rng = binding_range(b, p)
    if b.normalized:
        if rng is None or not all(math.isfinite(x) for x in rng):
            return None
        nums = [rng[0] + (rng[1] - rng[0]) * min(max(x, 0.0), 1.0) for x in nums]
    vector = np.ndim(p.value) > 0
    if not vector:
        return clamp(nums[0], rng) if len(nums) == 1 else None
    if b.component is not None:
        if len(nums) != 1:
            return None
        out = np.array(p.value if base is None else base, dtype=np.float64)
        out[b.component] = clamp(nums[0], rng)
        return out
    return clamp(np.array(nums), rng) if len(nums) == 3 else None


# -- files ---------------------------------------------------------------------------------
def bindings_from_dict(doc: Any, source: str = "bindings") -> list[Binding]:
    """The bindings of a parsed bindings document; LiveBindingError names ``source`` and the JSON path."""
    if not isinstance(doc, dict):
        raise LiveBindingError(f"{source}: expected a JSON object with 'version' and 'bindings', got "
                               f"{type(doc).__name__}")
    extra = sorted(set(doc) - {"version", "bindings"})
    if extra:
        raise LiveBindingError(f"{source}: unknown key {extra[0]!r} (expected 'version' and 'bindings')")
    if doc.get("version") != VERSION:
        raise LiveBindingError(f"{source}: version: expected {VERSION}, got {doc.get('version')!r}")
    items = doc.get("bindings")
    if not isinstance(items, list):
        raise LiveBindingError(f"{source}: bindings: expected a list, got {type(items).__name__}")
    out = []
    for i, item in enumerate(items):
        where = f"{source}: bindings[{i}]"
        if not isinstance(item, dict):
            raise LiveBindingError(f"{where}: expected an object, got {type(item).__name__}")
        unknown = sorted(set(item) - set(KEYS))
        if unknown:
            raise LiveBindingError(f"{where}: unknown key {unknown[0]!r} (known: {', '.join(KEYS)})")
        if "param" not in item:
            raise LiveBindingError(f"{where}: missing 'param' (the name of the live parameter)")
        check_fields(item, where)
        out.append(Binding(**item))
    return out


def load_bindings(path: str | Path) -> list[Binding]:
    """Read a bindings file (see the module docstring); errors name the file and the JSON path."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as exc:
        raise LiveBindingError(f"{p}: cannot read the bindings file: {exc.strerror or exc}") from None
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise LiveBindingError(f"{p}: not JSON: {exc.msg} at line {exc.lineno} column {exc.colno}") from None
    return bindings_from_dict(doc, str(p))


def bindings_to_dict(bindings: Sequence[Binding]) -> dict[str, Any]:
    """A bindings document (the inverse of :func:`bindings_from_dict`)."""
    return {"version": VERSION, "bindings": [b.to_dict() for b in bindings]}


def save_bindings(bindings: Sequence[Binding], path: str | Path) -> Path:
    """Write ``bindings`` as a JSON bindings file at ``path``; returns the path."""
    p = Path(path)
    p.write_text(json.dumps(bindings_to_dict(bindings), indent=2) + "\n", encoding="utf-8")
    return p

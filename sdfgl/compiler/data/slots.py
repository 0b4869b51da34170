"""Parameters of an instance type read from data: a primitive's numbers as texels of its record.

A primitive class whose code reads its numbers only as GLSL (never in Python) is one type
for all its instances in a grid union: its code is written once over a *template* whose
numbers are :class:`Slot` expressions reading the instance's record.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ...nodes.base import Node, Primitive
from ...params import Live
from ..emitter import Emitter


class SlotRead(Exception):
    """A node's code used a parameter's value in Python: that parameter cannot be data."""


class Slot(Live):
    """A parameter of a primitive type read from an instance's texels in the shader."""

    def __init__(self, expr: str, dims: int) -> None:
        super().__init__("slot")
        self.expr, self._dims = expr, dims

    @property
    def value(self) -> Any:
        raise SlotRead()

    @property
    def dims(self) -> int:
        return self._dims

    def roots(self) -> list:
        return []

    def glsl(self, em: "Emitter") -> str:
        return self.expr


def slot_values(prim: Primitive) -> list[tuple[str, np.ndarray]]:
    """The numeric attributes of a primitive that its code may read from data."""
    out = []
    for name, val in prim.__dict__.items():
        if name in ("params", "children") or name.startswith("_"):
            continue
        if name == "c" and type(prim).__name__ == "Sphere":
            continue  # folded into the translation (see build)
        if isinstance(val, (float, np.floating)) and not isinstance(val, bool):
            out.append((name, np.array([float(val)])))
        elif isinstance(val, np.ndarray) and val.dtype.kind == "f" and val.ndim == 1 and 2 <= val.size <= 4:
            out.append((name, val.astype(np.float64)))
    return out


def component(base: int, i: int) -> str:
    """GLSL for float ``i`` of a record read into texels d0, d1, ... starting at float ``base``."""
    k = base + i
    return f"d{k // 4}.{'xyzw'[k % 4]}"


def slot_expr(base: int, n: int) -> str:
    """GLSL for ``n`` floats of a record from float ``base`` on: a float or a vecN."""
    parts = [component(base, i) for i in range(n)]
    return parts[0] if n == 1 else f"vec{n}({', '.join(parts)})"


def template(prim: Node, slots: list[str], at: int) -> Node:
    """A copy of ``prim`` whose slot attributes are read from the record's texels."""
    tpl = type(prim).__new__(type(prim))
    tpl.__dict__.update(prim.__dict__)
    pos = at
    for name, val in slot_values(prim):
        if name in slots:
            tpl.__dict__[name] = Slot(slot_expr(pos, len(val)), len(val))
            pos += len(val)
    return tpl


def primitive_slots(prim: Primitive) -> list[str] | None:
    """The attributes of ``prim`` the shader can read from data, or None if its code needs
    a fixed value (then each distinct primitive is its own type)."""
    names = [name for name, _ in slot_values(prim)]
    try:
        template(prim, names, 0)._emit(Emitter("dist"), "q")
    except SlotRead:
        return None
    except Exception:  # noqa: BLE001 - any other failure: keep the values as code
        return None
    return names

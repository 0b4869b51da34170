"""Length units of a printed model: the 3MF unit names, their short forms and their size in millimetres.

Scene coordinates are taken as the chosen unit (nothing is scaled): a scene 20 units wide
saved with ``units="millimeter"`` is a 20 mm part.
"""
from __future__ import annotations

from ..errors import ParameterError

MILLIMETRES = {"micron": 1e-3, "millimeter": 1.0, "centimeter": 10.0, "inch": 25.4, "foot": 304.8, "meter": 1000.0}
"""The 3MF core specification's units and their size in millimetres."""

ALIASES = {"um": "micron", "µm": "micron", "mm": "millimeter", "millimetre": "millimeter", "cm": "centimeter",
           "centimetre": "centimeter", "in": "inch", "ft": "foot", "m": "meter", "metre": "meter"}
"""Short and British spellings accepted for the unit names."""

SYMBOLS = {"micron": "um", "millimeter": "mm", "centimeter": "cm", "inch": "in", "foot": "ft", "meter": "m"}
"""The short form each unit prints with."""


def unit_name(units: str, where: str = "units") -> str:
    """The 3MF name of ``units`` ("mm" -> "millimeter"); a clear error for an unknown one."""
    if not isinstance(units, str):
        raise ParameterError(f"{where}: a unit must be a string such as 'mm', got {type(units).__name__} {units!r}")
    key = units.strip().lower()
    key = key[:-1] if key.endswith("s") and key[:-1] in MILLIMETRES else key
    name = ALIASES.get(key, key)
    if name not in MILLIMETRES:
        raise ParameterError(f"{where}: unknown unit {units!r}; use one of "
                             f"{', '.join(sorted(set(MILLIMETRES) | set(ALIASES)))}")
    return name

"""The base type of live values: what the checks need to know of :mod:`sdfgl.params`.

A live value (a parameter or an expression over parameters) changes after the node that
uses it is built. The checks of :mod:`sdfgl.values.validate` run once now and again on
every change; they see live values only through this interface, so this layer does not
import the parameters' module (which subclasses it).
"""
from __future__ import annotations

from typing import Any, Callable


class LiveValue:
    """A value read now through :attr:`value` and re-checked whenever one of its
    :meth:`roots` changes (subclassed by :class:`sdfgl.params.Live`)."""

    @property
    def value(self) -> Any:
        """The current value: a float or a float64 array."""
        raise NotImplementedError

    @property
    def dims(self) -> int:
        """1 for a scalar, 3 for a 3-vector."""
        raise NotImplementedError

    def roots(self) -> list[Any]:
        """The settable parameters this value reads (each has :meth:`add_check`)."""
        raise NotImplementedError

    def add_check(self, check: Callable[[Any], None]) -> None:
        """Run ``check(new_value)`` before each change of this parameter is accepted."""
        raise NotImplementedError

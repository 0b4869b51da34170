"""The errors of live control: a malformed binding, a MIDI port or OSC server that cannot open."""
from __future__ import annotations

from ..errors import SdfglError


class LiveBindingError(SdfglError, ValueError):
    """A binding or a bindings file is malformed; the message names the file and JSON path at fault."""


class LiveInputError(SdfglError):
    """A MIDI port or an OSC server could not be opened; the message names it and why."""

"""MIDI input through mido with the python-rtmidi backend: a port whose messages go to a callback.

Needs the optional extra ``sdfgl[live]``. rtmidi calls the callback on its own thread. On
Linux the ports come from the ALSA sequencer (``/dev/snd/seq``); a virtual port lets other
programs connect to sdfgl instead.
"""
from __future__ import annotations

from typing import Any, Callable

from ..extras import require_extra
from .errors import LiveInputError


def input_names() -> list[str]:
    """The names of the MIDI input ports this system offers (empty when it has no MIDI)."""
    require_extra("live", "mido", "rtmidi", purpose="MIDI input")
    import mido
    try:
        return list(mido.get_input_names())
    except Exception:  # noqa: BLE001 - rtmidi raises its own errors when the system has no MIDI at all
        return []


def open_input(name: str | None, callback: Callable[[Any], None], virtual: bool = False) -> Any:
    """Open MIDI input port ``name`` (None: the first one; with ``virtual``, a new port of that name)
    calling ``callback(message)`` for each message. Returns the mido port (close it when done)."""
    require_extra("live", "mido", "rtmidi", purpose="MIDI input")
    import mido
    if not virtual:
        names = input_names()
        if name is None and names:
            name = names[0]
        if name not in names:
            known = ", ".join(repr(n) for n in names) or "none (no MIDI device, or no ALSA sequencer)"
            what = "no MIDI input port" if name is None else f"no MIDI input port {name!r}"
            raise LiveInputError(f"MIDI: {what}; this system has: {known}")
    try:
        return mido.open_input(name or "sdfgl", virtual=virtual, callback=callback)
    except Exception as exc:  # noqa: BLE001 - rtmidi's errors (no sequencer, port gone) become one message
        raise LiveInputError(f"MIDI: cannot open {'virtual ' if virtual else ''}port {name!r}: {exc}") from None

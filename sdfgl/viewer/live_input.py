"""The window's live control: MIDI and OSC messages move the parameters on screen (no recompile).

The controller (:class:`sdfgl.live.LiveControl`) runs deferred: its threads queue values
and wake the window, whose thread sets them between frames, exactly as the panel's sliders
do. Bindings name parameters, so they keep working when the scene file is reloaded. MIDI
learn (the panel's "learn" button) binds the next control moved to a parameter; "save
bindings" writes the bindings file.
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import glfw

from ..live import LiveBindingError, LiveControl
from ..params import Param

if TYPE_CHECKING:  # pragma: no cover
    from .window import Viewer

DEFAULT_FILE = "live.json"  # where "save bindings" writes without --bindings (in the screenshot folder)


class LiveInput:
    """``control``'s messages for ``viewer``; ``path`` is the bindings file it loaded (and saves to)."""

    def __init__(self, viewer: "Viewer", control: LiveControl, path: str | Path | None = None) -> None:
        self.viewer, self.control = viewer, control
        self.path = Path(path) if path is not None else None
        control.deferred = True
        control.use(viewer.scene.live_params())
        if self.path is not None:
            control.load(self.path)  # a bad file fails before the window opens, naming its JSON path

    def start(self) -> None:
        """Open the inputs (once the window exists: their threads wake it)."""
        self.control.wake = glfw.post_empty_event
        self.control.start()

    def poll(self) -> None:
        """Set the values that arrived (on the window's thread); a change redraws with the same program."""
        c = self.control
        c.use(self.viewer.scene.live_params())
        if c.apply_pending():
            self.viewer.param_changed()
        now = self.state()
        if now != self.viewer.state.live:
            self.viewer.state.live = now
            self.viewer.repaint = True  # the panel shows the bindings and whether it waits for a control

    def state(self) -> dict[str, Any]:
        """What the state file shows of live control."""
        c = self.control
        return {"bindings": c.describe(), "learning": c.learning[0] if c.learning else None,
                "received": c.received, "error": c.last_error, "osc_port": c.osc_port}

    def learn(self, p: Param) -> str:
        """Bind the next control moved to ``p``; returns the panel's message."""
        try:
            self.control.learn(p)
        except LiveBindingError as exc:  # no range for a CC to span: the panel says so
            return str(exc)
        return f"move a MIDI control (or send OSC) to bind {self.control.key(p)}"

    def sources(self, p: Param) -> str:
        """The controls bound to ``p``, for the panel ("CC21, /radius"; "" when none)."""
        key = self.control.key(p)
        return ", ".join(b.source for b in list(self.control.bindings) if b.param == key)

    def save(self) -> str:
        """Write the bindings file (the one loaded, else live.json in the screenshot folder); the panel's message."""
        path = self.path or self.viewer.screenshot_dir / DEFAULT_FILE
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            self.control.save(path)
        except Exception as exc:  # noqa: BLE001 - OSError, LiveBindingError: shown in the panel
            return f"could not save {path}: {exc}"
        return f"saved {path}"

    def close(self) -> None:
        """Close the inputs and stop their threads."""
        self.control.stop()

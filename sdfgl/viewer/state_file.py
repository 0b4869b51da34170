"""What the window shows, as a dataclass, as a JSON file for scripts and tests, and as its title.

``sdfgl view --state-file PATH`` writes it: the camera, the settings, counters of frames,
compiles and reloads, the overlay text and the panel's layout. The Xvfb tests drive the
window with real input events and read this file to see what happened.
"""
from __future__ import annotations

import json
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..camera import OrbitCamera

PRESENT_LOG = 1200  # presents kept in the state file's present_log
STATE_EVERY_S = 0.05  # the state file is written at most this often (and within 0.2 s of any change)


@dataclass
class ViewState:
    """What the viewer shows; written to the state file for scripts and tests."""

    settings: dict[str, Any]
    frames: int = 0
    compiles: int = 0
    reloads: int = 0
    error: str = ""
    last_frame_ms: float = 0.0
    scale: float = 1.0
    samples: int = 0
    moving: bool = False
    screenshots: list[str] = field(default_factory=list)
    frame_log: list[tuple[bool, float, float]] = field(default_factory=list)  # (moving, ms, scale)
    compiling: bool = False
    loading: float | None = None  # seconds the scene file's reload has been loading (None: none is)
    param_edits: int = 0
    overlay: str = ""  # the text drawn over the image (help, hint, status, error)
    overlay_font: int = 0  # its font size in pixels
    overlay_fits: bool = True  # whether all of it fits the window at that size
    overlay_size: tuple[int, int] = (0, 0)  # the window size it was laid out for
    panel: dict[str, Any] = field(default_factory=dict)
    compile_log: list[dict[str, float]] = field(default_factory=list)  # worker timings of each new program
    present_log: list[tuple[float, float | None, bool]] = field(default_factory=list)  # (wall time, yaw drawn, compiling)
    mean_steps: float = 0.0  # map() calls per pixel of the image on screen (pixel-centre rays)
    view: tuple[int, int, int, int] = (0, 0, 0, 0)  # the image's rectangle in the window: x, y, width, height
    live: dict[str, Any] = field(default_factory=dict)  # MIDI/OSC control: bindings, learning, messages, errors

    def log_present(self, yaw: float | None) -> None:
        """Note a present: when, the yaw of the frame shown (None: no frame yet), whether compiling."""
        self.present_log.append((time.time(), yaw, self.compiling))
        del self.present_log[:-PRESENT_LOG]


class StateFile:
    """Writes a :class:`ViewState` with the camera, scene label and window size as JSON, at most
    every STATE_EVERY_S (``path`` None: nothing is written, the clock still runs)."""

    def __init__(self, path: str | Path | None) -> None:
        self.path = Path(path) if path else None
        self.written_at = 0.0

    def due(self) -> bool:
        """Whether STATE_EVERY_S has passed since the last write."""
        return time.perf_counter() - self.written_at > STATE_EVERY_S

    def write(self, state: ViewState, camera: OrbitCamera, scene_label: str, size: tuple[int, int]) -> None:
        """Replace the file in one step (a reader never sees half of it)."""
        self.written_at = time.perf_counter()
        if self.path is None:
            return
        c = camera
        data = {"yaw": c.yaw, "pitch": c.pitch, "distance": c.distance, "target": c.target.tolist(),
                "scene": scene_label, "size": list(size), **dict(state.__dict__)}
        tmp = self.path.with_suffix(".tmp")
        tmp.write_text(json.dumps(data, default=str))
        os.replace(tmp, self.path)


def window_title(name: str, ms: float, state: ViewState, max_samples: int) -> str:
    """The window's title: the scene's ``name``, the frame time ``ms``, resolution or samples, settings."""
    s, st = state.settings, state
    shadows = s.get("shadows") or "off"
    w, h = state.view[2:]
    res = (f"{int(w * st.scale)}x{int(h * st.scale)} ({st.scale:.0%})" if st.moving
           else f"{w}x{h} {st.samples}/{max_samples} samples")
    err = " | ERROR (see overlay)" if st.error else ""
    return (f"sdfgl: {name} | {ms:.1f} ms ({1000 / max(ms, 1e-3):.0f} fps) | {res} | "
            f"{s.get('method', 'enhanced')} aa{s.get('aa', 1)} shadows {shadows} "
            f"ao {'on' if s.get('ao') else 'off'}{' debug ' + s['debug'] if s.get('debug') else ''}{err}")

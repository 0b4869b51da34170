"""The window's mouse and keys: the side panel gets them first, then orbit, pan, zoom and
the keys of KEYS_HELP, each an action of the :class:`~sdfgl.viewer.window.Viewer`."""
from __future__ import annotations

import time
from typing import TYPE_CHECKING, Any, Callable

import glfw

from ..camera import OrbitCamera
from ..nodes.base import IMPLICIT
from ..settings import DISTANCE_METHODS

if TYPE_CHECKING:  # pragma: no cover
    from .window import Viewer

KEYS_HELP = """\
mouse   left drag: orbit   right/middle drag: pan   wheel: zoom to target
A       anti-aliasing 1..4 samples per pixel side
S       shadows off / hard / soft
O       ambient occlusion on / off
M       marching method (sphere, relaxed, enhanced, newton, forward_newton)
G       ground plane on / off
D       debug view: off / steps heat map / normals / depth
F       frame the whole scene        R   reset the view
N       side panel: parameters, render settings, scene tree
P       save a screenshot PNG        H   this help
Q, Esc  quit"""
KEYS_COMPACT = """\
drag: orbit / pan
wheel: zoom
A aa   S shadows
O AO   M method
G ground  D debug
F frame   R reset
N panel   P shot
H help    Q quit"""  # the help of a window too small for KEYS_HELP at a legible size

METHOD_CYCLE = ("sphere", "relaxed", "enhanced", "newton", "forward_newton")
DEBUG_CYCLE = (None, "steps", "normal", "depth")
SHADOW_CYCLE = (False, "hard", "soft")
MOVE_HOLD_S = 0.15  # a camera change keeps the low-resolution mode this long
ZOOM_RANGE = (1e-4, 100.0)  # wheel zoom keeps the distance within these multiples of the framing distance


class Input:
    """The glfw input callbacks of ``viewer``'s window, and whether the camera is moving."""

    def __init__(self, viewer: "Viewer") -> None:
        self.viewer = viewer
        self.drag: tuple[int, float, float] | None = None  # (button, x, y) while a button is held
        self.last_move = -1.0  # when the camera last moved (perf_counter)

    def attach(self, window: Any, guarded: Callable[[Any, str], Any]) -> None:
        """Install the callbacks on ``window``, each wrapped by ``guarded(fn, where)``."""
        panel = self.viewer.panel
        if panel is not None:
            glfw.set_char_callback(window, guarded(lambda _w, c: self.viewer.redraw_ui(panel.on_char(c)), "key"))
        glfw.set_cursor_pos_callback(window, guarded(self.on_cursor, "mouse"))
        glfw.set_mouse_button_callback(window, guarded(self.on_button, "mouse"))
        glfw.set_scroll_callback(window, guarded(self.on_scroll, "zoom"))
        glfw.set_key_callback(window, guarded(self.on_key, "key"))

    def moved(self) -> None:
        """The camera changed: draw again, at reduced resolution while it keeps moving."""
        self.last_move = time.perf_counter()
        self.viewer.mark()

    def moving(self) -> bool:
        """A button is held, or the camera moved less than MOVE_HOLD_S ago."""
        return self.drag is not None or time.perf_counter() - self.last_move < MOVE_HOLD_S

    def _panel_takes(self, handled: Callable[[], bool]) -> bool:
        """Whether the visible panel takes the event (``handled()`` asks it)."""
        panel = self.viewer.panel
        if panel is None or not panel.visible:
            return False
        self.viewer.redraw_ui()
        return handled()

    def on_cursor(self, _w: Any, x: float, y: float) -> None:
        """Orbit (left button) or pan (the others) by the drag since the last position."""
        v = self.viewer
        if self._panel_takes(lambda: v.panel.on_cursor(x, y) and self.drag is None):
            return
        if self.drag is None:
            return
        button, x0, y0 = self.drag
        dx, dy = x - x0, y - y0
        self.drag = (button, x, y)
        if button == glfw.MOUSE_BUTTON_LEFT:
            v.camera.orbit(-0.4 * dx, 0.4 * dy)
        else:
            h = glfw.get_window_size(v.window)[1] or 1
            v.camera.pan(dx / h, dy / h)
        self.moved()

    def on_button(self, _w: Any, button: int, action: int, _mods: int) -> None:
        """A press starts a drag (unless the panel takes it), a release ends it."""
        v = self.viewer
        if self._panel_takes(lambda: v.panel.on_button(button, action == glfw.PRESS) and action == glfw.PRESS):
            return
        if action == glfw.PRESS:
            x, y = glfw.get_cursor_pos(v.window)
            self.drag = (button, x, y)
        elif action == glfw.RELEASE:
            self.drag = None

    def on_scroll(self, _w: Any, dx: float, dy: float) -> None:
        """Zoom towards the target, within ZOOM_RANGE of the framing distance."""
        v = self.viewer
        if self._panel_takes(lambda: v.panel.on_scroll(dx, dy)):
            return
        framing = OrbitCamera.framing(*v.scene.bounds, fov=v.camera.fov).distance
        lo, hi = ZOOM_RANGE[0] * framing, ZOOM_RANGE[1] * framing
        target = min(max(v.camera.distance * 0.88 ** dy, lo), hi)
        v.camera.zoom(target / v.camera.distance)
        self.moved()

    def cycle(self, key: str, values: tuple) -> None:
        """Set ``key`` to the value after its current one in ``values`` (the first if it is none)."""
        cur = self.viewer.wanted_settings.get(key)
        self.viewer.apply_settings({key: values[(values.index(cur) + 1) % len(values)] if cur in values
                                    else values[0]})

    def on_key(self, _w: Any, key: int, scan: int, action: int, mods: int) -> None:
        """The keys of KEYS_HELP (typing into the panel goes to the panel)."""
        v = self.viewer
        if self._panel_takes(lambda: v.panel.on_key(key, scan, action, mods)):
            return
        if action != glfw.PRESS:
            return
        v.hide_hint()
        s = v.wanted_settings
        if key in (glfw.KEY_Q, glfw.KEY_ESCAPE):
            glfw.set_window_should_close(v.window, True)
        elif key == glfw.KEY_A:
            v.apply_settings({"aa": s.get("aa", 1) % 4 + 1})
        elif key == glfw.KEY_S:
            self.cycle("shadows", SHADOW_CYCLE)
        elif key == glfw.KEY_O:
            v.apply_settings({"ao": not s.get("ao", False)})
        elif key == glfw.KEY_M:
            methods = METHOD_CYCLE if v.scene.exactness != IMPLICIT else tuple(
                m for m in METHOD_CYCLE if m not in DISTANCE_METHODS)
            self.cycle("method", methods)
        elif key == glfw.KEY_G:
            v.apply_settings({"ground": not s.get("ground", False)})
        elif key == glfw.KEY_D:
            self.cycle("debug", DEBUG_CYCLE)
        elif key == glfw.KEY_F:
            v.frame_scene()
            self.moved()
        elif key == glfw.KEY_R:
            v.reset_view()
            self.moved()
        elif key == glfw.KEY_P:
            v.screenshot()
        elif key == glfw.KEY_N:
            v.toggle_panel()
        elif key in (glfw.KEY_H, glfw.KEY_F1):
            v.toggle_help()

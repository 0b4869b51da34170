"""The interactive window: mouse orbit, live toggles, hot reload, adaptive resolution.

While the camera moves, frames are drawn at a reduced resolution chosen so a frame
stays under the target time; when it stops, full-resolution frames with sub-pixel
jitter are accumulated into a clean anti-aliased image, and then nothing is redrawn
until something changes. The scene is drawn by a render thread (:mod:`.render_thread`);
this thread answers input, presents the newest image right of the side panel, and
draws the panel and the text overlay.
"""
from __future__ import annotations

import copy
import json
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import glfw
import moderngl
import numpy as np
from PIL import Image, ImageDraw

from .. import shaderlib
from ..camera import Camera, OrbitCamera
from ..codegen import ShaderSource, generate
from ..errors import ContextError, SdfglError
from ..nodes.base import IMPLICIT, Node
from ..render import shader_origin
from ..scenefile import load_scene_file
from ..settings import DISTANCE_METHODS, Settings
from . import panel as panel_mod
from . import rawgl
from .overlay import layout_text
from .programs import Job, Result
from .render_thread import LANES, Exchange, Frame, FrameSpec, Lane, describe_error

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
PRESENT_LOG = 1200  # presents kept in the state file's present_log
STATE_EVERY_S = 0.05  # the state file is written at most this often (and within 0.2 s of any change)
ZOOM_RANGE = (1e-4, 100.0)  # wheel zoom keeps the distance within these multiples of the framing distance


def _codegen(scene: Node, settings: Settings, origin: np.ndarray, projection: str, highlight: Node | None) -> Any:
    """The window's shader source (run in a render thread); any failure becomes one overlay message."""
    try:
        return generate(scene, settings, origin, projection=projection, highlight=highlight)
    except SdfglError:
        raise
    except Exception as exc:  # noqa: BLE001 - a user's scene may raise anything while generating code
        raise SdfglError(describe_error(exc, "compile")) from exc


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


class Viewer:
    """A glfw window showing a scene (or a scene file, reloaded when it changes)."""

    def __init__(self, scene: Node | None = None, camera: Camera | None = None, *, path: str | Path | None = None,
                 size: tuple[int, int] = (960, 540), target_ms: float = 50.0, adaptive: bool = True,
                 max_samples: int = 16, state_file: str | Path | None = None,
                 screenshot_dir: str | Path = ".", panel: bool | None = None, **settings: Any) -> None:
        self.path = Path(path) if path else None
        self._explicit = dict(settings)  # given by the caller: a reload keeps them
        self._file_settings: dict[str, Any] = {}
        if self.path is not None:
            sf = load_scene_file(self.path)
            scene, camera = sf.scene, camera or sf.camera
            self._file_settings = sf.settings
            settings = {**sf.settings, **settings}
            self._mtime = self.path.stat().st_mtime
        if scene is None:
            raise SdfglError("Viewer needs a scene or a scene file")
        self.scene = scene
        self.state = ViewState(settings={**self._base(scene), **settings})
        Settings.build(**self.state.settings)  # validate before opening a window
        self.home = self._orbit_of(camera, scene, size[0] / size[1])
        self.camera = self._orbit_of(camera, scene, size[0] / size[1])
        self.size, self.target_ms, self.adaptive = size, target_ms, adaptive
        self.max_samples = max_samples
        self.state_file = Path(state_file) if state_file else None
        self.screenshot_dir = Path(screenshot_dir)
        self.show_help = False
        self.show_hint = True  # "H: help" until the first key
        self._want_panel = panel
        self._ui_frames = 0  # frames to redraw for the panel alone (hover, drag) without re-rendering the scene
        self._last_move = -1.0
        self._drag: tuple[int, float, float] | None = None
        self._dirty = True     # the render thread needs a new spec (camera, params, size, program)
        self._repaint = True   # the window needs presenting again (overlay, panel)
        self._version = 0      # of the newest spec
        self._spec_moving = False
        self._serial = 0       # of the newest frame taken
        self._frame: Frame | None = None  # on screen
        self._overlay_key: tuple | None = None
        self._shots = 0  # screenshots asked for
        self._state_at = 0.0  # when the state file was last written
        # scene, lane, program key (source text), source, origin
        self._shown: tuple[Node, int, str, ShaderSource, np.ndarray] | None = None
        self._good: tuple[Any, Node, dict[str, Any]] | None = None  # the last (shown, scene, settings) that drew
        self._token = 0
        self._error_token = 0
        self._highlight: tuple[Node, Node] | None = None  # (scene, subtree) tinted by the "select" debug view
        self._debug_before: Any = None
        # what the newest compile is for: scene, settings, why, origin, the file's settings (reloads)
        self._pending: tuple[Node, dict[str, Any], str, np.ndarray, dict[str, Any] | None] | None = None
        self._open_window()
        self._request(self.scene, self.state.settings, "open")

    # -- set-up ---------------------------------------------------------------------
    @staticmethod
    def _base(scene: Node) -> dict[str, Any]:
        """The window's default settings for ``scene``."""
        base: dict[str, Any] = {"aa": 1, "shadows": "soft", "ao": scene.exactness != IMPLICIT, "ground": False}
        if scene.exactness == IMPLICIT:
            base["method"] = "newton"
        return base

    @staticmethod
    def _orbit_of(camera: Camera | None, scene: Node, aspect: float) -> OrbitCamera:
        return OrbitCamera.of(camera, *scene.bounds, aspect=aspect)

    def _open_window(self) -> None:
        if not glfw.init():
            raise ContextError("glfw could not initialise: no display? (set DISPLAY, or run under Xvfb)")
        glfw.window_hint(glfw.CONTEXT_VERSION_MAJOR, 3)
        glfw.window_hint(glfw.CONTEXT_VERSION_MINOR, 3)
        glfw.window_hint(glfw.OPENGL_PROFILE, glfw.OPENGL_CORE_PROFILE)
        glfw.window_hint(glfw.OPENGL_FORWARD_COMPAT, True)
        glfw.window_hint(glfw.SCALE_TO_MONITOR, True)
        self.window = glfw.create_window(self.size[0], self.size[1], "sdfgl", None, None)
        if not self.window:
            glfw.terminate()
            raise ContextError("glfw could not open an OpenGL 3.3 core window")
        glfw.make_context_current(self.window)
        glfw.swap_interval(0)
        self.ctx = moderngl.create_context()
        self.present = self.ctx.program(vertex_shader=shaderlib.read("fullscreen.vert"),
                                        fragment_shader=shaderlib.read("present.frag"))
        self.present_vao = self.ctx.vertex_array(self.present, [])
        self.gl = rawgl.GL()
        self.exchange = Exchange()
        self.lanes: list[Lane] = []
        for i in range(LANES):
            self.lanes.append(Lane(i, self.window, self.exchange))
        self.exchange.lanes = self.lanes
        self._overlay_tex: moderngl.Texture | None = None
        self.panel: panel_mod.Panel | None = None
        self._resize_targets()
        self._panel_missing = panel_mod.available()
        if not self._panel_missing:
            self.panel = panel_mod.Panel(self)
            if self._want_panel is not None:
                self.panel.visible = self._want_panel
            glfw.set_char_callback(self.window, self._guarded(lambda _w, c: self._ui(self.panel.on_char(c)), "key"))
        glfw.set_cursor_pos_callback(self.window, self._guarded(self._on_cursor, "mouse"))
        glfw.set_mouse_button_callback(self.window, self._guarded(self._on_button, "mouse"))
        glfw.set_scroll_callback(self.window, self._guarded(self._on_scroll, "zoom"))
        glfw.set_key_callback(self.window, self._guarded(self._on_key, "key"))
        glfw.set_framebuffer_size_callback(self.window, self._guarded(lambda *_: self._resize_targets(), "resize"))
        glfw.set_window_refresh_callback(self.window, lambda *_: self._mark())
        self._write_state()  # scripts see the window at once; the render threads may take a while to start
        for lane in self.lanes:
            lane.wait_ready()

    def _resize_targets(self) -> None:
        fw, fh = glfw.get_framebuffer_size(self.window)
        self.fb_size = (max(fw, 1), max(fh, 1))
        self._mark()

    def view_rect(self) -> tuple[int, int, int, int]:
        """The image's rectangle in framebuffer pixels (x, y, width, height): right of the panel when it shows."""
        fw, fh = self.fb_size
        x = 0
        if self.panel is not None and self.panel.visible:
            ww = glfw.get_window_size(self.window)[0] or fw
            x = min(fw - 1, round(panel_mod.WIDTH * fw / ww))
        return x, 0, fw - x, fh

    def _aspect(self) -> float:
        _, _, w, h = self.view_rect()
        return w / h

    # -- events -----------------------------------------------------------------------
    def _guarded(self, fn: Any, where: str) -> Any:
        """``fn`` as a glfw callback that shows any exception in the window instead of raising it."""
        def callback(*args: Any) -> None:
            try:
                fn(*args)
            except Exception as exc:  # noqa: BLE001 - the window never dies from input
                self._set_error(describe_error(exc, where))
        return callback

    def _mark(self, moved: bool = False) -> None:
        """The image must be drawn again (camera, params, size or program changed)."""
        self._dirty = True
        self.state.samples = 0
        if moved:
            self._last_move = time.perf_counter()

    def _ui(self, _: Any = None) -> None:
        """Redraw a few frames for the panel (its hover and drag states) without re-rendering the scene."""
        self._ui_frames = 3

    def cursor(self) -> tuple[float, float]:
        """The mouse position in window coordinates."""
        return glfw.get_cursor_pos(self.window)

    def _on_cursor(self, _w: Any, x: float, y: float) -> None:
        if self.panel is not None and self.panel.visible:
            self._ui()
            if self.panel.on_cursor(x, y) and self._drag is None:
                return
        if self._drag is None:
            return
        button, x0, y0 = self._drag
        dx, dy = x - x0, y - y0
        self._drag = (button, x, y)
        if button == glfw.MOUSE_BUTTON_LEFT:
            self.camera.orbit(-0.4 * dx, 0.4 * dy)
        else:
            h = glfw.get_window_size(self.window)[1] or 1
            self.camera.pan(dx / h, dy / h)
        self._mark(moved=True)

    def _on_button(self, _w: Any, button: int, action: int, _mods: int) -> None:
        if self.panel is not None and self.panel.visible:
            self._ui()
            if self.panel.on_button(button, action == glfw.PRESS) and action == glfw.PRESS:
                return
        if action == glfw.PRESS:
            x, y = glfw.get_cursor_pos(self.window)
            self._drag = (button, x, y)
        elif action == glfw.RELEASE:
            self._drag = None

    def _on_scroll(self, _w: Any, _dx: float, dy: float) -> None:
        if self.panel is not None and self.panel.visible:
            self._ui()
            if self.panel.on_scroll(_dx, dy):
                return
        framing = OrbitCamera.framing(*self.scene.bounds, fov=self.camera.fov).distance
        lo, hi = ZOOM_RANGE[0] * framing, ZOOM_RANGE[1] * framing
        target = min(max(self.camera.distance * 0.88 ** dy, lo), hi)
        self.camera.zoom(target / self.camera.distance)
        self._mark(moved=True)

    @property
    def wanted_settings(self) -> dict[str, Any]:
        """The settings of the newest request (those being compiled, else those shown)."""
        return self._pending[1] if self._pending else self.state.settings

    def _cycle(self, key: str, values: tuple) -> None:
        cur = self.wanted_settings.get(key)
        self._apply({key: values[(values.index(cur) + 1) % len(values)] if cur in values else values[0]})

    def _on_key(self, _w: Any, key: int, _scan: int, action: int, _mods: int) -> None:
        if self.panel is not None and self.panel.visible:
            self._ui()
            if self.panel.on_key(key, _scan, action, _mods):
                return  # typing into the panel
        if action != glfw.PRESS:
            return
        if self.show_hint:
            self.show_hint = False
            self._repaint = True
        s = self.wanted_settings
        if key in (glfw.KEY_Q, glfw.KEY_ESCAPE):
            glfw.set_window_should_close(self.window, True)
        elif key == glfw.KEY_A:
            self._apply({"aa": s.get("aa", 1) % 4 + 1})
        elif key == glfw.KEY_S:
            self._cycle("shadows", SHADOW_CYCLE)
        elif key == glfw.KEY_O:
            self._apply({"ao": not s.get("ao", False)})
        elif key == glfw.KEY_M:
            methods = METHOD_CYCLE if self.scene.exactness != IMPLICIT else tuple(
                m for m in METHOD_CYCLE if m not in DISTANCE_METHODS)
            self._cycle("method", methods)
        elif key == glfw.KEY_G:
            self._apply({"ground": not s.get("ground", False)})
        elif key == glfw.KEY_D:
            self._cycle("debug", DEBUG_CYCLE)
        elif key == glfw.KEY_F:
            framed = OrbitCamera.framing(*self.scene.bounds, yaw=self.camera.yaw, pitch=self.camera.pitch,
                                         fov=self.camera.fov, aspect=self._aspect(),
                                         projection=self.camera.projection)
            self.camera = framed
            self._mark(moved=True)
        elif key == glfw.KEY_R:
            self.camera = self._orbit_of(self.home, self.scene, self._aspect())
            self._mark(moved=True)
        elif key == glfw.KEY_P:
            self.screenshot()
        elif key == glfw.KEY_N:
            if self.panel is None:
                self._set_error(self._panel_missing)
            else:
                self.panel.visible = not self.panel.visible
                self._mark()  # the view's size changes
        elif key in (glfw.KEY_H, glfw.KEY_F1):
            self.show_help = not self.show_help
            self._repaint = True

    def live_params(self) -> list[Any]:
        """The live parameters of the program on screen (its uniforms uP0, uP1, ...)."""
        return list(self._shown[3].params) if self._shown is not None else []

    def param_changed(self) -> None:
        """A live value changed: redraw with the same program (its uniform is set every frame)."""
        self.state.param_edits += 1
        self._mark()

    def select_node(self, node: Node | None) -> None:
        """Tint where ``node``'s subtree is the nearest surface (the "select" debug view); None ends it."""
        scene = self._pending[0] if self._pending else self.scene
        if node is not None:
            if self.wanted_settings.get("debug") != "select":
                self._debug_before = self.wanted_settings.get("debug")
            self._highlight = (scene, node)
            self._apply({"debug": "select"})
        else:
            self._highlight = None
            self._apply({"debug": self._debug_before})

    def apply_settings(self, change: dict[str, Any]) -> None:
        """Change render settings (compiled in the background)."""
        self._apply(change)

    def _apply(self, change: dict[str, Any]) -> None:
        """Change settings; the window keeps drawing the last program until the new one is compiled."""
        scene = self._pending[0] if self._pending else self.scene
        new = {**self.wanted_settings, **change}
        try:
            Settings.build(**new)
        except Exception as exc:  # noqa: BLE001 - shown in the window; the old settings stay
            self._set_error(describe_error(exc, "settings"))
            return
        self._request(scene, new, "settings")

    # -- drawing ----------------------------------------------------------------------
    def _request(self, scene: Node, settings: dict[str, Any], why: str,
                 file_settings: dict[str, Any] | None = None) -> None:
        """Compile (in the idle render thread) the program for ``scene`` and ``settings``; it replaces the
        shown one when it is linked and drawn once there.

        ``file_settings`` are the scene file's own settings when ``why`` is "reload"; a request made
        while a reload is still compiling stays a reload (it carries that reload's scene)."""
        if self._pending is not None and self._pending[2] == "reload" and why != "reload":
            why, file_settings = "reload", self._pending[4]
        origin = shader_origin(scene, self.camera.eye)
        st = Settings.build(**{**settings, "outputs": ("color", "steps")})  # steps: the panel's readout
        hl = None
        if st.debug == "select":  # the scene tree's selection (else the whole scene) is tinted
            hl = self._highlight[1] if self._highlight and self._highlight[0] is scene else scene
        projection = self.camera.projection
        self._token += 1
        meta = (scene, dict(settings), why, origin, file_settings)
        self._pending = meta
        job = Job(self._token, lambda: _codegen(scene, st, origin, projection, hl), scene, origin, meta)
        with self.exchange.cond:
            self.exchange.job = job  # a queued older request is dropped: the newest wins
            self.exchange.cond.notify_all()
        self.state.compiling = True
        self._repaint = True

    def _poll(self) -> None:
        """Take what the render threads finished: compiles, render errors, screenshots."""
        ex = self.exchange
        with ex.cond:
            results, ex.results = ex.results, []
            errors, ex.errors = ex.errors, []
            shots, ex.shots = ex.shots, []
        for res in results:
            self._accept(res)
        self.state.compiling = self._pending is not None
        for version, text in errors:
            self._render_failed(version, text)
        for paths, img in shots:
            self._save_shot(paths, img)

    def _accept(self, res: Result) -> None:
        if res.compiled:
            self.state.compiles += 1
            self.state.compile_log.append({"s": res.seconds, **res.timings})
            del self.state.compile_log[:-50]
        if res.token != self._token:
            return  # a newer request is on its way
        self._pending = None
        scene, settings, why, origin, file_settings = res.meta
        self._repaint = True
        if res.error or res.source is None:
            self._set_error(res.error)
            return
        self._shown = (scene, res.lane, res.source.text, res.source, origin)
        if why == "reload":
            self.state.reloads += 1
            self._file_settings = dict(file_settings or {})
        self.scene, self.state.settings = scene, settings
        if self._error_token < res.token:  # an error raised after this request (a failed reload) stays shown
            self._set_error("")
        self._mark()

    def _render_failed(self, version: int, text: str) -> None:
        """A frame failed in the render thread: show why and go back to the last program, scene and settings that drew."""
        self._set_error(text)
        good = self._good
        if version == self._version and good is not None and (good[0] is not self._shown or good[1] is not self.scene
                                                              or good[2] != self.state.settings):
            self._shown, self.scene, self.state.settings = good[0], good[1], dict(good[2])
            self._mark()

    def _moving(self) -> bool:
        return self._drag is not None or time.perf_counter() - self._last_move < MOVE_HOLD_S

    def _push_spec(self) -> None:
        """Hand the render thread what to draw now (a new version restarts its accumulation)."""
        self._dirty = False
        self._spec_moving = moving = self._moving()
        self.state.moving = moving
        view = self.view_rect()
        self.state.view = view
        if self._shown is None:
            return
        scene, lane, key, source, origin = self._shown
        if source.origin_offsets is not None:  # the origin is a uniform: it follows the camera and the
            origin = shader_origin(scene, self.camera.eye)  # parameters with no recompile (else it is fixed)
        self._version += 1
        spec = FrameSpec(self._version, lane, key, source, scene, origin, copy.deepcopy(self.camera), view[2:],
                         moving, self.max_samples, self.target_ms, self.adaptive)
        keep = {key} | ({self._good[0][2]} if self._good and self._good[0] else set())
        with self.exchange.cond:
            self.exchange.spec = spec
            self.exchange.keep = keep
            self.exchange.cond.notify_all()

    def _take_frame(self) -> Frame | None:
        """The newest frame a render thread published, if it is new; it becomes the one on screen."""
        ex = self.exchange
        with ex.cond:
            frame = ex.latest
            if frame is None or frame.serial == self._serial:
                return None
            self._serial = frame.serial
            ex.showing = frame.buffer
        st = self.state
        self._frame = frame
        if frame.spec.version == self._version:
            st.samples, st.moving, st.scale = frame.samples, frame.spec.moving, frame.scale
        if self._shown is not None and (frame.spec.lane, frame.spec.key) == self._shown[1:3]:
            self._good = (self._shown, self.scene, dict(self.state.settings))
        if frame.steps is not None:
            st.mean_steps = frame.steps
        st.frames += 1
        st.last_frame_ms = frame.ms
        st.frame_log.append((frame.spec.moving, frame.ms, frame.scale))
        del st.frame_log[:-400]
        self._title(frame.ms)
        return frame

    def _present(self) -> None:
        """Show the image on screen right of the panel, the overlay and the panel."""
        self.ctx.screen.use()
        self.ctx.viewport = (0, 0, *self.fb_size)
        frame = self._frame
        if frame is not None:
            self.gl.bind_texture(0, frame.buffer.glo)
        self._overlay().use(1)
        self.present["uImage"].value = 0
        self.present["uOverlay"].value = 1
        self.present["uWindow"].value = tuple(float(x) for x in self.fb_size)
        self.present["uView"].value = tuple(float(x) for x in self.view_rect())
        self.present["uHasImage"].value = 1.0 if frame is not None else 0.0
        self.present_vao.render(moderngl.TRIANGLES, vertices=3)
        if self.panel is not None:
            self.panel.draw()
            self.state.panel = {"visible": self.panel.visible, "rects": self.panel.rects, "message": self.panel.message,
                                "selected": self.panel.selected.label() if self.panel.selected else None,
                                "readout": self.panel.readout, "controls": self.panel.controls,
                                "params": {(q.name or f"p{i}"): np.asarray(q.value).tolist()
                                           for i, q in enumerate(self.live_params())}}
        glfw.swap_buffers(self.window)
        self.ctx.finish()  # the display texture was read: a render thread may draw into it again
        self._repaint = False
        self.state.present_log.append((time.time(), frame.spec.camera.yaw if frame is not None else None,
                                       self.state.compiling))
        del self.state.present_log[:-PRESENT_LOG]

    def _overlay(self) -> moderngl.Texture:
        text = "\n".join(x for x in ((KEYS_HELP if self.show_help else "H: help" if self.show_hint else ""),
                                     ("compiling..." if self.state.compiling else ""),
                                     (f"error: {self.state.error}" if self.state.error else "")) if x)
        x0 = self.view_rect()[0] + 10
        key = (text, x0, self.fb_size)
        if self._overlay_tex is None or key != self._overlay_key:
            img = Image.new("RGBA", self.fb_size, (0, 0, 0, 0))
            if text:
                draw = ImageDraw.Draw(img)
                x0 = x0 if x0 + 200 < self.fb_size[0] else 10  # a narrow view: over the panel rather than clipped
                font, shown, fits = layout_text(draw, text, self.fb_size[0] - x0 - 10, self.fb_size[1] - 20,
                                          shorter=(KEYS_HELP, KEYS_COMPACT))
                box = draw.multiline_textbbox((x0, 10), shown, font=font)
                draw.rectangle((box[0] - 6, box[1] - 6, box[2] + 6, box[3] + 6), fill=(0, 0, 0, 170))
                draw.multiline_text((x0, 10), shown, font=font,
                                    fill=(255, 120, 110, 255) if self.state.error and not self.show_help
                                    else (235, 235, 235, 255))
                self.state.overlay_font, self.state.overlay_fits = font.size, fits
            self.state.overlay_size = self.fb_size
            if self._overlay_tex is not None:
                self._overlay_tex.release()
            self._overlay_tex = self.ctx.texture(self.fb_size, 4, img.tobytes(), dtype="f1")
            self._overlay_key = key
            self.state.overlay = text
        return self._overlay_tex

    def _title(self, ms: float) -> None:
        s, st = self.state.settings, self.state
        shadows = s.get("shadows") or "off"
        w, h = self.state.view[2:]
        res = (f"{int(w * st.scale)}x{int(h * st.scale)} ({st.scale:.0%})" if st.moving
               else f"{w}x{h} {st.samples}/{self.max_samples} samples")
        name = self.path.name if self.path else self.scene.kind
        err = " | ERROR (see overlay)" if st.error else ""
        glfw.set_window_title(self.window, f"sdfgl: {name} | {ms:.1f} ms ({1000 / max(ms, 1e-3):.0f} fps) | {res} | "
                                           f"{s.get('method', 'enhanced')} aa{s.get('aa', 1)} shadows {shadows} "
                                           f"ao {'on' if s.get('ao') else 'off'}{' debug ' + s['debug'] if s.get('debug') else ''}{err}")

    # -- actions ----------------------------------------------------------------------
    def screenshot(self) -> Path:
        """Save the view as PNG once its image is finished (all samples accumulated), at the view's size,
        with what the window shows (the tree's selection tint included) and no overlay or panel."""
        try:
            self.screenshot_dir.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise SdfglError(f"cannot write screenshots to '{self.screenshot_dir}': {exc}") from exc
        self._shots += 1
        path = self.screenshot_dir / f"sdfgl-{time.strftime('%Y%m%d-%H%M%S')}-{self._shots - 1:03d}.png"
        with self.exchange.cond:
            self.exchange.shot_paths.append(str(path))
            self.exchange.cond.notify_all()
        return path

    def _save_shot(self, paths: list[str], img: np.ndarray) -> None:
        for path in paths:
            try:
                Image.fromarray(img).save(path)
            except OSError as exc:
                self._set_error(f"cannot write screenshot '{path}': {exc}")
                continue
            self.state.screenshots.append(path)
            print(f"sdfgl: saved {path}")

    def _set_error(self, text: str) -> None:
        if text and text != self.state.error:
            print(f"sdfgl: {text}", flush=True)
        self.state.error = text
        self._error_token = self._token  # the newest request when the error came
        self._repaint = True

    def _check_reload(self) -> None:
        if self.path is None:
            return
        try:
            mtime = self.path.stat().st_mtime
        except OSError:
            return
        if mtime == self._mtime:
            return
        self._mtime = mtime
        try:
            sf = load_scene_file(self.path)
            settings = self._reloaded_settings(sf.scene, sf.settings)
            if sf.scene.exactness == IMPLICIT and settings.get("method", "enhanced") in DISTANCE_METHODS:
                settings.update(method="newton", ao=False)
            Settings.build(**settings)
        except Exception as exc:  # noqa: BLE001 - a scene file may raise anything: show it, keep the window
            self._set_error(describe_error(exc, f"reload of '{self.path}'"))
            return
        self._request(sf.scene, settings, "reload", file_settings=sf.settings)  # shown when compiled: a GLSL error keeps the old scene

    def _reloaded_settings(self, scene: Node, file_settings: dict[str, Any]) -> dict[str, Any]:
        """Settings after a reload: what the file changed applies, key toggles of the rest stay,
        and what the caller gave explicitly wins."""
        new = dict(self.wanted_settings)
        base = self._base(scene)
        for k in set(self._file_settings) - set(file_settings):  # removed from the file: back to the default
            if k in base:
                new[k] = base[k]
            else:
                new.pop(k, None)
        new.update({k: v for k, v in file_settings.items() if k not in self._file_settings
                    or self._file_settings[k] != v})
        new.update(self._explicit)
        return new

    def _write_state(self) -> None:
        self._state_at = time.perf_counter()
        if self.state_file is None:
            return
        c = self.camera
        data = {"yaw": c.yaw, "pitch": c.pitch, "distance": c.distance, "target": c.target.tolist(),
                "scene": self.scene.label(), "size": list(self.fb_size), **{
                    k: v for k, v in self.state.__dict__.items()}}
        tmp = self.state_file.with_suffix(".tmp")
        tmp.write_text(json.dumps(data, default=str))
        os.replace(tmp, self.state_file)

    def run(self) -> None:
        """The event loop; returns when the window is closed."""
        last_poll = 0.0
        try:
            while not glfw.window_should_close(self.window):
                self._poll()
                if self._dirty or self._moving() != self._spec_moving:
                    self._push_spec()
                if self._take_frame() is not None or self._repaint:
                    self._present()
                elif self._ui_frames > 0:
                    self._ui_frames -= 1
                    self._present()
                if time.perf_counter() - self._state_at > STATE_EVERY_S:
                    self._write_state()
                if self._ui_frames > 0 or self._dirty:
                    glfw.poll_events()
                else:  # idle: no busy loop; the render threads wake it (frames, compiles), and it checks the file
                    wait = 0.2
                    if self._spec_moving and self._drag is None:
                        wait = max(0.0, MOVE_HOLD_S - (time.perf_counter() - self._last_move)) + 0.001
                    glfw.wait_events_timeout(min(wait, 0.2))
                now = time.perf_counter()
                if now - last_poll > 0.2:
                    last_poll = now
                    self._check_reload()
        finally:
            self.close()

    def close(self) -> None:
        """Stop the render threads and release the window."""
        if getattr(self, "window", None) is None:
            return
        ex = getattr(self, "exchange", None)
        if ex is not None:
            with ex.cond:
                ex.closing = True
                ex.cond.notify_all()
            for lane in self.lanes:
                lane.join(timeout=120)
            for lane in self.lanes:
                lane.destroy_window()
        if getattr(self, "panel", None) is not None:
            self.panel.close()
        glfw.destroy_window(self.window)
        self.window = None
        glfw.terminate()


def show(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (960, 540), **settings: Any) -> None:
    """Open a window on ``scene`` (see KEYS_HELP for the controls); returns when it is closed."""
    Viewer(scene, camera, size=size, **settings).run()

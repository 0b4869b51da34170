"""The interactive window: mouse orbit, live toggles, hot reload, adaptive resolution.

While the camera moves, frames are drawn at a reduced resolution chosen so a frame
stays under the target time; when it stops, full-resolution frames with sub-pixel
jitter are accumulated into a clean anti-aliased image, and then nothing is redrawn
until something changes.
"""
from __future__ import annotations

import json
import math
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import glfw
import moderngl
import numpy as np
from PIL import Image, ImageDraw, ImageFont

from .. import shaderlib
from ..camera import Camera, OrbitCamera
from ..codegen import generate
from ..errors import ContextError, SdfglError
from ..nodes.base import IMPLICIT, Node
from ..render import Renderer, camera_uniforms, scene_uniforms, shader_origin
from ..scenefile import load_scene_file
from ..settings import DISTANCE_METHODS, Settings
from . import panel as panel_mod
from .compile_worker import CompileWorker, Job, RawProgram, Result

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

METHOD_CYCLE = ("sphere", "relaxed", "enhanced", "newton", "forward_newton")
DEBUG_CYCLE = (None, "steps", "normal", "depth")
SHADOW_CYCLE = (False, "hard", "soft")
MOVE_HOLD_S = 0.15  # a camera change keeps the low-resolution mode this long
ZOOM_RANGE = (1e-4, 100.0)  # wheel zoom keeps the distance within these multiples of the framing distance


def describe_error(exc: BaseException, where: str) -> str:
    """One message for the overlay, whatever the exception (ours name their node or file)."""
    if isinstance(exc, SdfglError):
        return str(exc)
    if isinstance(exc, RecursionError):
        return f"{where}: the scene is nested too deeply for Python's recursion limit ({exc})"
    text = f"{where}: {type(exc).__name__}: {exc}"
    return text if len(text) < 800 else text[:800] + " ..."


def _fitting_font(draw: ImageDraw.ImageDraw, text: str, width: int, height: int) -> Any:
    """The largest font (8..22 px) in which ``text`` fits width x height, so help stays legible at any size."""
    font = None
    for size in range(22, 7, -1):
        font = ImageFont.load_default(size=size)
        box = draw.multiline_textbbox((0, 0), text, font=font)
        if box[2] - box[0] <= width and box[3] - box[1] <= height:
            return font
    return font


def _codegen(scene: Node, settings: Settings, origin: np.ndarray, projection: str, highlight: Node | None) -> Any:
    """The window's shader source (run in the compile worker); any failure becomes one overlay message."""
    try:
        return generate(scene, settings, origin, projection=projection, highlight=highlight)
    except SdfglError:
        raise
    except Exception as exc:  # noqa: BLE001 - a user's scene may raise anything while generating code
        raise SdfglError(describe_error(exc, "compile")) from exc


def _r2(n: int) -> tuple[float, float]:
    """The n-th point of the R2 low-discrepancy sequence, centred on 0 (sub-pixel jitter)."""
    g = 1.32471795724474602596
    return ((0.5 + n / g) % 1.0) - 0.5, ((0.5 + n / (g * g)) % 1.0) - 0.5


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
    panel: dict[str, Any] = field(default_factory=dict)
    compile_log: list[dict[str, float]] = field(default_factory=list)  # worker timings of each new program
    present_log: list[tuple[float, float, bool]] = field(default_factory=list)  # (wall time, yaw, compiling)


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
        self._image: tuple[moderngl.Texture | None, float] = (None, 1.0)
        self._last_move = -1.0
        self._drag: tuple[int, float, float] | None = None
        self._dirty = True
        self._overlay_text: str | None = None
        self._overlay_x = 10
        self._shown: tuple[Node, RawProgram, Any, np.ndarray] | None = None  # scene, program, source, origin
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
        self.renderer = Renderer(self.ctx)
        self.present = self.ctx.program(vertex_shader=shaderlib.read("fullscreen.vert"),
                                        fragment_shader=shaderlib.read("present.frag"))
        self.present_vao = self.ctx.vertex_array(self.present, [])
        self.compiler = CompileWorker(self.window, self.ctx)
        self._targets: dict[str, Any] = {}
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

    def _resize_targets(self) -> None:
        fw, fh = glfw.get_framebuffer_size(self.window)
        fw, fh = max(fw, 1), max(fh, 1)
        for obj in self._targets.values():
            obj.release()
        accum = self.ctx.texture((fw, fh), 4, dtype="f4")
        self._targets = {"accum": accum, "accum_fbo": self.ctx.framebuffer(color_attachments=[accum])}
        self.fb_size = (fw, fh)
        self._low: tuple[moderngl.Texture, moderngl.Framebuffer, tuple[int, int]] | None = None
        self._overlay_text = None
        self._mark()

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
            self._overlay_text = None
            self._dirty = True
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
                                         fov=self.camera.fov, aspect=self.size[0] / self.size[1],
                                         projection=self.camera.projection)
            self.camera = framed
            self._mark(moved=True)
        elif key == glfw.KEY_R:
            self.camera = self._orbit_of(self.home, self.scene, self.size[0] / self.size[1])
            self._mark(moved=True)
        elif key == glfw.KEY_P:
            self.screenshot()
        elif key == glfw.KEY_N:
            if self.panel is None:
                self._set_error(self._panel_missing)
            else:
                self.panel.visible = not self.panel.visible
                self._dirty = True
        elif key in (glfw.KEY_H, glfw.KEY_F1):
            self.show_help = not self.show_help
            self._overlay_text = None
            self._dirty = True

    def live_params(self) -> list[Any]:
        """The live parameters of the program on screen (its uniforms uP0, uP1, ...)."""
        return list(self._shown[2].params) if self._shown is not None else []

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
        """Compile (in the worker) the program for ``scene`` and ``settings``; it replaces the shown one when ready.

        ``file_settings`` are the scene file's own settings when ``why`` is "reload"; a request made
        while a reload is still compiling stays a reload (it carries that reload's scene)."""
        if self._pending is not None and self._pending[2] == "reload" and why != "reload":
            why, file_settings = "reload", self._pending[4]
        origin = shader_origin(scene, self.camera.eye)
        st = Settings.build(**settings)
        hl = None
        if st.debug == "select":  # the scene tree's selection (else the whole scene) is tinted
            hl = self._highlight[1] if self._highlight and self._highlight[0] is scene else scene
        projection = self.camera.projection
        self._token += 1
        meta = (scene, dict(settings), why, origin, file_settings)
        self._pending = meta
        self.compiler.submit(Job(self._token, lambda: _codegen(scene, st, origin, projection, hl), meta))
        self.state.compiling = True
        self._overlay_text = None
        self._dirty = True

    def _poll_compiles(self) -> None:
        """Take finished compiles: the newest good one is shown; an error keeps the last good program."""
        for res in self.compiler.poll():
            self._accept(res)
        self.state.compiling = self._pending is not None

    def _accept(self, res: Result) -> None:
        if res.compiled:
            self.state.compiles += 1
            self.state.compile_log.append({"s": res.seconds, **res.timings})
            del self.state.compile_log[:-50]
        if res.token != self._token:
            return  # a newer request is on its way
        self._pending = None
        scene, settings, why, origin, file_settings = res.meta
        self._overlay_text = None
        self._dirty = True
        if res.program is None:
            self._set_error(res.error)
            return
        self._shown = (scene, res.program, res.source, origin)
        good = self._good[0][1] if self._good and self._good[0] else None
        self.compiler.trim(res.program, good)  # both may be drawn next
        if why == "reload":
            self.state.reloads += 1
            self._file_settings = dict(file_settings or {})
        self.scene, self.state.settings = scene, settings
        if self._error_token < res.token:  # an error raised after this request (a failed reload) stays shown
            self._set_error("")
        self._mark()

    def _moving(self) -> bool:
        return self._drag is not None or time.perf_counter() - self._last_move < MOVE_HOLD_S

    def _low_target(self, scale: float) -> tuple[moderngl.Texture, moderngl.Framebuffer, tuple[int, int]]:
        size = (max(1, int(self.fb_size[0] * scale)), max(1, int(self.fb_size[1] * scale)))
        if self._low is None or self._low[2] != size:
            if self._low is not None:
                self._low[0].release()
                self._low[1].release()
            tex = self.ctx.texture(size, 4, dtype="f1")
            tex.filter = (moderngl.LINEAR, moderngl.LINEAR)
            self._low = (tex, self.ctx.framebuffer(color_attachments=[tex]), size)
        return self._low

    def _draw_scene(self, fbo: moderngl.Framebuffer, size: tuple[int, int], jitter: tuple[float, float],
                    blend: bool) -> float:
        assert self._shown is not None
        scene, prog, source, origin = self._shown
        if source.origin_offsets is not None:  # the origin is a uniform: it follows the camera and the
            origin = shader_origin(scene, self.camera.eye)  # parameters with no recompile (else it is fixed)
        camera_uniforms(prog, self.camera, size, origin, jitter)
        scene_uniforms(prog, source, scene, origin, self.renderer.data)
        fbo.use()
        self.ctx.viewport = (0, 0, *size)
        if blend:
            self.ctx.enable(moderngl.BLEND)
            self.ctx.blend_func = moderngl.ONE, moderngl.ONE
        t0 = time.perf_counter()
        prog.render(self.compiler.vao)
        self.ctx.finish()
        ms = 1000 * (time.perf_counter() - t0)
        if blend:
            self.ctx.disable(moderngl.BLEND)
        return ms

    def frame(self) -> None:
        """Draw one frame: low resolution while moving, else one more accumulated sample."""
        moving = self._moving()
        st = self.state
        if self._shown is None:  # the first program is still compiling: show the status line only
            self.ctx.screen.use()
            self.ctx.clear(0.1, 0.1, 0.12)
            self._present(None, 1.0)
            st.frames += 1
            self._dirty = False
            return
        if moving:
            if self.adaptive and not st.moving and st.last_frame_ms > self.target_ms:
                # the first moving frame: start from what the last full-resolution frame cost
                st.scale = float(max(0.1, min(st.scale, math.sqrt(self.target_ms / st.last_frame_ms))))
            scale = st.scale if self.adaptive else 1.0
            tex, fbo, size = self._low_target(scale)
            ms = self._draw_scene(fbo, size, (0.0, 0.0), blend=False)
            if self.adaptive:  # area scales with scale^2; damp the correction
                want = scale * math.sqrt(self.target_ms / max(ms, 1e-3))
                st.scale = float(min(1.0, max(0.1, 0.5 * scale + 0.5 * want)))
            image, weight = tex, 1.0
            st.samples = 0
        else:
            if st.samples == 0:
                self._targets["accum_fbo"].clear(0.0, 0.0, 0.0, 0.0)
            ms = self._draw_scene(self._targets["accum_fbo"], self.fb_size, _r2(st.samples), blend=True)
            st.samples += 1
            image, weight = self._targets["accum"], 1.0 / st.samples
        self._present(image, weight)
        st.frames += 1
        st.moving = moving
        st.last_frame_ms = ms
        st.frame_log.append((moving, ms, st.scale if moving else 1.0))
        del st.frame_log[:-400]
        self._title(ms)
        self._dirty = moving or st.samples < self.max_samples

    def _present(self, image: moderngl.Texture | None, weight: float) -> None:
        self.ctx.screen.use()
        self.ctx.viewport = (0, 0, *self.fb_size)
        (image or self._targets["accum"]).use(0)
        self._overlay().use(1)
        self.present["uImage"].value = 0
        self.present["uOverlay"].value = 1
        self.present["uWeight"].value = weight
        self.present["uWindow"].value = tuple(float(x) for x in self.fb_size)
        self.present_vao.render(moderngl.TRIANGLES, vertices=3)
        self._image = (image, weight)
        if self.panel is not None:
            self.panel.draw()
            self.state.panel = {"visible": self.panel.visible, "rects": self.panel.rects, "message": self.panel.message,
                                "selected": self.panel.selected.label() if self.panel.selected else None,
                                "params": {(q.name or f"p{i}"): np.asarray(q.value).tolist()
                                           for i, q in enumerate(self.live_params())}}
        glfw.swap_buffers(self.window)
        self.state.present_log.append((time.time(), self.camera.yaw, self.state.compiling))
        del self.state.present_log[:-400]

    def _overlay(self) -> moderngl.Texture:
        text = "\n".join(x for x in ((KEYS_HELP if self.show_help else "H: help" if self.show_hint else ""),
                                     ("compiling..." if self.state.compiling else ""),
                                     (f"error: {self.state.error}" if self.state.error else "")) if x)
        x0 = 10 + (panel_mod.WIDTH if self.panel is not None and self.panel.visible else 0)
        if text != self._overlay_text or x0 != self._overlay_x:
            img = Image.new("RGBA", self.fb_size, (0, 0, 0, 0))
            self._overlay_x = x0
            if text:
                draw = ImageDraw.Draw(img)
                x0 = x0 if x0 + 120 < self.fb_size[0] else 10
                font = _fitting_font(draw, text, self.fb_size[0] - x0 - 10, self.fb_size[1] - 20)
                box = draw.multiline_textbbox((x0, 10), text, font=font)
                draw.rectangle((box[0] - 6, box[1] - 6, box[2] + 6, box[3] + 6), fill=(0, 0, 0, 170))
                draw.multiline_text((x0, 10), text, font=font,
                                    fill=(255, 120, 110, 255) if self.state.error and not self.show_help
                                    else (235, 235, 235, 255))
            if "overlay" in self._targets:
                self._targets["overlay"].release()
            self._targets["overlay"] = self.ctx.texture(self.fb_size, 4, img.tobytes(), dtype="f1")
            self._overlay_text = text
            self.state.overlay = text
        return self._targets["overlay"]

    def _title(self, ms: float) -> None:
        s, st = self.state.settings, self.state
        shadows = s.get("shadows") or "off"
        res = (f"{int(self.fb_size[0] * st.scale)}x{int(self.fb_size[1] * st.scale)} ({st.scale:.0%})" if st.moving
               else f"{self.fb_size[0]}x{self.fb_size[1]} {st.samples}/{self.max_samples} samples")
        name = self.path.name if self.path else self.scene.kind
        err = " | ERROR (see overlay)" if st.error else ""
        glfw.set_window_title(self.window, f"sdfgl: {name} | {ms:.1f} ms ({1000 / max(ms, 1e-3):.0f} fps) | {res} | "
                                           f"{s.get('method', 'enhanced')} aa{s.get('aa', 1)} shadows {shadows} "
                                           f"ao {'on' if s.get('ao') else 'off'}{' debug ' + s['debug'] if s.get('debug') else ''}{err}")

    # -- actions ----------------------------------------------------------------------
    def screenshot(self) -> Path:
        """Render the current view at the window's framebuffer size and save it as PNG."""
        try:
            self.screenshot_dir.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise SdfglError(f"cannot write screenshots to '{self.screenshot_dir}': {exc}") from exc
        path = self.screenshot_dir / f"sdfgl-{time.strftime('%Y%m%d-%H%M%S')}-{len(self.state.screenshots):03d}.png"
        res = self.renderer.render(self.scene, self.camera, self.fb_size, **self.state.settings)
        res.save(path)
        self.ctx.screen.use()
        self.state.screenshots.append(str(path))
        self._dirty = True
        print(f"sdfgl: saved {path}")
        return path

    def _set_error(self, text: str) -> None:
        if text and text != self.state.error:
            print(f"sdfgl: {text}", flush=True)
        self.state.error = text
        self._error_token = self._token  # the newest request when the error came
        self._overlay_text = None
        self._dirty = True

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

    def _safe_frame(self) -> None:
        """Draw a frame; on any error show it and go back to the last program, scene and settings that drew."""
        try:
            self.frame()
            self._good = (self._shown, self.scene, dict(self.state.settings))
        except Exception as exc:  # noqa: BLE001 - the window never dies from a scene
            self._set_error(describe_error(exc, "render"))
            good = self._good
            if good is not None and (good[0] is not self._shown or good[1] is not self.scene
                                     or good[2] != self.state.settings):
                self._shown, self.scene, self.state.settings = good[0], good[1], dict(good[2])
                self._mark()
                return
            self._dirty = False  # nothing to go back to: show the error until something changes
            try:
                self._present(self._targets["accum"], 1.0 / max(1, self.state.samples))
            except Exception:  # noqa: BLE001 - the title and state file still carry the error
                pass

    def _write_state(self) -> None:
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
                self._poll_compiles()
                if self._dirty:
                    self._safe_frame()
                    self._write_state()
                    glfw.poll_events()
                elif self._ui_frames > 0:
                    self._ui_frames -= 1
                    self._present(*self._image)
                    self._write_state()
                    glfw.poll_events()
                else:
                    self._write_state()
                    glfw.wait_events_timeout(0.2)  # idle: no busy loop; wakes to check the file
                now = time.perf_counter()
                if now - last_poll > 0.2:
                    last_poll = now
                    self._check_reload()
        finally:
            self.close()

    def close(self) -> None:
        """Release GL objects and the window."""
        if getattr(self, "window", None) is not None:
            if getattr(self, "compiler", None) is not None:
                self.compiler.close()
            if getattr(self, "panel", None) is not None:
                self.panel.close()
            glfw.destroy_window(self.window)
            self.window = None
            glfw.terminate()


def show(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (960, 540), **settings: Any) -> None:
    """Open a window on ``scene`` (see KEYS_HELP for the controls); returns when it is closed."""
    Viewer(scene, camera, size=size, **settings).run()

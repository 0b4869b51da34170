"""The interactive window: mouse orbit, live toggles, hot reload, adaptive resolution.

While the camera moves, frames are drawn at a reduced resolution chosen so a frame
stays under the target time; when it stops, full-resolution frames with sub-pixel
jitter are accumulated into a clean anti-aliased image, and then nothing is redrawn
until something changes. The scene is drawn by render threads (:mod:`.render_thread`,
driven through :mod:`.progressive`); this thread answers input (:mod:`.input`), checks
the scene file (:mod:`.reload`), presents the newest image right of the side panel, draws
the panel and the text overlay, and writes the state file (:mod:`.state_file`).
"""
from __future__ import annotations

import time
from pathlib import Path
from typing import TYPE_CHECKING, Any, Sequence

import glfw
import moderngl
import numpy as np

from .. import shaderlib
from ..camera import Camera, OrbitCamera
from ..errors import ContextError, SdfglError
from ..gl.memory import limit_malloc_arenas
from ..nodes.base import Node
from ..raster import RasterMesh
from ..render import checked_meshes
from ..scenefile_process import DEFAULT_TIMEOUT_S
from ..settings import Settings
from . import panel as panel_mod
from . import rawgl
from .input import KEYS_COMPACT, KEYS_HELP, MOVE_HOLD_S, Input
from .live_input import LiveInput
from .overlay import overlay_image
from .progressive import Progressive
from .reload import SceneFileWatch, window_defaults
from .render_thread import describe_error
from .screenshots import Screenshots
from .state_file import StateFile, ViewState, window_title

if TYPE_CHECKING:  # pragma: no cover
    from ..live import LiveControl


class Viewer:
    """A glfw window showing a scene (or a scene file, reloaded when it changes).

    A scene file is loaded in a child process (:mod:`.reload`), stopped after ``load_timeout``
    seconds; the first load is waited for (a failure raises SceneFileError before any window opens),
    a reload is not: the last good scene stays on screen meanwhile and when it fails.

    ``live`` (a :class:`~sdfgl.live.LiveControl`) lets MIDI and OSC messages move the live
    parameters, with the bindings of the file ``bindings`` (names checked before the window opens).

    ``meshes`` (made by :func:`sdfgl.raster`) are drawn by rasterisation and composited with the
    scene by depth, by the same raster pass as ``sg.render(..., meshes=...)``.

    ``dirty`` says the render threads need a new frame spec (camera, parameters, size or
    program changed), ``repaint`` that the window needs presenting again (overlay, panel)."""

    def __init__(self, scene: Node | None = None, camera: Camera | None = None, *, path: str | Path | None = None,
                 size: tuple[int, int] = (960, 540), target_ms: float = 50.0, adaptive: bool = True,
                 max_samples: int = 16, state_file: str | Path | None = None,
                 screenshot_dir: str | Path = ".", panel: bool | None = None,
                 load_timeout: float = DEFAULT_TIMEOUT_S, live: "LiveControl | None" = None,
                 bindings: str | Path | None = None, meshes: Sequence[RasterMesh] = (), **settings: Any) -> None:
        self.meshes = checked_meshes(meshes)
        self.path = Path(path) if path else None
        self.watch: SceneFileWatch | None = None
        if self.path is not None:
            self.watch = SceneFileWatch(self.path, settings, load_timeout)  # the caller's settings: reloads keep them
            sf = self.watch.load()
            scene, camera = sf.scene, camera or sf.camera
            settings = {**sf.settings, **settings}
        if scene is None:
            raise SdfglError("Viewer needs a scene or a scene file")
        self.scene = scene
        self.state = ViewState(settings={**window_defaults(scene), **settings})
        Settings.build(**self.state.settings)  # validate before opening a window
        self.home = self._orbit_of(camera, scene, size[0] / size[1])
        self.camera = self._orbit_of(camera, scene, size[0] / size[1])
        self.size, self.target_ms, self.adaptive = size, target_ms, adaptive
        self.max_samples = max_samples
        self.state_file = StateFile(state_file)
        self.screenshot_dir = Path(screenshot_dir)  # screenshots, and the panel's saved scene
        self.shots = Screenshots(self.screenshot_dir)
        self.show_help = False
        self.show_hint = True  # "H: help" until the first key
        self._want_panel = panel
        self._ui_frames = 0  # frames to redraw for the panel alone (hover, drag) without re-rendering the scene
        self.dirty = True
        self.repaint = True
        self._overlay_key: tuple | None = None
        self.highlight: tuple[Node, Node] | None = None  # (scene, subtree) tinted by the "select" debug view
        self._debug_before: Any = None
        self.input = Input(self)
        self.live = LiveInput(self, live, bindings) if live is not None else None
        self._open_window()
        self.progressive.request(self.scene, self.state.settings, "open")

    # -- set-up ---------------------------------------------------------------------
    @staticmethod
    def _orbit_of(camera: Camera | None, scene: Node, aspect: float) -> OrbitCamera:
        return OrbitCamera.of(camera, *scene.bounds, aspect=aspect)

    def _open_window(self) -> None:
        limit_malloc_arenas()  # before the driver's threads start (see sdfgl.gl.memory)
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
        self.present = self.ctx.program(vertex_shader=shaderlib.read("mains/fullscreen.vert"),
                                        fragment_shader=shaderlib.read("mains/present.frag"))
        self.present_vao = self.ctx.vertex_array(self.present, [])
        self.gl = rawgl.GL()
        self.progressive = Progressive(self, self.window)
        self._overlay_tex: moderngl.Texture | None = None
        self.panel: panel_mod.Panel | None = None
        self._resize_targets()
        self._panel_missing = panel_mod.available()
        if not self._panel_missing:
            self.panel = panel_mod.Panel(self)
            if self._want_panel is not None:
                self.panel.visible = self._want_panel
        self.input.attach(self.window, self._guarded)
        glfw.set_framebuffer_size_callback(self.window, self._guarded(lambda *_: self._resize_targets(), "resize"))
        glfw.set_window_refresh_callback(self.window, lambda *_: self.mark())
        self._write_state()  # scripts see the window at once; the render threads may take a while to start
        self.progressive.wait_ready()
        if self.live is not None:
            try:
                self.live.start()
            except Exception:
                self.close()
                raise

    def _resize_targets(self) -> None:
        fw, fh = glfw.get_framebuffer_size(self.window)
        self.fb_size = (max(fw, 1), max(fh, 1))
        self.mark()

    def view_rect(self) -> tuple[int, int, int, int]:
        """The image's rectangle in framebuffer pixels (x, y, width, height): right of the panel when it shows."""
        fw, fh = self.fb_size
        x = 0
        if self.panel is not None and self.panel.visible:
            ww = glfw.get_window_size(self.window)[0] or fw
            x = min(fw - 1, round(panel_mod.WIDTH * fw / ww))
        return x, 0, fw - x, fh

    def aspect(self) -> float:
        """Width / height of the image's rectangle."""
        _, _, w, h = self.view_rect()
        return w / h

    # -- events -----------------------------------------------------------------------
    def _guarded(self, fn: Any, where: str) -> Any:
        """``fn`` as a glfw callback that shows any exception in the window instead of raising it."""
        def callback(*args: Any) -> None:
            try:
                fn(*args)
            except Exception as exc:  # noqa: BLE001 - the window never dies from input
                self.set_error(describe_error(exc, where))
        return callback

    def mark(self) -> None:
        """The image must be drawn again (camera, params, size or program changed)."""
        self.dirty = True
        self.state.samples = 0

    def redraw_ui(self, _: Any = None) -> None:
        """Redraw a few frames for the panel (its hover and drag states) without re-rendering the scene."""
        self._ui_frames = 3

    def cursor(self) -> tuple[float, float]:
        """The mouse position in window coordinates."""
        return glfw.get_cursor_pos(self.window)

    @property
    def wanted_settings(self) -> dict[str, Any]:
        """The settings of the newest request (those being compiled, else those shown)."""
        pending = self.progressive.pending
        return pending[1] if pending else self.state.settings

    # -- actions ----------------------------------------------------------------------
    def frame_scene(self) -> None:
        """Frame the whole scene from the current direction, for the view's aspect ratio."""
        self.camera = OrbitCamera.framing(*self.scene.bounds, yaw=self.camera.yaw, pitch=self.camera.pitch,
                                          fov=self.camera.fov, aspect=self.aspect(),
                                          projection=self.camera.projection)

    def reset_view(self) -> None:
        """Back to the camera the window opened with."""
        self.camera = self._orbit_of(self.home, self.scene, self.aspect())

    def toggle_panel(self) -> None:
        """Show or hide the side panel (or say why there is none)."""
        if self.panel is None:
            self.set_error(self._panel_missing)
        else:
            self.panel.visible = not self.panel.visible
            self.mark()  # the view's size changes

    def toggle_help(self) -> None:
        """Show or hide KEYS_HELP."""
        self.show_help = not self.show_help
        self.repaint = True

    def hide_hint(self) -> None:
        """Drop the "H: help" hint (after the first key)."""
        if self.show_hint:
            self.show_hint = False
            self.repaint = True

    def live_params(self) -> list[Any]:
        """The live parameters of the program on screen (its uniforms uP0, uP1, ...)."""
        return self.progressive.live_params()

    def param_changed(self) -> None:
        """A live value changed: redraw with the same program (its uniform is set every frame)."""
        self.state.param_edits += 1
        self.mark()

    def select_node(self, node: Node | None) -> None:
        """Tint where ``node``'s subtree is the nearest surface (the "select" debug view); None ends it."""
        pending = self.progressive.pending
        scene = pending[0] if pending else self.scene
        if node is not None:
            if self.wanted_settings.get("debug") != "select":
                self._debug_before = self.wanted_settings.get("debug")
            self.highlight = (scene, node)
            self.apply_settings({"debug": "select"})
        else:
            self.highlight = None
            self.apply_settings({"debug": self._debug_before})

    def apply_settings(self, change: dict[str, Any]) -> None:
        """Change render settings; the window keeps drawing the last program until the new one is compiled."""
        pending = self.progressive.pending
        scene = pending[0] if pending else self.scene
        new = {**self.wanted_settings, **change}
        try:
            Settings.build(**new)
        except Exception as exc:  # noqa: BLE001 - shown in the window; the old settings stay
            self.set_error(describe_error(exc, "settings"))
            return
        self.progressive.request(scene, new, "settings")

    # -- drawing ----------------------------------------------------------------------
    def _present(self) -> None:
        """Show the image on screen right of the panel, the overlay and the panel."""
        self.ctx.screen.use()
        self.ctx.viewport = (0, 0, *self.fb_size)
        frame = self.progressive.frame
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
        self.repaint = False
        self.state.log_present(frame.spec.camera.yaw if frame is not None else None)

    def _overlay(self) -> moderngl.Texture:
        text = "\n".join(x for x in ((KEYS_HELP if self.show_help else "H: help" if self.show_hint else ""),
                                     self._loading_text(),
                                     ("compiling..." if self.state.compiling else ""),
                                     (f"error: {self.state.error}" if self.state.error else "")) if x)
        x0 = self.view_rect()[0] + 10
        key = (text, x0, self.fb_size)
        if self._overlay_tex is None or key != self._overlay_key:
            img, font_size, fits = overlay_image(text, x0, self.fb_size, bool(self.state.error) and not self.show_help,
                                                 shorter=(KEYS_HELP, KEYS_COMPACT))
            if font_size is not None:
                self.state.overlay_font, self.state.overlay_fits = font_size, fits
            self.state.overlay_size = self.fb_size
            if self._overlay_tex is not None:
                self._overlay_tex.release()
            self._overlay_tex = self.ctx.texture(self.fb_size, 4, img.tobytes(), dtype="f1")
            self._overlay_key = key
            self.state.overlay = text
        return self._overlay_tex

    # -- actions ----------------------------------------------------------------------
    def screenshot(self) -> Path:
        """Save the view as PNG once its image is finished (all samples accumulated), at the view's size,
        with what the window shows (the tree's selection tint included) and no overlay or panel."""
        return self.shots.ask(self.progressive.exchange)

    def save_shot(self, paths: list[str], img: np.ndarray) -> None:
        """Write a finished image (a render thread made it) to each of ``paths``."""
        self.state.screenshots += self.shots.save(paths, img, self.set_error)

    def set_error(self, text: str) -> None:
        """Show ``text`` over the image (and print it once); "" clears it."""
        if text and text != self.state.error:
            print(f"sdfgl: {text}", flush=True)
        self.state.error = text
        self.progressive.error_token = self.progressive.token  # the newest request when the error came
        self.repaint = True

    def _loading_text(self) -> str:
        """The overlay's line for a reload in progress (its seconds once it takes a while)."""
        if self.state.loading is None or self.path is None:
            return ""
        took = f" {self.state.loading:.0f} s (limit {self.watch.loader.timeout:g} s)" \
            if self.watch is not None and self.state.loading >= 1 else ""
        return f"loading {self.path.name}...{took}"

    def _check_reload(self) -> None:
        """Start a reload when the file changed; take a finished one (never waits for it)."""
        if self.watch is None:
            return
        if self.watch.changed():
            self.watch.start_reload()
        try:
            got = self.watch.poll_reload(self.wanted_settings)
        except Exception as exc:  # noqa: BLE001 - a scene file may raise anything: show it, keep the window
            self.set_error(describe_error(exc, f"reload of '{self.path}'"))
            got = None
        loading = self.watch.loading
        if (loading is None) != (self.state.loading is None) or int(loading or 0) != int(self.state.loading or 0):
            self.repaint = True  # the overlay's line changes
        self.state.loading = loading
        if got is not None:  # shown when compiled: a GLSL error keeps the old scene
            scene, settings, file_settings = got
            self.progressive.request(scene, settings, "reload", file_settings=file_settings)

    def _write_state(self) -> None:
        self.state_file.write(self.state, self.camera, self.scene.label(), self.fb_size)

    def run(self) -> None:
        """The event loop; returns when the window is closed."""
        last_poll = 0.0
        pr = self.progressive
        try:
            while not glfw.window_should_close(self.window):
                pr.poll()
                if self.live is not None:
                    self.live.poll()
                moving = self.input.moving()
                if self.dirty or moving != pr.spec_moving:
                    pr.push_spec(moving)
                frame = pr.take_frame()
                if frame is not None:
                    name = self.path.name if self.path else self.scene.kind
                    glfw.set_window_title(self.window, window_title(name, frame.ms, self.state, self.max_samples))
                if frame is not None or self.repaint:
                    self._present()
                elif self._ui_frames > 0:
                    self._ui_frames -= 1
                    self._present()
                if self.state_file.due():
                    self._write_state()
                if self._ui_frames > 0 or self.dirty:
                    glfw.poll_events()
                else:  # idle: no busy loop; the render threads wake it (frames, compiles), and it checks the file
                    wait = 0.2
                    if pr.spec_moving and self.input.drag is None:
                        wait = max(0.0, MOVE_HOLD_S - (time.perf_counter() - self.input.last_move)) + 0.001
                    glfw.wait_events_timeout(min(wait, 0.2))
                now = time.perf_counter()
                if now - last_poll > 0.2:
                    last_poll = now
                    self._check_reload()
        finally:
            self.close()

    def close(self) -> None:
        """Stop the render threads and release the window."""
        if getattr(self, "watch", None) is not None:
            self.watch.close()
        if getattr(self, "live", None) is not None:
            self.live.close()
        if getattr(self, "window", None) is None:
            return
        if getattr(self, "progressive", None) is not None:
            self.progressive.close()
        if getattr(self, "panel", None) is not None:
            self.panel.close()
        glfw.destroy_window(self.window)
        self.window = None
        glfw.terminate()


def show(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (960, 540),
         meshes: Sequence[RasterMesh] = (), **settings: Any) -> None:
    """Open a window on ``scene`` (see KEYS_HELP for the controls); returns when it is closed.

    ``meshes`` (made by :func:`sdfgl.raster`) are drawn by rasterisation in the same view, as in
    ``sg.render(scene, meshes=...)``."""
    Viewer(scene, camera, size=size, meshes=meshes, **settings).run()

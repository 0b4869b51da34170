"""The window's side of the render threads: compiles in the background and progressive frames.

A compile request is handed to an idle render thread; the newest request wins, and the
program it makes replaces the one on screen only once it has drawn. A frame spec (camera,
size, program) is handed to the thread of the program on screen: a new spec restarts its
accumulation, and while nothing changes it adds jittered full-resolution samples up to
``max_samples`` (at reduced resolution while the camera moves). The window takes the
newest frame each thread publishes.
"""
from __future__ import annotations

import copy
from typing import TYPE_CHECKING, Any

import numpy as np

from ..compiler.generate import generate
from ..compiler.source import ShaderSource
from ..errors import SdfglError
from ..nodes.base import Node
from ..render import coarse_source, shader_origin
from ..settings import Settings
from .programs import Job, Result
from .render_thread import LANES, Exchange, Frame, FrameSpec, Lane, describe_error

if TYPE_CHECKING:  # pragma: no cover
    from .window import Viewer


def _codegen(scene: Node, settings: Settings, origin: np.ndarray, projection: str, highlight: Node | None,
             target: str = "render") -> Any:
    """The window's shader source for ``target`` (run in a render thread); any failure becomes one
    overlay message."""
    try:
        return generate(scene, settings, origin, target=target, projection=projection, highlight=highlight)
    except SdfglError:
        raise
    except Exception as exc:  # noqa: BLE001 - a user's scene may raise anything while generating code
        raise SdfglError(describe_error(exc, "compile")) from exc


class Progressive:
    """Compile requests and frame specs for ``viewer``'s render threads (made on ``window``)."""

    def __init__(self, viewer: "Viewer", window: Any) -> None:
        self.viewer = viewer
        self.exchange = Exchange()
        self.lanes: list[Lane] = [Lane(i, window, self.exchange) for i in range(LANES)]
        self.exchange.lanes = self.lanes
        self.token = 0         # of the newest compile request
        self.error_token = 0   # the newest request when the error on screen came
        self.version = 0       # of the newest spec
        self.spec_moving = False
        self.serial = 0        # of the newest frame taken
        self.frame: Frame | None = None  # on screen
        # scene, lane, program key (source text), source, origin
        self.shown: tuple[Node, int, str, ShaderSource, np.ndarray] | None = None
        self.good: tuple[Any, Node, dict[str, Any]] | None = None  # the last (shown, scene, settings) that drew
        # what the newest compile is for: scene, settings, why, origin, the file's settings (reloads)
        self.pending: tuple[Node, dict[str, Any], str, np.ndarray, dict[str, Any] | None] | None = None

    def wait_ready(self) -> None:
        """Wait until every render thread has started."""
        for lane in self.lanes:
            lane.wait_ready()

    def live_params(self) -> list[Any]:
        """The live parameters of the program on screen (its uniforms uP0, uP1, ...)."""
        return list(self.shown[3].params) if self.shown is not None else []

    # -- compiles -------------------------------------------------------------------------
    def request(self, scene: Node, settings: dict[str, Any], why: str,
                file_settings: dict[str, Any] | None = None) -> None:
        """Compile (in the idle render thread) the program for ``scene`` and ``settings``; it replaces the
        shown one when it is linked and drawn once there.

        ``file_settings`` are the scene file's own settings when ``why`` is "reload"; a request made
        while a reload is still compiling stays a reload (it carries that reload's scene)."""
        v = self.viewer
        if self.pending is not None and self.pending[2] == "reload" and why != "reload":
            why, file_settings = "reload", self.pending[4]
        origin = shader_origin(scene, v.camera.eye)
        st = Settings.build(**{**settings, "outputs": ("color", "steps")})  # steps: the panel's readout
        hl = None
        if st.debug == "select":  # the scene tree's selection (else the whole scene) is tinted
            hl = v.highlight[1] if v.highlight and v.highlight[0] is scene else scene
        projection = v.camera.projection
        self.token += 1
        meta = (scene, dict(settings), why, origin, file_settings)
        self.pending = meta
        if v.meshes:  # the march stops at the raster meshes' depth; their own program is built beside it
            job = Job(self.token, lambda: _codegen(scene, st, origin, projection, hl, "render_over_mesh"), scene,
                      origin, meta, lambda: _codegen(scene, st, origin, projection, None, "raster_mesh"))
        else:  # the image, and the coarse pass that proves where its rays may start
            job = Job(self.token, lambda: _codegen(scene, st, origin, projection, hl), scene, origin, meta,
                      coarse_build=lambda source: coarse_source(scene, source, st.resolved(scene.exactness), origin,
                                                                projection))
        with self.exchange.cond:
            self.exchange.job = job  # a queued older request is dropped: the newest wins
            self.exchange.cond.notify_all()
        v.state.compiling = True
        v.repaint = True

    def poll(self) -> None:
        """Take what the render threads finished: compiles, render errors, screenshots."""
        ex = self.exchange
        with ex.cond:
            results, ex.results = ex.results, []
            errors, ex.errors = ex.errors, []
            shots, ex.shots = ex.shots, []
        for res in results:
            self._accept(res)
        self.viewer.state.compiling = self.pending is not None
        for version, text in errors:
            self._render_failed(version, text)
        for paths, img in shots:
            self.viewer.save_shot(paths, img)

    def _accept(self, res: Result) -> None:
        v = self.viewer
        if res.compiled:
            v.state.compiles += 1
            v.state.compile_log.append({"s": res.seconds, **res.timings})
            del v.state.compile_log[:-50]
        if res.token != self.token:
            return  # a newer request is on its way
        self.pending = None
        scene, settings, why, origin, file_settings = res.meta
        v.repaint = True
        if res.error or res.source is None:
            v.set_error(res.error)
            return
        self.shown = (scene, res.lane, res.source.text, res.source, origin)
        if why == "reload":
            v.state.reloads += 1
            if v.watch is not None:
                v.watch.file_settings = dict(file_settings or {})
        v.scene, v.state.settings = scene, settings
        if self.error_token < res.token:  # an error raised after this request (a failed reload) stays shown
            v.set_error("")
        v.mark()

    def _render_failed(self, version: int, text: str) -> None:
        """A frame failed in the render thread: show why and go back to the last program, scene and settings that drew."""
        v = self.viewer
        v.set_error(text)
        good = self.good
        if version == self.version and good is not None and (good[0] is not self.shown or good[1] is not v.scene
                                                             or good[2] != v.state.settings):
            self.shown, v.scene, v.state.settings = good[0], good[1], dict(good[2])
            v.mark()

    # -- frames ---------------------------------------------------------------------------
    def push_spec(self, moving: bool) -> None:
        """Hand the render thread what to draw now (a new version restarts its accumulation)."""
        v = self.viewer
        v.dirty = False
        self.spec_moving = moving
        v.state.moving = moving
        view = v.view_rect()
        v.state.view = view
        if self.shown is None:
            return
        scene, lane, key, source, origin = self.shown
        if source.origin_offsets is not None:  # the origin is a uniform: it follows the camera and the
            origin = shader_origin(scene, v.camera.eye)  # parameters with no recompile (else it is fixed)
        self.version += 1
        spec = FrameSpec(self.version, lane, key, source, scene, origin, copy.deepcopy(v.camera), view[2:],
                         moving, v.max_samples, v.target_ms, v.adaptive, v.meshes)
        keep = {key} | ({self.good[0][2]} if self.good and self.good[0] else set())
        with self.exchange.cond:
            self.exchange.spec = spec
            self.exchange.keep = keep
            self.exchange.cond.notify_all()

    def take_frame(self) -> Frame | None:
        """The newest frame a render thread published, if it is new; it becomes the one on screen."""
        ex = self.exchange
        with ex.cond:
            frame = ex.latest
            if frame is None or frame.serial == self.serial:
                return None
            self.serial = frame.serial
            ex.showing = frame.buffer
        v = self.viewer
        st = v.state
        self.frame = frame
        if frame.spec.version == self.version:
            st.samples, st.moving, st.scale = frame.samples, frame.spec.moving, frame.scale
        if self.shown is not None and (frame.spec.lane, frame.spec.key) == self.shown[1:3]:
            self.good = (self.shown, v.scene, dict(v.state.settings))
        if frame.steps is not None:
            st.mean_steps = frame.steps
        st.frames += 1
        st.last_frame_ms = frame.ms
        st.frame_log.append((frame.spec.moving, frame.ms, frame.scale))
        del st.frame_log[:-400]
        return frame

    def close(self) -> None:
        """Stop the render threads (each finishes its frame) and release their windows."""
        ex = self.exchange
        with ex.cond:
            ex.closing = True
            ex.cond.notify_all()
        for lane in self.lanes:
            lane.join(timeout=120)
        for lane in self.lanes:
            lane.destroy_window()

"""The side panel: live parameters, render settings, timings and the scene tree (Dear ImGui).

Built on imgui-bundle (Dear ImGui 1.92, maintained, Linux wheels; its glfw backend
uses the same pyGLFW the window does). Needs the optional extra ``sdfgl[panel]``
(imgui-bundle and PyOpenGL, which its renderer draws with); without it the window works
and the panel key says what to install.

A slider writes ``param.value``: the next frame sets the uniform, nothing recompiles. With
live control on, each parameter has a "learn" button (the next MIDI control moved, or OSC
address sent, drives it) and the bindings can be saved.
A render setting goes through the window's asynchronous compile.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ParameterError, SdfglError
from ..nodes.base import Node
from ..params import Param
from ..settings import METHODS, SHADOWS

if TYPE_CHECKING:  # pragma: no cover
    from .window import Viewer

WIDTH = 300              # panel width in pixels
MIN_WINDOW_WIDTH = 800   # narrower windows open with the panel hidden
DEBUG_NAMES = ("off", "steps", "normal", "depth", "select")
INSTALL_HINT = "the panel needs the optional extra: pip install 'sdfgl[panel]' (imgui-bundle, PyOpenGL)"


def available() -> str:
    """'' when the GUI library imports, else the message saying what to install."""
    try:
        import OpenGL  # noqa: F401
        from imgui_bundle import imgui  # noqa: F401
    except ImportError:
        return INSTALL_HINT
    return ""


def colour_params(scene: Node) -> set[int]:
    """ids of the parameters that are a whole colour (``.color(param)``): they get colour pickers."""
    out: set[int] = set()
    stack = [scene]
    while stack:
        n = stack.pop()
        rgb = n.params.get("rgb") if n.kind == "color" else None
        if isinstance(rgb, Param):
            out.add(id(rgb))
        stack.extend(n.children)
    return out


def python_lines(params: list[Param]) -> str:
    """The parameters' current values as Python (``name = sg.param(value, ...)``)."""
    lines = []
    for i, p in enumerate(params):
        v = p.value
        val = repr(float(v)) if np.ndim(v) == 0 else repr(tuple(float(x) for x in v))
        name = p.name or f"p{i}"
        extra = f", name={p.name!r}" if p.name else ""
        rng = getattr(p, "range", None)
        extra += f", range={tuple(rng)!r}" if rng is not None else ""
        lines.append(f"{name.replace(' ', '_')} = sg.param({val}{extra})")
    return "\n".join(lines)


def slider_range(p: Param) -> tuple[float, float]:
    """The param's own range, else the browser view's default (around the value, where its nodes accept it)."""
    rng = getattr(p, "range", None)
    if rng is not None:
        return float(rng[0]), float(rng[1])
    from ..web.spec import slider_range as default_range
    return default_range(p)


def control(p: Param, colours: set[int]) -> tuple[str, float, float]:
    """The control a parameter gets: ("slider" | "colour" | "vector", low, high).

    A scalar gets a slider over its range (and a typed entry), a whole colour a colour picker
    (0..1), any other vector a 3-slider over its range."""
    if np.ndim(p.value) == 0:
        return ("slider", *slider_range(p))
    if id(p) in colours:
        return "colour", 0.0, 1.0
    return ("vector", *slider_range(p))


class Panel:
    """Dear ImGui drawn over the window's left edge; input goes to it first when it wants it."""

    def __init__(self, viewer: "Viewer") -> None:
        from imgui_bundle import imgui
        from imgui_bundle.python_backends.glfw_backend import GlfwRenderer
        self.imgui = imgui
        self.viewer = viewer
        imgui.create_context()
        imgui.get_io().set_ini_filename("")  # no imgui.ini written next to the user's files
        self.impl = GlfwRenderer(viewer.window, attach_callbacks=False)
        self.visible = viewer.fb_size[0] >= MIN_WINDOW_WIDTH
        self.message = ""
        self.selected: Node | None = None
        self._ranges: dict[int, tuple[str, float, float]] = {}  # the control of each param
        self._colours: tuple[int, set[int]] = (0, set())
        self.wants_mouse = False
        self.wants_keyboard = False
        self.rects: dict[str, tuple[float, float, float, float]] = {}  # widget -> (x0, y0, x1, y1), for scripts
        self.readout: dict[str, float] = {}  # the live figures the panel shows, for scripts
        self.controls: dict[str, str] = {}   # param label -> its control ("slider", "colour", "vector")

    # -- input: called by the window's callbacks, before its own handling -------------
    def on_cursor(self, x: float, y: float) -> bool:
        self.impl.io.add_mouse_pos_event(x, y)
        return self.visible and self.wants_mouse

    def on_button(self, button: int, press: bool) -> bool:
        self.impl.io.add_mouse_button_event(button, press)
        return self.visible and (self.wants_mouse or self.over(*self.viewer.cursor()))

    def on_scroll(self, dx: float, dy: float) -> bool:
        self.impl.io.add_mouse_wheel_event(dx, dy)
        return self.visible and self.over(*self.viewer.cursor())

    def on_key(self, key: int, scancode: int, action: int, mods: int) -> bool:
        self.impl.keyboard_callback(self.viewer.window, key, scancode, action, mods)
        return self.visible and self.wants_keyboard

    def on_char(self, char: int) -> None:
        self.impl.char_callback(self.viewer.window, char)

    def over(self, x: float, y: float) -> bool:
        """Whether window point (x, y) lies on the panel."""
        return self.visible and x < WIDTH

    # -- drawing -------------------------------------------------------------------------
    def draw(self) -> None:
        """Build and draw one frame of the panel over what is on screen."""
        if not self.visible:
            return
        imgui = self.imgui
        self.impl.process_inputs()
        imgui.new_frame()
        h = self.impl.io.display_size.y
        imgui.set_next_window_pos((0, 0))
        imgui.set_next_window_size((WIDTH, h))
        flags = imgui.WindowFlags_.no_move | imgui.WindowFlags_.no_resize | imgui.WindowFlags_.no_collapse
        imgui.begin("sdfgl", None, flags)
        self._status()
        if imgui.collapsing_header("Parameters", imgui.TreeNodeFlags_.default_open):
            self._params()
        if imgui.collapsing_header("Render", imgui.TreeNodeFlags_.default_open):
            self._settings()
        if imgui.collapsing_header("Scene tree", imgui.TreeNodeFlags_.default_open):
            self._tree(self.viewer.scene)
        imgui.end()
        io = imgui.get_io()
        self.wants_mouse, self.wants_keyboard = io.want_capture_mouse, io.want_text_input
        imgui.render()
        self.impl.render(imgui.get_draw_data())

    def _status(self) -> None:
        imgui, v = self.imgui, self.viewer
        st = v.state
        w, h = st.view[2:]
        self.readout = {"frame_ms": round(st.last_frame_ms, 2), "mean_steps": round(st.mean_steps, 2),
                        "samples": st.samples}
        imgui.text(f"{st.last_frame_ms:.1f} ms/frame  {w}x{h}{' (moving)' if st.moving else ''}")
        imgui.text(f"{st.mean_steps:.1f} steps/pixel (mean of map() calls)")
        imgui.text(f"samples {st.samples}/{v.max_samples}   programs {st.compiles}")
        if st.compile_log:
            imgui.text(f"last compile {st.compile_log[-1]['s']:.2f} s (in the background)")
        if st.compiling:
            imgui.text_colored((1.0, 0.8, 0.3, 1.0), "compiling...")
        if st.error:
            imgui.text_colored((1.0, 0.45, 0.4, 1.0), "error (see overlay)")
        if self.message:
            imgui.text_wrapped(self.message)

    def _params(self) -> None:
        imgui, v = self.imgui, self.viewer
        params = v.live_params()
        if not params:
            imgui.text_wrapped("no sg.param in this scene")
            return
        key = id(v.scene)
        if self._colours[0] != key:
            self._colours = (key, colour_params(v.scene))
        for i, p in enumerate(params):
            label = p.name or f"p{i}"
            imgui.push_id(f"param{i}")
            if id(p) not in self._ranges:
                self._ranges[id(p)] = control(p, self._colours[1])
            kind, lo, hi = self._ranges[id(p)]
            self.controls[label] = kind
            if kind == "slider":
                changed, new = imgui.slider_float(label, float(p.value), lo, hi)
                self.rects[label] = (*imgui.get_item_rect_min(), *imgui.get_item_rect_max())
                typed, val = imgui.input_float("##typed", float(p.value), 0.0, 0.0, "%.4g")
                if typed:
                    changed, new = True, val
            elif kind == "colour":
                changed, rgb = imgui.color_edit3(label, [float(x) for x in p.value])
                new = tuple(rgb)
                self.rects[label] = (*imgui.get_item_rect_min(), *imgui.get_item_rect_max())
            else:
                changed, xyz = imgui.slider_float3(label, [float(x) for x in p.value], lo, hi)
                new = tuple(xyz)
                self.rects[label] = (*imgui.get_item_rect_min(), *imgui.get_item_rect_max())
            if v.live is not None:
                self._live_row(p, label)
            imgui.pop_id()
            if changed:
                self.set_param(p, new)
        if imgui.button("print as Python"):
            print(python_lines(params), flush=True)
            self.message = "values printed to the terminal"
        imgui.same_line()
        if imgui.button("save JSON"):
            self.message = self._save_json()
        self.rects["save JSON"] = (*imgui.get_item_rect_min(), *imgui.get_item_rect_max())
        if v.live is not None:
            if imgui.button("save bindings"):
                self.message = v.live.save()
            self.rects["save bindings"] = (*imgui.get_item_rect_min(), *imgui.get_item_rect_max())

    def _live_row(self, p: Param, label: str) -> None:
        """The parameter's MIDI/OSC row: a "learn" button and the controls bound to it."""
        imgui, live = self.imgui, self.viewer.live
        assert live is not None
        learning = live.control.learning
        waiting = learning is not None and learning[0] == live.control.key(p)
        if imgui.small_button("cancel" if waiting else "learn"):
            if waiting:
                live.control.cancel_learn()
                self.message = ""
            else:
                self.message = live.learn(p)
        self.rects[f"learn:{label}"] = (*imgui.get_item_rect_min(), *imgui.get_item_rect_max())
        imgui.same_line()
        imgui.text("waiting for a control..." if waiting else (live.sources(p) or "no MIDI/OSC"))

    def set_param(self, p: Param, value: Any) -> None:
        """Set a live value (validated by its nodes); the image re-renders with the same program."""
        try:
            p.value = value
        except ParameterError as exc:
            self.message = str(exc)
            return
        self.message = ""
        self.viewer.param_changed()

    def _save_json(self) -> str:
        """Write the scene, the view's camera and its settings as a JSON scene document (sdfgl.scene_io)."""
        from ..scene_io import save_scene
        v = self.viewer
        path = v.screenshot_dir / "scene.json"
        # the tree's selection is a view of this window, not a setting a document can render alone
        settings = {k: val for k, val in v.state.settings.items() if not (k == "debug" and val == "select")}
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            save_scene(v.scene, path, camera=v.camera, settings=settings)
        except OSError as exc:
            return f"could not save {path}: {exc}"
        except SdfglError as exc:
            return f"could not save {path}: {exc}"
        return f"saved {path}"

    def _settings(self) -> None:
        imgui, v = self.imgui, self.viewer
        s = v.wanted_settings
        change: dict[str, Any] = {}
        c, aa = imgui.slider_int("AA", int(s.get("aa", 1)), 1, 4)
        if c:
            change["aa"] = aa
        names = ["off", "hard", "soft"]
        cur = names[SHADOWS.index(s.get("shadows", "soft") or False)]
        c, idx = imgui.combo("shadows", names.index(cur), names)
        if c:
            change["shadows"] = SHADOWS[idx]
        c, ao = imgui.checkbox("ambient occlusion", bool(s.get("ao", False)))
        if c:
            change["ao"] = ao
        c, ground = imgui.checkbox("ground", bool(s.get("ground", False)))
        if c:
            change["ground"] = ground
        methods = list(METHODS)
        c, idx = imgui.combo("method", methods.index(s.get("method", "enhanced")), methods)
        if c:
            change["method"] = methods[idx]
        c, hs = imgui.slider_float("hit scale", float(s.get("hit_scale", 0.25)), 0.01, 2.0, "%.3f",
                                   imgui.SliderFlags_.logarithmic)
        if c:
            change["hit_scale"] = hs
        dbg = s.get("debug") or "off"
        c, idx = imgui.combo("debug view", DEBUG_NAMES.index(dbg) if dbg in DEBUG_NAMES else 0, list(DEBUG_NAMES))
        if c:
            change["debug"] = None if idx == 0 else DEBUG_NAMES[idx]
        if change:
            v.apply_settings(change)

    def _tree(self, node: Node, depth: int = 0) -> None:
        imgui = self.imgui
        flags = imgui.TreeNodeFlags_.open_on_arrow | imgui.TreeNodeFlags_.span_avail_width
        if depth < 2:
            flags |= imgui.TreeNodeFlags_.default_open
        if not node.children:
            flags |= imgui.TreeNodeFlags_.leaf
        if node is self.selected:
            flags |= imgui.TreeNodeFlags_.selected
        text = f"{node.label()}  [{node.exactness}, L={node.lipschitz:g}]"
        opened = imgui.tree_node_ex(f"{text}##{id(node)}", flags)
        self.rects[f"tree:{node.label()}"] = (*imgui.get_item_rect_min(), *imgui.get_item_rect_max())
        if imgui.is_item_clicked() and not imgui.is_item_toggled_open():
            self.select(None if node is self.selected else node)
        if opened:
            for child in node.children:
                self._tree(child, depth + 1)
            imgui.tree_pop()

    def select(self, node: Node | None) -> None:
        """Tint where ``node``'s subtree is the nearest surface (None: no tint)."""
        self.selected = node
        self.viewer.select_node(node)

    def close(self) -> None:
        self.impl.shutdown()
        self.imgui.destroy_context()

"""The notebook widget: the browser viewer inside Jupyter, synced both ways with Python.

Built on anywidget (an ES module plus traitlets, on top of ipywidgets' comm protocol): the
widget's JavaScript is the same viewer.js the HTML page uses, with no build step or
front-end extension to install, and it runs in JupyterLab, Notebook 7, VS Code and Colab.

    w = sg.widget(scene, size=(640, 400))
    w                 # shows the view
    w.camera          # the camera the user has orbited to, as an OrbitCamera
    r.value = 1.3     # the view follows a parameter changed in Python
                      # and a slider moved in the view sets r.value
"""
from __future__ import annotations

import weakref
from typing import Any

import numpy as np

from ..camera import Camera, OrbitCamera
from ..errors import ParameterError, SdfglError
from ..nodes.base import Node
from ..params import Param
from ..uniforms import live_frame
from . import assets
from .spec import orbit_state, build, camera_from_state

try:
    import anywidget
    import traitlets
except ImportError as _exc:  # pragma: no cover - exercised only without the extra
    raise SdfglError("sg.widget needs anywidget: pip install 'sdfgl[web]'") from _exc


def _value_json(v: Any) -> Any:
    return [float(x) for x in v] if np.ndim(v) else float(v)


class SceneWidget(anywidget.AnyWidget):
    """An interactive view of a scene in a notebook (see the module docstring)."""

    _esm = assets.read("viewer.js") + "\n" + assets.read("widget.js")
    _css = assets.read("style.css")
    spec = traitlets.Dict().tag(sync=True)
    values = traitlets.List().tag(sync=True)            # live parameter values, in uniform order
    camera_state = traitlets.Dict().tag(sync=True)      # target, distance, yaw, pitch, fov
    settings_state = traitlets.Dict().tag(sync=True)    # aa, shadows, ao, debug
    frame = traitlets.Dict().tag(sync=True)             # exact scene-box uniforms for the values
    error = traitlets.Unicode("").tag(sync=True)        # why the last value from the view was refused

    def __init__(self, scene: Node, camera: Camera | None = None, size: tuple[int, int] = (640, 400),
                 **settings: Any) -> None:
        spec, params = build(scene, camera, size, **settings)
        self.scene = scene
        self._origin = np.asarray(spec["origin"])
        self._params: tuple[Param, ...] = params
        self._applying = False
        super().__init__(spec=spec, values=[p["value"] for p in spec["params"]], camera_state=spec["camera"],
                         settings_state=spec["settings"], frame=self._frame())
        self.observe(self._values_from_view, names="values")
        # a Param calls its checks after every accepted change: one of them tells this widget.
        # The check holds the widget weakly, the widget holds the check (whatever the Param keeps).
        ref = weakref.ref(self)

        def follow(_value: Any) -> None:
            w = ref()
            if w is not None:
                w._values_from_python()
        self._follow = follow
        for p in self._params:
            p.add_check(follow)

    def __repr__(self) -> str:
        w, h = self.spec["size"]
        vals = ", ".join(f"{p.label}={v}" for p, v in zip(self._params, self.values))
        return f"<sdfgl widget {w}x{h} of {self.spec['title'][:60]}{'; ' + vals if vals else ''}>"

    # -- Python -> view ------------------------------------------------------------------
    def _frame(self) -> dict[str, Any]:
        if not self._params:
            return {}
        return {k: list(v) if isinstance(v, tuple) else v for k, v in live_frame(self.scene, self._origin).items()}

    def _values_from_python(self) -> None:
        if self._applying:
            return
        new = [_value_json(p.value) for p in self._params]
        if new != self.values:
            with self.hold_sync():
                self.values = new
                self.frame = self._frame()

    # -- view -> Python ------------------------------------------------------------------
    def _values_from_view(self, change: dict[str, Any]) -> None:
        if self._applying:
            return
        self._applying = True
        try:
            for p, v in zip(self._params, change["new"]):
                if _value_json(p.value) != v:
                    p.value = v
            self.error = ""
        except ParameterError as exc:
            self.error = str(exc)
            self.values = [_value_json(p.value) for p in self._params]  # the view goes back
        finally:
            self._applying = False
        self.frame = self._frame()

    # -- the camera and toggles in Python ------------------------------------------------
    @property
    def camera(self) -> OrbitCamera:
        """The view's current camera (as the user left it)."""
        return camera_from_state(self.camera_state)

    @camera.setter
    def camera(self, cam: Camera) -> None:
        if not isinstance(cam, Camera):
            raise ParameterError(f"widget.camera must be an sdfgl Camera, got {type(cam).__name__}")
        self.camera_state = orbit_state(OrbitCamera.of(cam, *self.scene.bounds))

    @property
    def settings(self) -> dict[str, Any]:
        """The toggles' current states: aa, shadows, ao, debug."""
        return dict(self.settings_state)

    def render(self, size: tuple[int, int] | None = None, **settings: Any) -> Any:
        """Render the current view headless (EGL) with the view's camera and toggles."""
        from ..render import render
        st = {**{k: v for k, v in self.settings_state.items()}, **settings}
        return render(self.scene, self.camera, size or tuple(self.spec["size"]), **st)


def widget(scene: Node, camera: Camera | None = None, size: tuple[int, int] = (640, 400),
           **settings: Any) -> SceneWidget:
    """An interactive notebook view of ``scene`` (orbit, pan, zoom, toggles, a slider per ``sg.param``).

    Parameters and camera are synced both ways: ``w.camera`` is the current view,
    setting ``w.camera`` or a parameter's ``.value`` in Python updates the view, and a
    slider moved in the view sets the parameter (validated by its nodes).
    """
    return SceneWidget(scene, camera, size, **settings)

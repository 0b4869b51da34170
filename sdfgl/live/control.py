"""Live control: MIDI knobs and OSC addresses driving a scene's live parameters.

    r = sg.param(1.0, name="radius", range=(0.5, 2.0))
    scene = sg.sphere(r)
    with sg.live_control(scene, osc=9000) as ctl:
        ctl.bind_osc("/radius", r)
        ctl.bind_midi(cc=21, param=r)
        ctl.learn(r)            # the next CC moved (or OSC address sent) drives r too
        ...                     # sg.render(scene) shows each new value: a uniform, no recompile

Messages arrive on background threads (the OSC server's, rtmidi's). Each becomes a value
(:mod:`.bindings`), clamped to the range, and is set on the parameter under one lock, so
the nodes' checks run as for any assignment; a value a node rejects is dropped and kept in
:attr:`LiveControl.last_error`. With ``deferred=True`` (the viewer) values wait in a queue
until the owner's thread takes them with :meth:`LiveControl.apply_pending`, and ``wake()``
is called so that thread looks soon. ``smooth`` bindings ease towards each value on a
small timer thread.
"""
from __future__ import annotations

import math
import threading
import time
from pathlib import Path
from typing import Any, Callable, Iterable, Sequence

import numpy as np

from ..errors import ParameterError
from ..nodes.base import Node
from ..params import Param
from .bindings import Binding, cc_value, check_target, load_bindings, osc_value, save_bindings
from .errors import LiveBindingError

SMOOTH_TICK_S = 1 / 120  # how often smoothed values step


class LiveControl:
    """Bindings from MIDI control changes and OSC messages to live parameters (see the module docstring).

    Args:
        scene: the scene whose named parameters bindings may name (or None).
        params: more parameters to offer by name (e.g. the viewer's program's).
        osc: a UDP port to receive OSC on when started (0: any free port; None: no OSC).
        osc_host: the address the OSC server binds (default 127.0.0.1: this machine only).
        midi: a MIDI input port's name to open when started ("" : the first port; None: no MIDI).
        midi_virtual: open ``midi`` as a new virtual port other programs connect to.
        bindings: bindings to start with (e.g. :func:`load_bindings`).
        deferred: queue values for :meth:`apply_pending` instead of setting them on arrival.
        wake: called (on the receiving thread) when a deferred value is queued.
    """

    def __init__(self, scene: Node | None = None, *, params: Iterable[Param] = (), osc: int | None = None,
                 osc_host: str = "127.0.0.1", midi: str | None = None, midi_virtual: bool = False,
                 bindings: Iterable[Binding] = (), deferred: bool = False,
                 wake: Callable[[], None] | None = None) -> None:
        if scene is not None and not isinstance(scene, Node):
            raise ParameterError(f"live_control: 'scene' must be an sdfgl node or None, got {type(scene).__name__} "
                                 f"{scene!r}")
        self._lock = threading.RLock()
        self.scene = scene  # held: the checks of its nodes live as long as it does
        self._params: dict[str, Param] = {}
        self._known: tuple[int, ...] = ()
        self.osc_request, self.osc_host = osc, osc_host
        self.midi_request, self.midi_virtual = midi, midi_virtual
        self.deferred, self.wake = deferred, wake
        self.learning: tuple[str, dict[str, Any]] | None = None
        self.last_error = ""
        self.received = 0           # messages that moved a parameter
        self.last: tuple[str, str, Any] | None = None  # (source, param, value) of the newest one
        self._pending: dict[str, Any] = {}
        self._targets: dict[str, tuple[Any, float]] = {}  # smoothed param -> (target, time constant)
        self._current: dict[str, Any] = {}
        self._smoother: threading.Thread | None = None
        self._stopping = threading.Event()
        self._wanted = threading.Event()
        self._osc: Any = None
        self._midi: Any = None
        self.use([*(scene.live_params() if scene is not None else []), *params])
        self.bindings: list[Binding] = []
        for b in bindings:
            self.add(b)

    # -- parameters -----------------------------------------------------------------------
    @staticmethod
    def key(p: Param) -> str:
        """The name bindings use for ``p``: its name (an unnamed one gets its label, which no file can name)."""
        return p.name or p.label

    @property
    def params(self) -> dict[str, Param]:
        """The parameters bindings can drive, by name."""
        with self._lock:
            return dict(self._params)

    def use(self, params: Sequence[Param]) -> None:
        """Offer these parameters by name (replacing those offered before, e.g. after a scene reload);
        bindings keep their names and drive whichever parameter has the name now."""
        ids = tuple(id(p) for p in params)
        if ids == self._known:
            return
        with self._lock:
            self._known = ids
            self._params = {self.key(p): p for p in params}
            for k in list(self._targets):
                if k not in self._params:
                    del self._targets[k]

    def _resolve(self, param: Param | str) -> tuple[str, Param]:
        if isinstance(param, Param):
            with self._lock:
                self._params.setdefault(self.key(param), param)
            return self.key(param), param
        with self._lock:
            p = self._params.get(param)
        if p is None:
            known = ", ".join(sorted(self._params)) or "none"
            raise LiveBindingError(f"no live parameter named {param!r} to bind (the scene has: {known})")
        return param, p

    # -- bindings --------------------------------------------------------------------------
    def add(self, binding: Binding, where: str = "") -> Binding:
        """Add ``binding`` (its parameter must be offered and fit it); returns it. ``where`` prefixes errors."""
        try:
            _, p = self._resolve(binding.param)
            check_target(binding, p)
        except LiveBindingError as exc:
            raise LiveBindingError(f"{where}{exc}") from None
        with self._lock:
            if binding not in self.bindings:
                self.bindings.append(binding)
        return binding

    def bind_osc(self, address: str, param: Param | str, *, component: int | None = None,
                 range: tuple[float, float] | None = None, normalized: bool = False,
                 smooth: float = 0.0) -> Binding:
        """Drive ``param`` from OSC ``address``: one float sets it (three set a 3-vector), clamped to its
        range; ``normalized`` floats 0..1 span the range instead. Returns the binding."""
        key, _ = self._resolve(param)
        return self.add(Binding(key, osc=address, component=component, range=range, normalized=normalized,
                                smooth=smooth))

    def bind_midi(self, cc: int, param: Param | str, *, channel: int | None = None, component: int | None = None,
                  range: tuple[float, float] | None = None, smooth: float = 0.0) -> Binding:
        """Drive ``param`` from MIDI control change ``cc`` (on ``channel`` 0..15, None: any): 0..127 spans
        its range (or ``range``). Returns the binding."""
        key, _ = self._resolve(param)
        return self.add(Binding(key, cc=cc, channel=channel, component=component, range=range, smooth=smooth))

    def unbind(self, param: Param | str) -> int:
        """Remove every binding of ``param``; returns how many there were."""
        key = self.key(param) if isinstance(param, Param) else param
        with self._lock:
            before = len(self.bindings)
            self.bindings = [b for b in self.bindings if b.param != key]
            return before - len(self.bindings)

    def learn(self, param: Param | str, *, component: int | None = None,
              range: tuple[float, float] | None = None, smooth: float = 0.0) -> None:
        """MIDI learn: the next control change (or OSC address) that arrives gets bound to ``param``.

        The options are those of :meth:`bind_midi`; the CC's channel is bound too. Raises
        LiveBindingError at once when a CC could not drive ``param`` (no finite range)."""
        key, p = self._resolve(param)
        check_target(Binding(key, cc=0, component=component, range=range, smooth=smooth), p)
        with self._lock:
            self.learning = (key, {"component": component, "range": range, "smooth": smooth})

    def cancel_learn(self) -> None:
        """Stop waiting for a control to learn."""
        with self._lock:
            self.learning = None

    def load(self, path: str | Path) -> list[Binding]:
        """Add the bindings of a bindings file; errors name the file and the JSON path (an unknown parameter too)."""
        got = load_bindings(path)
        for i, b in enumerate(got):
            self.add(b, where=f"{path}: bindings[{i}]: ")
        return got

    def save(self, path: str | Path) -> Path:
        """Write the bindings as a JSON bindings file; every bound parameter needs a name."""
        with self._lock:
            bindings = list(self.bindings)
        unnamed = [b.param for b in bindings if b.param.startswith("#")]
        if unnamed:
            raise LiveBindingError(f"cannot save bindings of unnamed parameter {unnamed[0]}: give it a name "
                                   f"(sg.param(..., name='radius')) so the file can name it")
        return save_bindings(bindings, path)

    # -- messages --------------------------------------------------------------------------
    def handle_midi(self, msg: Any) -> None:
        """Route one mido message: a control change moves the parameters bound to it (or is learned)."""
        if getattr(msg, "type", None) != "control_change":
            return
        with self._lock:
            if self.learning is not None:
                key, opts = self.learning
                self.learning = None
                try:
                    self.add(Binding(key, cc=msg.control, channel=msg.channel, **opts))
                except LiveBindingError as exc:
                    self.last_error = str(exc)
            hits = [b for b in self.bindings
                    if b.cc == msg.control and (b.channel is None or b.channel == msg.channel)]
            for b in hits:
                p = self._params.get(b.param)
                if p is None:
                    continue
                v = cc_value(b, p, msg.value)
                if b.component is not None:
                    vec = np.array(self._latest(b.param, p), dtype=np.float64)
                    vec[b.component] = v
                    v = vec
                self._deliver(b, p, v)

    def handle_osc(self, address: str, *args: Any) -> None:
        """Route one OSC message: the parameters bound to ``address`` take its numbers (or it is learned)."""
        with self._lock:
            if self.learning is not None and args:
                key, opts = self.learning
                self.learning = None
                try:
                    self.add(Binding(key, osc=address, **opts))
                except LiveBindingError as exc:
                    self.last_error = str(exc)
            for b in [b for b in self.bindings if b.osc == address]:
                p = self._params.get(b.param)
                if p is None:
                    continue
                v = osc_value(b, p, args, base=self._latest(b.param, p))
                if v is None:
                    self.last_error = (f"OSC {address}: {len(args)} argument(s) {list(args)!r} do not fit "
                                       f"{b.param} (one number, or three for a 3-vector)")
                    continue
                self._deliver(b, p, v)

    def _latest(self, key: str, p: Param) -> Any:
        """The newest value meant for ``p`` (lock held): an eased-towards target, a queued value, or its own."""
        if key in self._targets:
            return self._targets[key][0]
        return self._pending.get(key, p.value)

    def _deliver(self, b: Binding, p: Param, value: Any) -> None:
        """A new value for ``p`` (lock held): set now, queued, or eased towards."""
        self.received += 1
        self.last = (b.source, b.param, value)
        if b.smooth > 0:
            if b.param not in self._targets:  # easing starts from where the parameter is now
                self._current[b.param] = self._pending.get(b.param, p.value)
            self._targets[b.param] = (value, b.smooth)
            self._wanted.set()
            return
        self._targets.pop(b.param, None)
        self._set(b.param, p, value)

    def _set(self, key: str, p: Param, value: Any) -> None:
        self._current[key] = value
        if self.deferred:
            self._pending[key] = value
            if self.wake is not None:
                self.wake()
            return
        self._assign(p, value)

    def _assign(self, p: Param, value: Any) -> bool:
        try:
            p.value = value
        except ParameterError as exc:
            self.last_error = str(exc)
            return False
        return True

    def apply_pending(self) -> list[Param]:
        """Set the queued values (deferred mode) on this thread; returns the parameters that changed."""
        with self._lock:
            pending, self._pending = self._pending, {}
            out = []
            for key, value in pending.items():
                p = self._params.get(key)
                if p is not None and self._assign(p, value):
                    out.append(p)
            return out

    def _smooth_loop(self) -> None:
        last = time.perf_counter()
        while not self._stopping.is_set():
            if not self._targets:
                self._wanted.wait(0.5)
                self._wanted.clear()
                last = time.perf_counter()
                continue
            time.sleep(SMOOTH_TICK_S)
            now = time.perf_counter()
            dt, last = now - last, now
            with self._lock:
                for key, (target, tau) in list(self._targets.items()):
                    p = self._params.get(key)
                    if p is None:
                        del self._targets[key]
                        continue
                    cur = np.asarray(self._current.get(key, p.value), dtype=np.float64)
                    goal = np.asarray(target, dtype=np.float64)
                    step = cur + (goal - cur) * (1.0 - math.exp(-dt / tau))
                    if np.all(np.abs(goal - step) <= 1e-4 * np.maximum(1.0, np.abs(goal))):  # close enough: land
                        step = goal
                        del self._targets[key]
                    self._set(key, p, float(step) if step.ndim == 0 else step)

    # -- inputs ----------------------------------------------------------------------------
    @property
    def osc_port(self) -> int | None:
        """The UDP port OSC is received on (None until started with ``osc``)."""
        return self._osc.port if self._osc is not None else None

    def start(self) -> "LiveControl":
        """Open the OSC server and the MIDI port asked for, and the smoothing timer; returns self."""
        from .midi import open_input
        from .osc import OscServer
        if self._smoother is None:
            self._stopping.clear()
            self._smoother = threading.Thread(target=self._smooth_loop, name="sdfgl-live-smooth", daemon=True)
            self._smoother.start()
        try:
            if self.osc_request is not None and self._osc is None:
                self._osc = OscServer(self.handle_osc, self.osc_request, self.osc_host)
            if self.midi_request is not None and self._midi is None:
                self._midi = open_input(self.midi_request or None, self.handle_midi, virtual=self.midi_virtual)
        except Exception:
            self.stop()
            raise
        return self

    def stop(self) -> None:
        """Close the inputs and stop the threads (each within a fraction of a second)."""
        if self._osc is not None:
            self._osc.close()
            self._osc = None
        if self._midi is not None:
            self._midi.close()
            self._midi = None
        if self._smoother is not None:
            self._stopping.set()
            self._wanted.set()
            self._smoother.join(timeout=5)
            self._smoother = None

    def __enter__(self) -> "LiveControl":
        return self.start()

    def __exit__(self, *exc: Any) -> None:
        self.stop()

    def describe(self) -> list[str]:
        """One line per binding: "CC21 -> radius", "/radius -> radius"."""
        with self._lock:
            return [f"{b.source} -> {b.param}" + (f"[{b.component}]" if b.component is not None else "")
                    for b in self.bindings]


def live_control(scene: Node | None = None, **options: Any) -> LiveControl:
    """A :class:`LiveControl` for ``scene``: bind its parameters to MIDI CCs and OSC addresses, then
    ``start()`` it (or use it as a context manager).

    Args:
        scene: the scene whose named live parameters bindings may name (None: bind Param objects).
        options: those of :class:`LiveControl`: ``osc=PORT`` (0: a free port), ``osc_host``,
            ``midi="port name"``, ``midi_virtual``, ``params``, ``bindings``, ``deferred``, ``wake``.

    Opening the inputs needs ``pip install 'sdfgl[live]'`` (mido, python-rtmidi, python-osc);
    :meth:`LiveControl.handle_midi` and :meth:`LiveControl.handle_osc` route messages without it.

    Example:
        >>> r = sg.param(1.0, name="radius", range=(0.5, 2.0))
        >>> ctl = sg.live_control(sg.sphere(r))
        >>> _ = ctl.bind_osc("/radius", r)
        >>> ctl.handle_osc("/radius", 5.0)      # what the OSC server does for each message
        >>> r.value                              # clamped to the range
        2.0
    """
    return LiveControl(scene, **options)

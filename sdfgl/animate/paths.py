"""Camera paths: a camera for every moment of an animation.

    sg.turntable(distance=5, pitch=20)                      # one turn over the clip
    sg.camera_path({0: ((6, 2, 0), (0, 0, 0)),              # time: (eye, target)
                    2: ((0, 3, 6), (0, 0.5, 0)),
                    4: {"eye": (-6, 2, 0), "target": (0, 0, 0), "fov": 35}})

A path is evaluated on the CPU in float64 (the camera is a set of uniforms), so moving it
never changes the shader. ``path.camera(t, duration, scene)`` gives the camera at ``t``.
"""
from __future__ import annotations

from typing import Any, Mapping, Sequence

import numpy as np

from ..camera import Camera, OrbitCamera, check_fov
from ..errors import ParameterError
from ..nodes.base import Node
from ..values import validate as v
from .keyframes import keyframe_list

PATH_EASES = ("spline", "linear", "smooth")


class CameraPath:
    """Base class: ``camera(t, duration, scene)`` returns the camera at ``t`` seconds."""

    def camera(self, t: float, duration: float, scene: Node | None = None) -> Camera:  # pragma: no cover
        raise NotImplementedError


class Turntable(CameraPath):
    """An orbit camera turning about the target: ``turns`` full turns over the clip (or one per ``period``)."""

    def __init__(self, distance: float | None = None, pitch: float = 20.0, target: Sequence[float] | None = None,
                 fov: float = 45.0, yaw: float = 30.0, turns: float = 1.0, period: float | None = None) -> None:
        self.distance = None if distance is None else v.scalar("turntable", "distance", distance, positive=True)
        self.pitch = v.scalar("turntable", "pitch", pitch)
        if abs(self.pitch) > 89.9:
            raise ParameterError(f"turntable: parameter 'pitch' must lie in [-89.9, 89.9], got {self.pitch:g}")
        self.target = None if target is None else v.vector("turntable", "target", target)
        self.fov = check_fov("turntable", fov)
        self.yaw = v.scalar("turntable", "yaw", yaw)
        self.turns = v.scalar("turntable", "turns", turns)
        self.period = None if period is None else v.scalar("turntable", "period", period, positive=True)

    def camera(self, t: float, duration: float, scene: Node | None = None) -> OrbitCamera:
        target, distance = self.target, self.distance
        if scene is None:  # nothing to frame: orbit the origin
            if distance is None:
                raise ParameterError("turntable: give 'distance', or a scene to frame")
            target = np.zeros(3) if target is None else target
        elif target is None or distance is None:
            frame = OrbitCamera.framing(*scene.bounds, fov=self.fov)
            target = frame.target if target is None else target
            distance = frame.distance if distance is None else distance
        spin = t / self.period if self.period is not None else self.turns * t / duration if duration > 0 else 0.0
        return OrbitCamera(target, distance, (self.yaw + 360.0 * spin) % 360.0, self.pitch, self.fov)

    def __repr__(self) -> str:
        return (f"turntable(distance={self.distance}, pitch={self.pitch:g}, yaw={self.yaw:g}, "
                f"turns={self.turns:g}, period={self.period})")


def turntable(distance: float | None = None, pitch: float = 20.0, target: Sequence[float] | None = None,
              fov: float = 45.0, yaw: float = 30.0, turns: float = 1.0, period: float | None = None) -> Turntable:
    """A camera orbiting a target, for ``sg.animate(..., camera=sg.turntable(...))``.

    Args:
        distance: eye-to-target distance in scene units, > 0 (default: what frames the
            scene's bounds at ``fov``).
        pitch: elevation above the target's horizontal plane in degrees, in [-89.9, 89.9].
        target: the 3-vector it orbits (default: the centre of the scene's box, or the
            origin when there is no scene).
        fov: vertical field of view in degrees, in [1e-4, 179].
        yaw: the starting turn about the Y axis in degrees, as ``OrbitCamera`` (0 looks
            along -Z from +Z); the turntable adds 360 degrees per turn.
        turns: full turns over the clip; frames are at ``i / fps``, so a 1-turn clip loops
            without a repeated frame.
        period: seconds per turn; when given it replaces ``turns`` (a clip of any length).

    Returns a :class:`Turntable`; ``.camera(t, duration, scene)`` is its ``OrbitCamera``
    at ``t`` seconds into a clip of ``duration`` seconds.

    Example:
        >>> tt = sg.turntable(distance=5, pitch=20, yaw=0)
        >>> tt.camera(1.0, 4.0)  # a quarter of the way through a 4 s clip
        OrbitCamera(target=(0.0, 0.0, 0.0), distance=5, yaw=90, pitch=20, fov=45)
    """
    return Turntable(distance, pitch, target, fov, yaw, turns, period)


def _interpolate(ts: np.ndarray, ps: np.ndarray, t: float, ease: str) -> np.ndarray:
    """Values ``ps`` (n, k) at times ``ts`` (n,) interpolated at ``t`` (held outside the keys)."""
    if t <= ts[0]:
        return ps[0].copy()
    if t >= ts[-1]:
        return ps[-1].copy()
    i = int(np.searchsorted(ts, t, side="right")) - 1
    dt = ts[i + 1] - ts[i]
    s = (t - ts[i]) / dt
    if ease == "linear":
        return ps[i] + s * (ps[i + 1] - ps[i])
    if ease == "smooth":
        return ps[i] + s * s * (3 - 2 * s) * (ps[i + 1] - ps[i])

    def slope(j: int) -> np.ndarray:  # Catmull-Rom tangents for uneven key times, one-sided at the ends
        a, b = max(j - 1, 0), min(j + 1, len(ts) - 1)
        return (ps[b] - ps[a]) / (ts[b] - ts[a])
    h00, h10, h01, h11 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2
    return h00 * ps[i] + h10 * dt * slope(i) + h01 * ps[i + 1] + h11 * dt * slope(i + 1)


class LookAtPath(CameraPath):
    """A look-at camera whose eye, target and fov pass through keyframes."""

    def __init__(self, keys: Mapping[float, Any] | Sequence[tuple[float, Any]], ease: str = "spline",
                 up: Sequence[float] = (0.0, 1.0, 0.0), fov: float = 45.0) -> None:
        what = "camera_path"
        if ease not in PATH_EASES:
            raise ParameterError(f"{what}: ease must be one of {', '.join(PATH_EASES)}, got {ease!r}")
        self.ease = ease
        self.up = v.vector(what, "up", up, nonzero=True)
        fov = v.scalar(what, "fov", fov, positive=True)
        rows = []
        for i, (t, key) in enumerate(keyframe_list(keys, what)):
            if isinstance(key, Mapping):
                unknown = set(key) - {"eye", "target", "fov"}
                if unknown or "eye" not in key:
                    raise ParameterError(f"{what}: key {i} must have 'eye' (and may have 'target', 'fov'), "
                                         f"got keys {sorted(key)}")
                eye, target, kfov = key["eye"], key.get("target", (0.0, 0.0, 0.0)), key.get("fov", fov)
            else:
                try:
                    eye, target = key
                except (TypeError, ValueError):
                    raise ParameterError(f"{what}: key {i} must be (eye, target) or a dict, got {key!r}") from None
                kfov = fov
            Camera(eye, target, self.up, kfov)  # each key must be a valid camera (names the bad value)
            rows.append([t, *v.vector(what, f"key {i} eye", eye), *v.vector(what, f"key {i} target", target),
                         v.scalar(what, f"key {i} fov", kfov)])
        table = np.array(rows, dtype=np.float64)
        self.times, self.values = table[:, 0], table[:, 1:]

    @property
    def duration(self) -> float:
        """The time of the last key."""
        return float(self.times[-1])

    def camera(self, t: float, duration: float = 0.0, scene: Node | None = None) -> Camera:
        x = _interpolate(self.times, self.values, t, self.ease)
        eye, target = x[0:3], x[3:6]
        if np.linalg.norm(eye - target) < 1e-9:
            raise ParameterError(f"camera_path: at t={t:g} s the eye meets the target; move the keys apart")
        return Camera(eye, target, self.up, float(np.clip(x[6], 1e-4, 179.0)))

    def __repr__(self) -> str:
        return f"camera_path({len(self.times)} keys, {self.times[0]:g}..{self.times[-1]:g} s, ease={self.ease!r})"


def camera_path(keys: Mapping[float, Any] | Sequence[tuple[float, Any]], ease: str = "spline",
                up: Sequence[float] = (0.0, 1.0, 0.0), fov: float = 45.0) -> LookAtPath:
    """A look-at camera moving through keyframes, held before the first key and after the last.

    Args:
        keys: ``{seconds: (eye, target)}`` or ``{seconds: {"eye": ..., "target": ...,
            "fov": ...}}`` (target defaults to the origin, fov to ``fov``), or a list of
            ``(seconds, key)`` pairs; times strictly increasing, eye and target 3-vectors
            in scene units, each key a valid camera (eye != target).
        ease: "spline" (Catmull-Rom: passes through every key without stopping), "linear"
            or "smooth" (eases in and out of every key, stopping at each).
        up: the world up direction (3-vector, not zero) the cameras keep level to.
        fov: vertical field of view in degrees for keys that give none, > 0.

    Returns a :class:`LookAtPath`: ``.camera(t)`` is the ``Camera`` at ``t`` seconds,
    interpolated in float64 on the CPU (the camera is uniforms: moving it never recompiles);
    ``.duration`` is the time of the last key.

    Example:
        >>> path = sg.camera_path({0: ((6, 2, 0), (0, 0, 0)), 2: ((0, 2, 6), (0, 0, 0))}, ease="linear")
        >>> path.camera(1.0).eye.tolist(), path.duration
        ([3.0, 2.0, 3.0], 2.0)
    """
    return LookAtPath(keys, ease, up, fov)

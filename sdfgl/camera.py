"""Cameras: a look-at pinhole camera and the orbit camera the viewer drives.

Y is up, angles are in degrees, ``fov`` is the vertical field of view. ``rays()``
returns exactly the rays the shader traces (pixel centres, row 0 at the top).
"""
from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from .errors import ParameterError
from .nodes import validate as v

UP = np.array([0.0, 1.0, 0.0])
# camera positions and distances reach the shader as float32 (relative to the scene): keep them
# well inside its range (3.4e38), the same bound as the settings
COORD_MAX = 1e29


def _finite(op: str, **values: float) -> None:
    """Refuse NaN, inf or a non-number given to a camera operation, naming the operation and argument."""
    for name, val in values.items():
        if isinstance(val, bool) or not isinstance(val, (int, float, np.integer, np.floating)) or not math.isfinite(val):
            raise ParameterError(f"{op}: '{name}' must be a finite number, got {val!r}")


def _in_range(op: str, name: str, vec: np.ndarray) -> None:
    if not np.all(np.isfinite(vec)) or np.max(np.abs(vec)) > COORD_MAX:
        raise ParameterError(f"{op}: the camera's '{name}' would be {tuple(float(x) for x in vec)}, outside "
                             f"+-{COORD_MAX:g} (what the float32 shader can hold); the camera is unchanged")


class Camera:
    """Pinhole camera at ``eye`` looking at ``target``."""

    def __init__(self, eye: Sequence[float], target: Sequence[float] = (0.0, 0.0, 0.0),
                 up: Sequence[float] = (0.0, 1.0, 0.0), fov: float = 45.0) -> None:
        self.eye = v.vector("camera", "eye", eye)
        self.target = v.vector("camera", "target", target)
        self.up_hint = v.vector("camera", "up", up, nonzero=True)
        self.fov = v.scalar("camera", "fov", fov)
        if not 1e-4 <= self.fov <= 179.0:
            raise ParameterError(f"camera: parameter 'fov' must be in [1e-4, 179] degrees, got {self.fov:g}")
        _in_range("camera", "eye", self.eye)
        _in_range("camera", "target", self.target)
        self.basis()  # validate the geometry now

    @classmethod
    def look_at(cls, eye: Sequence[float], target: Sequence[float] = (0.0, 0.0, 0.0),
                up: Sequence[float] = (0.0, 1.0, 0.0), fov: float = 45.0) -> "Camera":
        """Camera at ``eye`` looking at ``target`` with ``up`` as the approximate up direction."""
        return cls(eye, target, up, fov)

    def basis(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Unit (right, up, forward) vectors in float64."""
        f = self.target - self.eye
        n = np.linalg.norm(f)
        if n == 0:
            raise ParameterError("camera: 'eye' and 'target' coincide; the view direction is undefined")
        f = f / n
        r = np.cross(f, self.up_hint)
        rn = np.linalg.norm(r)
        if rn < 1e-9:  # looking straight along 'up': pick any perpendicular right vector
            r = np.cross(f, np.array([0.0, 0.0, 1.0]) if abs(f[2]) < 0.9 else np.array([1.0, 0.0, 0.0]))
            rn = np.linalg.norm(r)
        r = r / rn
        u = np.cross(r, f)
        return r, u, f

    @property
    def tan_half_fov(self) -> float:
        return math.tan(math.radians(self.fov) / 2)

    def rays(self, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
        """Float64 ray origins and unit directions, shape (height, width, 3), row 0 on top."""
        if width < 1 or height < 1:
            raise ParameterError(f"camera.rays: size must be positive, got {width}x{height}")
        r, u, f = self.basis()
        th = self.tan_half_fov
        x = (2.0 * (np.arange(width) + 0.5) - width) / height
        y = (height - 2.0 * (np.arange(height) + 0.5)) / height
        d = f + th * (x[None, :, None] * r + y[:, None, None] * u)
        d /= np.linalg.norm(d, axis=-1, keepdims=True)
        o = np.broadcast_to(self.eye, d.shape).copy()
        return o, d

    def pixel_angle(self, height: int) -> float:
        """Angle one pixel subtends: a ray's footprint at distance t is t * pixel_angle."""
        return 2.0 * self.tan_half_fov / height

    def __repr__(self) -> str:
        return f"Camera(eye={tuple(self.eye)}, target={tuple(self.target)}, fov={self.fov:g})"


class OrbitCamera(Camera):
    """Camera orbiting ``target`` at ``distance``; ``yaw`` turns about Y, ``pitch`` lifts the eye."""

    def __init__(self, target: Sequence[float] = (0.0, 0.0, 0.0), distance: float = 5.0,
                 yaw: float = 30.0, pitch: float = 20.0, fov: float = 45.0) -> None:
        self.distance = v.scalar("OrbitCamera", "distance", distance, positive=True)
        if self.distance > COORD_MAX:
            raise ParameterError(f"OrbitCamera: parameter 'distance' must be at most {COORD_MAX:g}, got {self.distance:g}")
        self.yaw = v.scalar("OrbitCamera", "yaw", yaw)
        self.pitch = v.scalar("OrbitCamera", "pitch", pitch)
        if abs(self.pitch) > 89.9:
            raise ParameterError(f"OrbitCamera: parameter 'pitch' must lie in [-89.9, 89.9], got {self.pitch:g}")
        tgt = v.vector("OrbitCamera", "target", target)
        super().__init__(self._eye(tgt), tgt, UP, fov)

    def _eye(self, target: np.ndarray) -> np.ndarray:
        y, p = math.radians(self.yaw), math.radians(self.pitch)
        return target + self.distance * np.array([math.cos(p) * math.sin(y), math.sin(p), math.cos(p) * math.cos(y)])

    def _update(self) -> None:
        self.eye = self._eye(self.target)

    def _move(self, op: str, **state: object) -> None:
        """Apply new yaw/pitch/distance/target only if the eye and target stay in range."""
        old = {k: getattr(self, k) for k in state}
        for k, val in state.items():
            setattr(self, k, val)
        eye = self._eye(self.target)
        try:
            _in_range(op, "target", self.target)
            _in_range(op, "eye", eye)
        except ParameterError:
            for k, val in old.items():
                setattr(self, k, val)
            raise
        self.eye = eye

    def orbit(self, dyaw: float, dpitch: float) -> None:
        """Turn about the target by the given angles in degrees (pitch is clamped)."""
        _finite("OrbitCamera.orbit", dyaw=dyaw, dpitch=dpitch)
        self._move("OrbitCamera.orbit", yaw=(self.yaw + float(dyaw)) % 360.0,
                   pitch=max(-89.0, min(89.0, self.pitch + float(dpitch))))

    def pan(self, dx: float, dy: float) -> None:
        """Move target and eye along the image plane by fractions of the view height."""
        _finite("OrbitCamera.pan", dx=dx, dy=dy)
        r, u, _ = self.basis()
        span = 2.0 * self.distance * self.tan_half_fov
        self._move("OrbitCamera.pan", target=self.target + span * (-float(dx) * r + float(dy) * u))

    def zoom(self, factor: float) -> None:
        """Multiply the distance to the target by ``factor`` (> 0), down to 1e-9 and up to 1e29."""
        _finite("OrbitCamera.zoom", factor=factor)
        if not factor > 0:
            raise ParameterError(f"OrbitCamera.zoom: 'factor' must be > 0, got {factor!r}")
        self._move("OrbitCamera.zoom", distance=min(max(self.distance * float(factor), 1e-9), COORD_MAX))

    @classmethod
    def framing(cls, lo: np.ndarray, hi: np.ndarray, yaw: float = 30.0, pitch: float = 20.0,
                fov: float = 45.0) -> "OrbitCamera":
        """An orbit camera that shows the whole box [lo, hi] (infinite sides are ignored)."""
        finite = np.isfinite(lo) & np.isfinite(hi)
        lo_f = np.where(finite, lo, -1.0)
        hi_f = np.where(finite, hi, 1.0)
        centre = (lo_f + hi_f) / 2
        radius = max(float(np.linalg.norm(hi_f - lo_f)) / 2, 1e-6)
        dist = radius / math.sin(math.radians(fov) / 2) * 1.05
        return cls(centre, dist, yaw, pitch, fov)

    def __repr__(self) -> str:
        return (f"OrbitCamera(target={tuple(self.target)}, distance={self.distance:g}, yaw={self.yaw:g}, "
                f"pitch={self.pitch:g}, fov={self.fov:g})")

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


class Camera:
    """Pinhole camera at ``eye`` looking at ``target`` (Y up, angles in degrees).

    Args:
        eye: the eye position (x, y, z).
        target: the point looked at; must differ from ``eye``.
        up: approximate up direction (not zero).
        fov: vertical field of view in degrees, in [1e-4, 179].

    ``rays(w, h)`` gives the float64 rays the shader traces (pixel centres, row 0 on top).

    Example:
        >>> cam = sg.Camera.look_at((0, 0, 5), (0, 0, 0), fov=40)
        >>> o, d = cam.rays(4, 3)
        >>> d.shape
        (3, 4, 3)
    """

    def __init__(self, eye: Sequence[float], target: Sequence[float] = (0.0, 0.0, 0.0),
                 up: Sequence[float] = (0.0, 1.0, 0.0), fov: float = 45.0) -> None:
        self.eye = v.vector("camera", "eye", eye)
        self.target = v.vector("camera", "target", target)
        self.up_hint = v.vector("camera", "up", up, nonzero=True)
        self.fov = v.scalar("camera", "fov", fov)
        if not 1e-4 <= self.fov <= 179.0:
            raise ParameterError(f"camera: parameter 'fov' must be in [1e-4, 179] degrees, got {self.fov:g}")
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
    """Camera orbiting ``target`` at ``distance`` (the viewer drives it).

    Args:
        target: the point looked at and orbited.
        distance: eye-to-target distance, > 0.
        yaw: turn about the Y axis, degrees (0 looks along -Z from +Z).
        pitch: lift of the eye above the target's horizontal plane, degrees in [-89.9, 89.9].
        fov: vertical field of view, degrees.

    Example:
        >>> cam = sg.OrbitCamera(target=(0, 1, 0), distance=5, yaw=0, pitch=0)
        >>> [round(float(x), 6) for x in cam.eye]
        [0.0, 1.0, 5.0]
    """

    def __init__(self, target: Sequence[float] = (0.0, 0.0, 0.0), distance: float = 5.0,
                 yaw: float = 30.0, pitch: float = 20.0, fov: float = 45.0) -> None:
        self.distance = v.scalar("OrbitCamera", "distance", distance, positive=True)
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

    def orbit(self, dyaw: float, dpitch: float) -> None:
        """Turn about the target by the given angles in degrees (pitch is clamped)."""
        self.yaw = (self.yaw + dyaw) % 360.0
        self.pitch = max(-89.0, min(89.0, self.pitch + dpitch))
        self._update()

    def pan(self, dx: float, dy: float) -> None:
        """Move target and eye along the image plane by fractions of the view height."""
        r, u, _ = self.basis()
        span = 2.0 * self.distance * self.tan_half_fov
        self.target = self.target + span * (-dx * r + dy * u)
        self._update()

    def zoom(self, factor: float) -> None:
        """Multiply the distance to the target by ``factor`` (> 0); there is no minimum."""
        if not factor > 0:
            raise ParameterError(f"OrbitCamera.zoom: factor must be > 0, got {factor!r}")
        self.distance = max(self.distance * factor, 1e-9)
        self._update()

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

"""Cameras: a look-at camera and the orbit camera the viewer drives, perspective or
orthographic, and framing that fits a box for the image's aspect ratio.

Y is up, angles are in degrees, ``fov`` is the vertical field of view. ``rays()``
returns exactly the rays the shader traces (pixel centres, row 0 at the top).
"""
from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from .errors import ParameterError
from .values import validate as v

UP = np.array([0.0, 1.0, 0.0])
PROJECTIONS = ("perspective", "orthographic")
FRAME_MARGIN = 1.05  # framing leaves this much room around the box


def check_fov(name: str, fov: object) -> float:
    """A vertical field of view in degrees, in [1e-4, 179]; ParameterError naming ``name.fov``."""
    out = float(v.scalar(name, "fov", fov))
    if not 1e-4 <= out <= 179.0:
        raise ParameterError(f"{name}: parameter 'fov' must be in [1e-4, 179] degrees, got {out:g}")
    return out


def _projection(name: str, projection: str, ortho_height: float | None) -> float | None:
    if projection not in PROJECTIONS:
        raise ParameterError(f"{name}: parameter 'projection' must be 'perspective' or 'orthographic', "
                             f"got {projection!r}")
    if ortho_height is None:
        return None
    if projection != "orthographic":
        raise ParameterError(f"{name}: 'ortho_height' applies to projection='orthographic' only")
    return float(v.scalar(name, "ortho_height", ortho_height, positive=True))

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
    """Camera at ``eye`` looking at ``target`` (Y up, angles in degrees).

    Args:
        eye: the eye position (x, y, z).
        target: the point looked at; must differ from ``eye``.
        up: approximate up direction (not zero).
        fov: vertical field of view in degrees, in [1e-4, 179].
        projection: ``"perspective"`` (a pinhole with vertical field of view ``fov``) or
            ``"orthographic"``: parallel rays along the view direction from the image
            plane through ``eye``.
        ortho_height: world height of an orthographic view (default: the height the
            perspective view has at the target, 2 |target - eye| tan(fov / 2)).

    ``rays(w, h)`` gives the float64 rays the shader traces (pixel centres, row 0 on top).

    Example:
        >>> cam = sg.Camera.look_at((0, 0, 5), (0, 0, 0), fov=40)
        >>> o, d = cam.rays(4, 3)
        >>> d.shape
        (3, 4, 3)
        >>> sg.Camera((0, 0, 5), projection="orthographic", ortho_height=2).ortho_height
        2.0
    """

    def __init__(self, eye: Sequence[float], target: Sequence[float] = (0.0, 0.0, 0.0),
                 up: Sequence[float] = (0.0, 1.0, 0.0), fov: float = 45.0, projection: str = "perspective",
                 ortho_height: float | None = None) -> None:
        self.eye = v.vector("camera", "eye", eye)
        self.target = v.vector("camera", "target", target)
        self.up_hint = v.vector("camera", "up", up, nonzero=True)
        self.fov = check_fov("camera", fov)
        self.projection = projection
        self._ortho_height = _projection("camera", projection, ortho_height)
        _in_range("camera", "eye", self.eye)
        _in_range("camera", "target", self.target)
        self.basis()  # validate the geometry now

    @classmethod
    def look_at(cls, eye: Sequence[float], target: Sequence[float] = (0.0, 0.0, 0.0),
                up: Sequence[float] = (0.0, 1.0, 0.0), fov: float = 45.0, projection: str = "perspective",
                ortho_height: float | None = None) -> "Camera":
        """Camera at ``eye`` looking at ``target`` with ``up`` as the approximate up direction."""
        return cls(eye, target, up, fov, projection, ortho_height)

    @property
    def orthographic(self) -> bool:
        return self.projection == "orthographic"

    @property
    def ortho_height(self) -> float:
        """World height of an orthographic view (given, or the perspective view's at the target)."""
        if self._ortho_height is not None:
            return self._ortho_height
        return 2.0 * float(np.linalg.norm(self.target - self.eye)) * self.tan_half_fov

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
        x = (2.0 * (np.arange(width) + 0.5) - width) / height
        y = (height - 2.0 * (np.arange(height) + 0.5)) / height
        plane = x[None, :, None] * r + y[:, None, None] * u
        if self.orthographic:
            o = self.eye + 0.5 * self.ortho_height * plane
            return o, np.broadcast_to(f, o.shape).copy()
        d = f + self.tan_half_fov * plane
        d /= np.linalg.norm(d, axis=-1, keepdims=True)
        o = np.broadcast_to(self.eye, d.shape).copy()
        return o, d

    def pixel_angle(self, height: int) -> float:
        """Angle one pixel subtends: a ray's footprint at distance t is t * pixel_angle
        (perspective; see :meth:`footprint`)."""
        return 2.0 * self.tan_half_fov / height

    def footprint(self, t: np.ndarray | float, height: int) -> np.ndarray | float:
        """Width of one pixel at ray parameter t: t * pixel_angle, or constant when orthographic."""
        if self.orthographic:
            return np.zeros_like(np.asarray(t, dtype=float)) + self.ortho_height / height
        return np.asarray(t) * self.pixel_angle(height)

    def project(self, points: np.ndarray, width: int, height: int) -> np.ndarray:
        """Normalised image coordinates (x, y in [-1, 1] inside the image, y up) of (..., 3) points;
        the inverse of rays() (behind a perspective eye: nan)."""
        r, u, f = self.basis()
        rel = np.asarray(points, dtype=float) - self.eye
        x, y, z = rel @ r, rel @ u, rel @ f
        aspect = width / height
        if self.orthographic:
            half = 0.5 * self.ortho_height
            return np.stack([x / (half * aspect), y / half], axis=-1)
        with np.errstate(divide="ignore", invalid="ignore"):
            z = np.where(z > 0, z, np.nan)
            return np.stack([x / (z * self.tan_half_fov * aspect), y / (z * self.tan_half_fov)], axis=-1)

    def __repr__(self) -> str:
        ortho = f", projection='orthographic', ortho_height={self.ortho_height:g}" if self.orthographic else ""
        return f"Camera(eye={tuple(self.eye)}, target={tuple(self.target)}, fov={self.fov:g}{ortho})"


class OrbitCamera(Camera):
    """Camera orbiting ``target`` at ``distance`` (the viewer drives it).

    Args:
        target: the point looked at and orbited.
        distance: eye-to-target distance, > 0.
        yaw: turn about the Y axis, degrees (0 looks along -Z from +Z).
        pitch: lift of the eye above the target's horizontal plane, degrees in [-89.9, 89.9].
        fov: vertical field of view, degrees.
        projection: ``"perspective"`` or ``"orthographic"``, as for :class:`Camera`.
        ortho_height: world height of an orthographic view, as for :class:`Camera`.

    Example:
        >>> cam = sg.OrbitCamera(target=(0, 1, 0), distance=5, yaw=0, pitch=0)
        >>> [round(float(x), 6) for x in cam.eye]
        [0.0, 1.0, 5.0]
    """

    def __init__(self, target: Sequence[float] = (0.0, 0.0, 0.0), distance: float = 5.0,
                 yaw: float = 30.0, pitch: float = 20.0, fov: float = 45.0, projection: str = "perspective",
                 ortho_height: float | None = None) -> None:
        self.distance = v.scalar("OrbitCamera", "distance", distance, positive=True)
        if self.distance > COORD_MAX:
            raise ParameterError(f"OrbitCamera: parameter 'distance' must be at most {COORD_MAX:g}, got {self.distance:g}")
        self.yaw = v.scalar("OrbitCamera", "yaw", yaw)
        self.pitch = v.scalar("OrbitCamera", "pitch", pitch)
        if abs(self.pitch) > 89.9:
            raise ParameterError(f"OrbitCamera: parameter 'pitch' must lie in [-89.9, 89.9], got {self.pitch:g}")
        tgt = v.vector("OrbitCamera", "target", target)
        super().__init__(self._eye(tgt), tgt, UP, fov, projection, ortho_height)

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
        span = self.ortho_height if self.orthographic else 2.0 * self.distance * self.tan_half_fov
        self._move("OrbitCamera.pan", target=self.target + span * (-float(dx) * r + float(dy) * u))

    def zoom(self, factor: float) -> None:
        """Multiply the distance to the target by ``factor`` (> 0), down to 1e-9 and up to 1e29."""
        _finite("OrbitCamera.zoom", factor=factor)
        if not factor > 0:
            raise ParameterError(f"OrbitCamera.zoom: 'factor' must be > 0, got {factor!r}")
        old_height = self._ortho_height
        if old_height is not None:
            self._ortho_height = min(max(old_height * float(factor), 1e-9), COORD_MAX)
        try:
            self._move("OrbitCamera.zoom", distance=min(max(self.distance * float(factor), 1e-9), COORD_MAX))
        except ParameterError:
            self._ortho_height = old_height
            raise

    @classmethod
    def framing(cls, lo: np.ndarray, hi: np.ndarray, yaw: float = 30.0, pitch: float = 20.0,
                fov: float = 45.0, aspect: float = 4 / 3, projection: str = "perspective") -> "OrbitCamera":
        """An orbit camera from (yaw, pitch) that shows every corner of the box [lo, hi] in an
        image of width / height ``aspect`` (infinite sides are ignored), with 5% to spare.

        Perspective: the nearest distance at which each corner lies inside the view
        frustum, |x| <= (d + z) tan(fov/2) aspect and |y| <= (d + z) tan(fov/2) in camera
        coordinates about the box centre. Orthographic: the view height that holds the
        corners' extent, from a distance outside the box."""
        _projection("OrbitCamera.framing", projection, None)
        if not (isinstance(aspect, (int, float)) and 1e-4 <= aspect <= 1e4):
            raise ParameterError(f"OrbitCamera.framing: 'aspect' must be a number in [1e-4, 1e4], got {aspect!r}")
        finite = np.isfinite(lo) & np.isfinite(hi)
        lo_f = np.where(finite, lo, -1.0)
        hi_f = np.where(finite, hi, 1.0)
        centre = (lo_f + hi_f) / 2
        half = np.maximum((hi_f - lo_f) / 2, 1e-6)
        probe = cls(centre, 1.0, yaw, pitch, fov)
        r, u, f = probe.basis()
        corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * half
        x, y, z = np.abs(corners @ r), np.abs(corners @ u), corners @ f
        th = math.tan(math.radians(fov) / 2)
        depth = float(np.max(-z))  # how far the box reaches toward the eye
        if projection == "orthographic":
            height = 2.0 * max(float(np.max(y)), float(np.max(x)) / aspect) * FRAME_MARGIN
            dist = max(depth * FRAME_MARGIN, height / (2.0 * th))
            return cls(centre, dist, yaw, pitch, fov, "orthographic", height)
        need = np.maximum(x / (th * aspect), y / th) * FRAME_MARGIN - z
        dist = max(float(np.max(need)), depth * FRAME_MARGIN, 1e-6)
        return cls(centre, dist, yaw, pitch, fov)

    @classmethod
    def of(cls, camera: Camera | None, lo: np.ndarray, hi: np.ndarray, aspect: float = 1.0) -> "OrbitCamera":
        """An orbit camera showing what ``camera`` shows (a copy of an orbit camera; a look-at
        camera orbits about its target from where it stands), or framing [lo, hi] for an
        image of width / height ``aspect`` if None. The projection is kept."""
        if isinstance(camera, OrbitCamera):
            return cls(camera.target, camera.distance, camera.yaw, camera.pitch, camera.fov, camera.projection,
                       camera._ortho_height)
        if camera is not None:
            off = camera.eye - camera.target
            dist = float(np.linalg.norm(off))
            yaw = math.degrees(math.atan2(off[0], off[2]))
            pitch = math.degrees(math.asin(max(-0.999, min(0.999, off[1] / dist))))
            return cls(camera.target, dist, yaw, pitch, camera.fov, camera.projection, camera._ortho_height)
        return cls.framing(lo, hi, aspect=aspect)

    def __repr__(self) -> str:
        ortho = f", projection='orthographic', ortho_height={self.ortho_height:g}" if self.orthographic else ""
        return (f"OrbitCamera(target={tuple(float(x) for x in self.target)}, distance={self.distance:g}, yaw={self.yaw:g}, "
                f"pitch={self.pitch:g}, fov={self.fov:g}{ortho})")

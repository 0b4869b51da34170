"""The float64 twin of shaders/lib/noise3.glsl: the same integer hash and gradients."""
from __future__ import annotations

import numpy as np

OCTAVE_SHIFT = np.array([17.13, 31.71, 47.37])
# Gradient and value bounds of noise3, derived over every pattern of corner gradients: for a
# point f of the cell, the largest |grad n| over the 8^8 patterns is max over unit u of
# sum_c |A_c(f)^T u|_1 (grad n = sum_c A_c(f) g_c is linear in the corner gradients g_c, and
# each corner picks the sign pattern that best aligns with u). Maximised over f and u, this
# is 37/8, reached at the cell's centre along an axis (each corner adds 37/64); the value's
# largest |n| is 3/2, also at the centre (each corner adds |f - o|_1 / 8). Both are attained,
# so neither can be lowered; tests/test_noise_bounds.py repeats the maximisation.
NOISE_LIPSCHITZ = 37.0 / 8.0
NOISE_MAX = 1.5


def _pcg3d_x(c: np.ndarray) -> np.ndarray:
    v = c.astype(np.int64).astype(np.uint32)
    with np.errstate(over="ignore"):
        v = v * np.uint32(1664525) + np.uint32(1013904223)
        x, y, z = v[..., 0], v[..., 1], v[..., 2]
        x = x + y * z
        y = y + z * x
        z = z + x * y
        x, y, z = x ^ (x >> np.uint32(16)), y ^ (y >> np.uint32(16)), z ^ (z >> np.uint32(16))
        x = x + y * z
        y = y + z * x
        z = z + x * y
    return x


CORNERS = np.array([[dx, dy, dz] for dx in (0, 1) for dy in (0, 1) for dz in (0, 1)], dtype=np.float64)


def noise3(p: np.ndarray) -> np.ndarray:
    """Gradient noise at (..., 3) points (the eight corners hashed in one array)."""
    i = np.floor(p)
    f = p - i
    u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0)
    h = _pcg3d_x(i[..., None, :] + CORNERS)  # (..., 8)
    g = np.stack([(h & 1), (h >> 1) & 1, (h >> 2) & 1], axis=-1).astype(np.float64) * 2.0 - 1.0
    vals = np.sum(g * (f[..., None, :] - CORNERS), axis=-1)  # (..., 8), corner (dx, dy, dz) at 4 dx + 2 dy + dz
    ux, uy, uz = u[..., 0], u[..., 1], u[..., 2]

    def lerp(a: np.ndarray, b: np.ndarray, t: np.ndarray) -> np.ndarray:
        return a + (b - a) * t

    def v(dx: int, dy: int, dz: int) -> np.ndarray:
        return vals[..., 4 * dx + 2 * dy + dz]
    x00, x10 = lerp(v(0, 0, 0), v(1, 0, 0), ux), lerp(v(0, 1, 0), v(1, 1, 0), ux)
    x01, x11 = lerp(v(0, 0, 1), v(1, 0, 1), ux), lerp(v(0, 1, 1), v(1, 1, 1), ux)
    return lerp(lerp(x00, x10, uy), lerp(x01, x11, uy), uz)


def fbm3(p: np.ndarray, octaves: int) -> np.ndarray:
    """Fractal sum of ``octaves`` noise layers (frequency x2, amplitude x0.5 each)."""
    total = np.zeros(p.shape[:-1])
    amp = 1.0
    for o in range(octaves):
        total = total + amp * noise3(p + o * OCTAVE_SHIFT)
        p = p * 2.0
        amp *= 0.5
    return total


def fbm_lipschitz(octaves: int) -> float:
    """Gradient bound of fbm3: each octave adds (2^o)(0.5^o) = 1 times the noise's bound."""
    return NOISE_LIPSCHITZ * max(octaves, 0)


def fbm_max(octaves: int) -> float:
    """Bound of |fbm3|: the octaves' amplitudes 1, 1/2, ... times the noise's bound."""
    return NOISE_MAX * (2.0 - 2.0 ** (1 - max(octaves, 0)))

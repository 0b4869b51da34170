"""Distance to a quadratic Bezier curve: the float64 twin of shaders/lib/sd_bezier.glsl,
shared by the Bezier tube and the text outlines."""
from __future__ import annotations

import numpy as np


def quadratic_distance2(pos: np.ndarray, qa: np.ndarray, qb: np.ndarray, qc: np.ndarray) -> np.ndarray:
    """Squared distances from points pos to quadratic Bezier curves qa qb qc (arrays (..., 2) or (..., 3), broadcast):
    the nearest parameter from Inigo Quilez's closed-form cubic, then two Newton steps,
    the same formula as shaders/lib/sd_bezier.glsl."""
    a = qb - qa
    b = qa - 2.0 * qb + qc
    c = a * 2.0
    d = qa - pos
    kk = 1.0 / np.sum(b * b, axis=-1)
    kx = kk * np.sum(a * b, axis=-1)
    ky = kk * (2.0 * np.sum(a * a, axis=-1) + np.sum(d * b, axis=-1)) / 3.0
    kz = kk * np.sum(d * a, axis=-1)
    p = ky - kx * kx
    q = kx * (2.0 * kx * kx - 3.0 * ky) + kz
    h = q * q + 4.0 * p ** 3

    def dist2(t: np.ndarray) -> np.ndarray:
        for _ in range(2):  # Newton on (B(t) - pos) . B'(t) = 0
            tt = t[..., None]
            e, de = d + (c + b * tt) * tt, c + 2.0 * b * tt
            g = np.sum(e * de, axis=-1)
            dg = np.sum(de * de, axis=-1) + 2.0 * np.sum(e * b, axis=-1)
            t = np.clip(t - np.where(dg > 0, g / np.where(dg > 0, dg, 1.0), 0.0), 0.0, 1.0)
        e = d + (c + b * t[..., None]) * t[..., None]
        return np.sum(e * e, axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        hs = np.sqrt(np.maximum(h, 0.0))
        t1 = np.clip(np.cbrt((hs - q) / 2.0) + np.cbrt((-hs - q) / 2.0) - kx, 0.0, 1.0)
        z = np.sqrt(np.maximum(-p, 0.0))
        den = np.where(p * z != 0, p * z * 2.0, 1.0)
        vv = np.arccos(np.clip(q / den, -1.0, 1.0)) / 3.0
        m, n = np.cos(vv), np.sin(vv) * 1.732050808
        ta = np.clip((m + m) * z - kx, 0.0, 1.0)
        tb = np.clip((-n - m) * z - kx, 0.0, 1.0)
    return np.where(h >= 0.0, dist2(t1), np.minimum(dist2(ta), dist2(tb)))

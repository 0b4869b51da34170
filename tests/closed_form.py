"""Closed-form ray intersections: ground truth written independently of sdfgl.reference.

Boxes (oriented, given centre, half sizes and a rotation matrix whose columns are the
box axes in world space), spheres and planes. Every function takes float64 rays (N, 3)
and returns (t, normal): t = inf where the ray misses, the unit outward normal of the
face hit (0 on a miss).
"""
from __future__ import annotations

import numpy as np


def rotation(deg: float, axis) -> np.ndarray:
    """Rodrigues rotation matrix (degrees, right-handed about ``axis``)."""
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    th = np.radians(deg)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + np.sin(th) * k + (1 - np.cos(th)) * (k @ k)


def box(o: np.ndarray, d: np.ndarray, centre, half, rot: np.ndarray | None = None):
    """First entry of rays into an oriented box (slab method in the box frame)."""
    r = np.eye(3) if rot is None else rot
    lo_o = (o - np.asarray(centre, dtype=float)) @ r  # ray in box coordinates
    lo_d = d @ r
    half = np.asarray(half, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        t0 = (-half - lo_o) / lo_d
        t1 = (half - lo_o) / lo_d
    tn = np.minimum(t0, t1)
    tf = np.maximum(t0, t1)
    tn = np.where(np.isnan(tn), -np.inf, tn)
    tf = np.where(np.isnan(tf), np.inf, tf)
    t_enter = tn.max(axis=1)
    t_exit = tf.min(axis=1)
    hit = (t_enter <= t_exit) & (t_enter > 0)
    axis = tn.argmax(axis=1)
    n_local = np.zeros_like(o)
    n_local[np.arange(len(o)), axis] = -np.sign(lo_d[np.arange(len(o)), axis])
    n = n_local @ r.T
    return np.where(hit, t_enter, np.inf), np.where(hit[:, None], n, 0.0)


def sphere(o: np.ndarray, d: np.ndarray, centre, radius: float):
    """First entry of rays into a sphere (the near root, without cancellation)."""
    oc = o - np.asarray(centre, dtype=float)
    b = np.sum(oc * d, axis=1)
    c = np.sum(oc * oc, axis=1) - radius * radius
    disc = b * b - c
    ok = (disc >= 0) & (b < 0) & (c > 0)
    t = np.where(ok, c / (-b + np.sqrt(np.maximum(disc, 0))), np.inf)
    p = o + d * np.where(ok, t, 0)[:, None]
    n = (p - np.asarray(centre, dtype=float)) / radius
    return t, np.where(ok[:, None], n, 0.0)


def first(*hits):
    """The nearest of several (t, normal) results."""
    ts = np.stack([h[0] for h in hits])
    k = ts.argmin(axis=0)
    idx = np.arange(ts.shape[1])
    return ts[k, idx], np.stack([h[1] for h in hits])[k, idx]

"""Mitsuba 3 as an optional back end: import it with a clear message, pick a variant that works.

The LLVM variants are faster, but on some machines (llvmpipe's LLVM on this project's
CI, for one) Dr.Jit's code generation aborts the whole process. A variant is therefore
tried in a child process first; the parent only switches to it when the child rendered
a small SDF-grid scene and exited cleanly. The scalar RGB variant is the fallback.
``SDFGL_MITSUBA_VARIANT`` forces a variant (no probe). The outcome is remembered per
Mitsuba version and Python executable in ``$XDG_CACHE_HOME/sdfgl/mitsuba-variant.json``
(the probe costs a few seconds), when that directory is writable.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from types import ModuleType

from ..errors import SdfglError

PREFERRED = ("llvm_ad_rgb", "scalar_rgb")
FALLBACK = "scalar_rgb"
PROBE_TIMEOUT_S = 90.0

_PROBE = """
import numpy as np, mitsuba as mi
mi.set_variant({variant!r})
g = np.linspace(-1, 1, 8)
z, y, x = np.meshgrid(g, g, g, indexing="ij")
grid = (np.sqrt(x * x + y * y + z * z) - 0.7).astype(np.float32)[..., None]
scene = mi.load_dict({{"type": "scene", "integrator": {{"type": "path"}},
    "sensor": {{"type": "perspective", "film": {{"type": "hdrfilm", "width": 8, "height": 8}},
               "to_world": mi.ScalarTransform4f().look_at(origin=[0.5, 0.5, 3], target=[0.5, 0.5, 0.5], up=[0, 1, 0])}},
    "shape": {{"type": "sdfgrid", "grid": mi.TensorXf(grid)}}, "light": {{"type": "constant"}}}})
img = np.array(mi.render(scene, spp=2))
assert img.shape[:2] == (8, 8) and np.isfinite(img).all()
print("sdfgl-probe-ok")
"""

_chosen: dict[str, object] = {}


class MitsubaMissing(SdfglError):
    """Mitsuba 3 is not installed."""


def import_mitsuba() -> ModuleType:
    """The ``mitsuba`` module, or an error that says how to install it."""
    try:
        import mitsuba
    except ImportError as exc:
        raise MitsubaMissing(
            "physically based rendering needs Mitsuba 3, which is not installed: "
            "pip install 'sdfgl[pbr]' (or pip install mitsuba)") from exc
    return mitsuba


def variant_works(variant: str, timeout: float = PROBE_TIMEOUT_S) -> tuple[bool, str]:
    """Render a tiny SDF grid with ``variant`` in a child process; (worked, why not)."""
    try:
        out = subprocess.run([sys.executable, "-c", _PROBE.format(variant=variant)], capture_output=True,
                             text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return False, f"{variant}: the probe render did not finish in {timeout:g} s"
    if out.returncode == 0 and "sdfgl-probe-ok" in out.stdout:
        return True, ""
    last = (out.stderr.strip().splitlines() or [f"exit status {out.returncode}"])[0][:200]
    return False, f"{variant}: the probe render failed ({last})"


def _cache_file() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "sdfgl" / "mitsuba-variant.json"


def _cache_key(mi: ModuleType) -> str:
    return f"{getattr(mi, '__version__', '?')}|{sys.executable}"


def _read_cache(key: str) -> tuple[str, str] | None:
    try:
        entry = json.loads(_cache_file().read_text(encoding="utf-8")).get(key)
    except (OSError, ValueError, AttributeError):
        return None
    return (entry[0], entry[1]) if isinstance(entry, list) and len(entry) == 2 else None


def _write_cache(key: str, variant: str, how: str) -> None:
    path = _cache_file()
    try:
        data = json.loads(path.read_text(encoding="utf-8")) if path.is_file() else {}
        data = data if isinstance(data, dict) else {}
        data[key] = [variant, how]
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(json.dumps(data), encoding="utf-8")
        tmp.replace(path)
    except (OSError, ValueError):
        pass  # an unwritable cache only costs the probe next time


def _probe(mi: ModuleType) -> tuple[str, str]:
    notes = []
    for cand in PREFERRED:
        if cand not in mi.variants():
            notes.append(f"{cand}: not in this Mitsuba build")
            continue
        ok, why = (True, "") if cand == FALLBACK else variant_works(cand)
        if ok:
            return cand, "automatic" + (f" ({'; '.join(notes)})" if notes else "")
        notes.append(why)
    return FALLBACK, "automatic (" + "; ".join(notes) + ")"


def mitsuba(variant: str | None = None) -> tuple[ModuleType, str, str]:
    """Mitsuba with a working variant set: (module, variant, how it was chosen).

    ``variant`` None picks automatically (``SDFGL_MITSUBA_VARIANT``, else the first of
    ``PREFERRED`` whose probe renders); the choice is made once per process.
    """
    mi = import_mitsuba()
    if variant is None:
        variant = os.environ.get("SDFGL_MITSUBA_VARIANT") or None
        how = "set by SDFGL_MITSUBA_VARIANT"
    else:
        how = "asked for"
    if variant is None:
        if "variant" not in _chosen:
            key = _cache_key(mi)
            cached = _read_cache(key)
            if cached is None:
                cached = _probe(mi)
                _write_cache(key, *cached)
            _chosen["variant"], _chosen["how"] = cached
        variant, how = str(_chosen["variant"]), str(_chosen["how"])
    if variant not in mi.variants():
        raise SdfglError(f"pbr: Mitsuba variant {variant!r} is not available; this build has {', '.join(mi.variants())}")
    if mi.variant() != variant:
        mi.set_variant(variant)
    return mi, variant, how

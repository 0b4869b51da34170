"""Batch job files: JSON that lists render jobs, with sweeps and random cameras expanded here.

The format is documented in docs/batch-format.md. ``load_jobs(path)`` validates the file
(every error names the JSON path and what was wrong) and returns concrete ``Job``s in a
fixed order; random values come from ``seed`` and the entry's position, so the same file
always gives the same jobs, whatever the number of workers.
"""
from __future__ import annotations

import itertools
import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import SdfglError

CHANNELS = ("depth", "normal", "steps")
ORBIT_KEYS = {"target", "distance", "yaw", "pitch", "fov"}
LOOK_KEYS = {"eye", "target", "up", "fov"}
TOP_KEYS = {"jobs", "defaults", "seed", "version", "allow_outside"}
JOB_KEYS = {"scene", "camera", "size", "settings", "params", "time", "output", "data", "channels", "count",
            "sweep", "seed"}
MAX_JOBS = 1_000_000  # jobs one file may expand into (count times the sweep's combinations, over all entries)
_FIELD = re.compile(r"\{([A-Za-z_][\w.]*)(?::([^{}]*))?\}")


class JobFileError(SdfglError):
    """A job file that cannot be read or does not follow docs/batch-format.md."""


@dataclass
class Job:
    """One image to render (all paths absolute, all values concrete)."""

    index: int
    label: str                           # e.g. "jobs[2] #5": where it came from, for messages
    scene: str
    size: tuple[int, int] = (640, 480)
    camera: dict[str, Any] | None = None  # OrbitCamera or look-at keys; None: the scene file's camera
    settings: dict[str, Any] = field(default_factory=dict)
    params: dict[str, Any] = field(default_factory=dict)
    time: float | None = None
    output: str | None = None            # colour PNG
    data: str | None = None              # .npz with the channels
    channels: tuple[str, ...] = CHANNELS

    @property
    def outputs(self) -> list[str]:
        return [p for p in (self.output, self.data) if p]


def _err(where: str, msg: str) -> JobFileError:
    return JobFileError(f"job file: {where}: {msg}")


def _number(x: Any, where: str) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x):
        raise _err(where, f"must be a finite number, got {json.dumps(x)}")
    return float(x)


def _sample(spec: Any, where: str, rng: np.random.Generator) -> Any:
    """A concrete value: numbers and lists pass; {"uniform": [a, b]}, {"sphere": [a, b]} (pitch, area-uniform)
    and {"choice": [...]} draw from ``rng``."""
    if not isinstance(spec, dict):
        return spec
    if len(spec) != 1:
        raise _err(where, f"a random value is one of {{\"uniform\": [lo, hi]}}, {{\"sphere\": [lo, hi]}}, "
                          f"{{\"choice\": [...]}}; got {json.dumps(spec)}")
    (kind, arg), = spec.items()
    if kind == "choice":
        if not isinstance(arg, list) or not arg:
            raise _err(f"{where}.choice", "must be a non-empty list")
        return arg[int(rng.integers(len(arg)))]
    if kind not in ("uniform", "sphere"):
        raise _err(where, f"unknown random value '{kind}' (uniform, sphere or choice)")
    if not isinstance(arg, list) or len(arg) != 2:
        raise _err(f"{where}.{kind}", f"must be [lo, hi], got {json.dumps(arg)}")
    lo, hi = (_number(x, f"{where}.{kind}[{i}]") for i, x in enumerate(arg))
    if lo > hi:
        raise _err(f"{where}.{kind}", f"lo ({lo:g}) must not exceed hi ({hi:g})")
    if kind == "uniform":
        return float(rng.uniform(lo, hi))
    if not -90 <= lo <= hi <= 90:
        raise _err(f"{where}.sphere", "takes pitch limits in degrees within [-90, 90]")
    s = rng.uniform(math.sin(math.radians(lo)), math.sin(math.radians(hi)))  # uniform over the sphere's area
    return math.degrees(math.asin(s))


def _vec(x: Any, where: str) -> list[float]:
    if not isinstance(x, list) or len(x) != 3:
        raise _err(where, f"must be 3 numbers, got {json.dumps(x)}")
    return [_number(c, f"{where}[{i}]") for i, c in enumerate(x)]


def _camera(spec: Any, where: str, rng: np.random.Generator) -> dict[str, Any] | None:
    if spec is None:
        return None
    if not isinstance(spec, dict):
        raise _err(where, f"must be an object of OrbitCamera keys ({', '.join(sorted(ORBIT_KEYS))}) or look-at "
                          f"keys ({', '.join(sorted(LOOK_KEYS))}), got {json.dumps(spec)}")
    keys = set(spec)
    allowed = LOOK_KEYS if "eye" in keys else ORBIT_KEYS
    if keys - allowed:
        raise _err(where, f"unknown camera key(s) {sorted(keys - allowed)}; "
                          f"{'look-at' if 'eye' in keys else 'orbit'} cameras take {sorted(allowed)}")
    out: dict[str, Any] = {}
    for k, val in spec.items():
        w = f"{where}.{k}"
        val = _sample(val, w, rng)
        if k in ("target", "distance") and val == "auto":
            out[k] = "auto"
        elif k in ("eye", "target", "up"):
            out[k] = _vec(val, w)
        else:
            out[k] = _number(val, w)
    return out


def _size(x: Any, where: str) -> tuple[int, int]:
    if (not isinstance(x, list) or len(x) != 2 or any(isinstance(c, bool) or not isinstance(c, int) for c in x)
            or not all(1 <= c <= 16384 for c in x)):
        raise _err(where, f"must be [width, height], two integers in 1..16384, got {json.dumps(x)}")
    return int(x[0]), int(x[1])


def _fill(pattern: Any, where: str, values: dict[str, Any]) -> str:
    """``pattern`` with {name} / {name:spec} fields from ``values`` (index, job, and sweep keys)."""
    if not isinstance(pattern, str) or not pattern:
        raise _err(where, f"must be a file path, got {json.dumps(pattern)}")

    def sub(m: re.Match) -> str:
        name, spec = m.group(1), m.group(2) or ""
        if name not in values:
            raise _err(where, f"unknown field '{{{name}}}' in '{pattern}' (known: {', '.join(sorted(values))})")
        try:
            return format(values[name], spec)
        except (ValueError, TypeError) as exc:
            raise _err(where, f"field '{{{m.group(0)[1:-1]}}}': {exc}") from None
    return _FIELD.sub(sub, pattern)


def _merge(defaults: dict[str, Any], entry: dict[str, Any]) -> dict[str, Any]:
    out = dict(defaults)
    for k, val in entry.items():
        if k in ("camera", "settings", "params") and isinstance(val, dict) and isinstance(out.get(k), dict):
            out[k] = {**out[k], **val}
        else:
            out[k] = val
    return out


def _set_path(job: dict[str, Any], key: str, value: Any, where: str) -> None:
    """Apply one sweep value: "camera.yaw", "params.radius", "settings.aa", "time" or "size"."""
    head, _, tail = key.partition(".")
    if head in ("camera", "params", "settings") and tail:
        job[head] = {**(job.get(head) or {}), tail: value}
    elif head in ("time", "size", "scene") and not tail:
        job[head] = value
    else:
        raise _err(where, f"cannot sweep '{key}': use camera.KEY, params.NAME, settings.KEY, time, size or scene")


def _expand(entry: dict[str, Any], where: str, base: Path, seed: int, position: int, first: int) -> list[Job]:
    unknown = set(entry) - JOB_KEYS
    if unknown:
        raise _err(where, f"unknown key(s) {sorted(unknown)}; a job takes {sorted(JOB_KEYS)}")
    count = entry.get("count", 1)
    if isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise _err(f"{where}.count", f"must be a positive integer, got {json.dumps(count)}")
    sweep = entry.get("sweep", {})
    if not isinstance(sweep, dict) or any(not isinstance(vals, list) or not vals for vals in sweep.values()):
        raise _err(f"{where}.sweep", "must map a key (camera.yaw, params.NAME, time, ...) to a non-empty list")
    if "seed" in entry and (isinstance(entry["seed"], bool) or not isinstance(entry["seed"], int) or entry["seed"] < 0):
        raise _err(f"{where}.seed", f"must be a non-negative integer, got {json.dumps(entry['seed'])}")
    total = count * math.prod(len(vals) for vals in sweep.values())
    if first + total > MAX_JOBS:
        raise _err(where, f"expands into {total} jobs (count {count} x {total // count} sweep combinations); "
                          f"a file may hold at most {MAX_JOBS}")
    rng = np.random.default_rng([int(entry.get("seed", seed)), position])
    combos = [dict(zip(sweep, c)) for c in itertools.product(*sweep.values())]
    jobs = []
    for k in range(count):
        for combo in combos:
            j = dict(entry)
            for key, val in combo.items():
                _set_path(j, key, val, f"{where}.sweep.{key}")
            n = len(jobs)
            jw = f"{where}" + (f" #{n}" if count * len(combos) > 1 else "")
            fields = {"index": n, "job": first + n, "repeat": k,
                      **{key: (v if not isinstance(v, (list, dict)) else json.dumps(v)) for key, v in combo.items()}}
            jobs.append(_concrete(j, jw, base, rng, fields, first + n))
    return jobs


def _concrete(j: dict[str, Any], where: str, base: Path, rng: np.random.Generator, fields: dict[str, Any],
              index: int) -> Job:
    scene = j.get("scene")
    if not isinstance(scene, str) or not scene:
        raise _err(f"{where}.scene", f"must be the path of a scene file, got {json.dumps(scene)}")
    out, data = j.get("output"), j.get("data")
    if out is None and data is None:
        raise _err(where, "needs 'output' (a colour PNG) or 'data' (an .npz of depth/normal/steps), or both")
    output = str(base / _fill(out, f"{where}.output", fields)) if out is not None else None
    if output and not output.lower().endswith(".png"):
        raise _err(f"{where}.output", f"the colour image is written as PNG: use a .png name, got '{out}'")
    datap = str(base / _fill(data, f"{where}.data", fields)) if data is not None else None
    if datap and not datap.lower().endswith(".npz"):
        raise _err(f"{where}.data", f"depth/normal/steps are written as .npz: use a .npz name, got '{data}'")
    channels = j.get("channels", list(CHANNELS))
    if not isinstance(channels, list) or not channels or any(c not in CHANNELS for c in channels):
        raise _err(f"{where}.channels", f"must be a non-empty list of {list(CHANNELS)}, got {json.dumps(channels)}")
    settings = j.get("settings", {})
    if not isinstance(settings, dict):
        raise _err(f"{where}.settings", f"must be an object of render settings, got {json.dumps(settings)}")
    if "outputs" in settings:
        raise _err(f"{where}.settings.outputs", "is chosen by 'output', 'data' and 'channels'")
    params = j.get("params", {})
    if not isinstance(params, dict):
        raise _err(f"{where}.params", f"must map parameter names to values, got {json.dumps(params)}")
    params = {name: _sample(val, f"{where}.params.{name}", rng) for name, val in params.items()}
    t = j.get("time")
    return Job(index=index, label=where, scene=str(base / scene),
               size=_size(j.get("size", [640, 480]), f"{where}.size"),
               camera=_camera(j.get("camera"), f"{where}.camera", rng), settings=dict(settings), params=params,
               time=None if t is None else _number(_sample(t, f"{where}.time", rng), f"{where}.time"),
               output=output, data=datap, channels=tuple(channels))


def parse_jobs(doc: Any, base: Path, allow_outside: bool = False) -> list[Job]:
    """Concrete jobs from a parsed job document; relative paths are taken from ``base``.

    An output outside ``base`` (an absolute path, or one through ``..``) is refused unless
    ``allow_outside`` or the document's ``"allow_outside": true`` permits it."""
    if not isinstance(doc, dict):
        raise _err("(top)", "must be an object with a 'jobs' list")
    unknown = set(doc) - TOP_KEYS
    if unknown:
        raise _err("(top)", f"unknown key(s) {sorted(unknown)}; the file takes {', '.join(sorted(TOP_KEYS))}")
    if not isinstance(doc.get("allow_outside", False), bool):
        raise _err("allow_outside", f"must be true or false, got {json.dumps(doc['allow_outside'])}")
    allow_outside = allow_outside or doc.get("allow_outside", False)
    entries = doc.get("jobs")
    if not isinstance(entries, list) or not entries:
        raise _err("jobs", "must be a non-empty list")
    defaults = doc.get("defaults", {})
    if not isinstance(defaults, dict):
        raise _err("defaults", "must be an object of job keys")
    seed = doc.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise _err("seed", f"must be a non-negative integer, got {json.dumps(seed)}")
    jobs: list[Job] = []
    for i, entry in enumerate(entries):
        if not isinstance(entry, dict):
            raise _err(f"jobs[{i}]", f"must be an object, got {json.dumps(entry)}")
        jobs += _expand(_merge(defaults, entry), f"jobs[{i}]", base, seed, i, len(jobs))
    seen: dict[str, str] = {}
    for job in jobs:
        for p in job.outputs:
            if p in seen:
                raise _err(job.label, f"writes '{p}', which {seen[p]} writes too")
            seen[p] = job.label
            if not allow_outside:
                check_inside(p, base, job.label)
    return jobs


def check_inside(path: str, base: Path, label: str) -> None:
    """Refuse an output ``path`` that lies outside the folder ``base`` (links followed)."""
    folder = Path(base).resolve()
    if not Path(path).resolve().is_relative_to(folder):
        raise _err(label, f"writes '{path}', outside the job file's folder '{folder}'; set \"allow_outside\": true "
                          f"in the file (or pass --allow-outside) to allow it")


def load_jobs(path: str | Path, allow_outside: bool = False) -> list[Job]:
    """Read and expand the job file at ``path`` (paths inside are relative to its folder;
    outputs outside it only with ``allow_outside`` or the file's ``"allow_outside": true``)."""
    p = Path(path)
    try:
        doc = json.loads(p.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise JobFileError(f"job file '{p}' does not exist") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise JobFileError(f"cannot read job file '{p}': {exc}") from None
    except json.JSONDecodeError as exc:
        raise JobFileError(f"job file '{p}', line {exc.lineno}, column {exc.colno}: {exc.msg}") from None
    try:
        return parse_jobs(doc, p.resolve().parent, allow_outside)
    except JobFileError as exc:
        raise JobFileError(str(exc).replace("job file:", f"job file '{p}':", 1)) from None

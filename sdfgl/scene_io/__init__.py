"""Scenes as data: versioned JSON documents (docs/scene-format.md).

    sg.save_scene(scene, "s.json", camera=cam, settings={"aa": 2})
    doc = sg.load_scene("s.json")        # .scene, .camera, .settings, .params
    d = scene.to_dict(); same = sg.from_dict(d)

Loading runs no code: JSON is parsed after a size and nesting check, nodes are built by
calling registered node classes (:mod:`sdfgl.nodes.record`) with checked values, and
expression strings go through the safe parser (:mod:`sdfgl.expr`). A bad document raises
one :class:`~sdfgl.errors.SceneDocumentError` naming the JSON path at fault. A saved scene
loads back to the same generated GLSL, byte for byte.
"""
from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import SceneDocumentError, SdfglError
from ..files import write_text_atomically
from .decode import Document, from_document
from .encode import to_document
from .limits import FORMAT, MAX_ARRAY, MAX_BYTES, MAX_NESTING, MAX_NODES, MAX_PARAMS, VERSION

__all__ = ["save_scene", "load_scene", "to_dict", "from_dict", "dumps", "loads", "Document",
           "FORMAT", "VERSION", "MAX_BYTES", "MAX_NESTING", "MAX_NODES", "MAX_ARRAY", "MAX_PARAMS"]

_STRING = re.compile(rb'"(?:[^"\\]|\\.)*"', re.S)


def to_dict(scene: Any, camera: Any = None, settings: dict[str, Any] | None = None,
            base: str | Path | None = None) -> dict[str, Any]:
    """The scene (and optionally camera and render settings) as a JSON-ready document dict;
    mesh files inside folder ``base`` are referenced relative to it (else by absolute path)."""
    return to_document(scene, camera, settings, None if base is None else Path(base))


def from_dict(doc: Any, base: str | Path | None = None) -> Any:
    """The scene node of a document dict (as :meth:`Node.to_dict` or ``json.load`` gives it).

    Args:
        doc: the document dict.
        base: the folder relative mesh files are read from (None: the working directory).

    Use :func:`load_scene` (or :func:`loads`) for the camera, settings and parameters too.

    Example:
        >>> s = sg.sphere(1).translate((0, 1, 0))
        >>> sg.compile(sg.from_dict(s.to_dict())) == sg.compile(s)
        True
    """
    return from_document(doc, None if base is None else Path(base)).scene


def dumps(scene: Any, camera: Any = None, settings: dict[str, Any] | None = None, indent: int | None = 1,
          base: str | Path | None = None) -> str:
    """The document as JSON text; mesh files inside folder ``base`` are referenced relative to it."""
    text = json.dumps(to_document(scene, camera, settings, None if base is None else Path(base)), indent=indent,
                      allow_nan=False)
    if len(text.encode()) > MAX_BYTES:
        raise SceneDocumentError(f"(document): {len(text.encode())} bytes, over the limit of {MAX_BYTES} a document "
                                 f"is loaded within; save large meshes to files and build them with sg.load_mesh")
    return text


def _check_nesting(raw: bytes) -> None:
    """Refuse JSON nested deeper than MAX_NESTING before the (recursive) JSON parser sees it."""
    stripped = _STRING.sub(b'""', raw)
    arr = np.frombuffer(stripped, dtype=np.uint8)
    step = (np.isin(arr, (ord("["), ord("{"))).astype(np.int32) - np.isin(arr, (ord("]"), ord("}"))))
    if step.size and int(np.cumsum(step).max()) > MAX_NESTING:
        raise SceneDocumentError(f"(document): nested deeper than {MAX_NESTING} levels (the limit); deep scenes are "
                                 f"written with a 'nodes' table, which keeps documents shallow")


def loads(text: str | bytes, base: str | Path | None = None) -> Document:
    """Parse a JSON document (within the size and nesting limits) and decode it; relative mesh
    files are read from folder ``base`` (None: the working directory)."""
    raw = text.encode() if isinstance(text, str) else bytes(text)
    if len(raw) > MAX_BYTES:
        raise SceneDocumentError(f"(document): {len(raw)} bytes (limit {MAX_BYTES})")
    _check_nesting(raw)
    try:
        doc = json.loads(raw, parse_constant=_no_constant)
    except json.JSONDecodeError as exc:
        raise SceneDocumentError(f"(document): not valid JSON: {exc.msg} at line {exc.lineno}, column {exc.colno}") \
            from None
    except UnicodeDecodeError as exc:
        raise SceneDocumentError(f"(document): not UTF-8 text: {exc.reason} at byte {exc.start}") from None
    except RecursionError:  # pragma: no cover - _check_nesting keeps the parser far from it
        raise SceneDocumentError(f"(document): nested too deeply (limit {MAX_NESTING})") from None
    return from_document(doc, None if base is None else Path(base))


def _no_constant(name: str) -> Any:
    raise SceneDocumentError(f"(document): {name} is not allowed; write infinity as {{\"float\": \"inf\"}}")


def save_scene(scene: Any, path: str | Path, camera: Any = None, settings: dict[str, Any] | None = None) -> Path:
    """Write ``scene`` (and optionally ``camera`` and render ``settings``) as a JSON document.

    Args:
        scene: the scene node; every node kind can be saved (see docs/scene-format.md).
        path: the file to write (conventionally ``.json``).
        camera: an :class:`OrbitCamera` or look-at :class:`Camera`, or None.
        settings: render settings (validated now), e.g. ``{"method": "newton"}``.

    Returns the path. Loading it back gives the same generated GLSL, byte for byte. A mesh
    node read from a file is saved as a reference to it (relative to the document's folder
    when it lies in it or below), with the file's SHA-256; one built from a trimesh is saved
    with its triangles (see docs/scene-format.md).

    Example:
        >>> import tempfile, pathlib
        >>> path = pathlib.Path(tempfile.mkdtemp()) / "s.json"
        >>> _ = sg.save_scene(sg.sphere(1) | sg.box(1.5), path, settings={"aa": 2})
        >>> doc = sg.load_scene(path)
        >>> doc.settings, sg.compile(doc.scene) == sg.compile(sg.sphere(1) | sg.box(1.5))
        ({'aa': 2}, True)
    """
    path = Path(path)
    text = dumps(scene, camera, settings, base=path.parent)
    return write_text_atomically(path, text + "\n", "scene document")


def load_scene(path: str | Path) -> Document:
    """Read a JSON scene document; no code in it runs.

    Args:
        path: the document file.

    Returns a :class:`Document`: ``.scene``, ``.camera`` (or None), ``.settings`` (a dict
    for ``render(**settings)``) and ``.params`` (name -> live parameter, to animate or drive
    sliders). Mesh nodes' files are read relative to the document's folder and must not have
    changed since it was saved. A malformed document raises one :class:`~sdfgl.errors.SceneDocumentError`
    naming the file and the JSON path, e.g. ``scene.children[2]: sphere: parameter 'radius'
    must be a number, got str 'x'``. Limits: MAX_BYTES, MAX_NESTING, MAX_NODES, MAX_ARRAY.

    Example:
        >>> import json, tempfile, pathlib
        >>> path = pathlib.Path(tempfile.mkdtemp()) / "bad.json"
        >>> _ = path.write_text(json.dumps({"format": "sdfgl-scene", "version": 1,
        ...                                 "scene": {"kind": "sphere", "radius": "x"}}))
        >>> try:
        ...     sg.load_scene(path)
        ... except sg.SceneDocumentError as exc:
        ...     print(str(exc).split("': ")[1])
        scene: sphere: parameter 'radius' must be a number, got str 'x'
    """
    p = Path(path)
    try:
        size = p.stat().st_size
        if size > MAX_BYTES:
            raise SceneDocumentError(f"{size} bytes (limit {MAX_BYTES})")
        raw = p.read_bytes()
    except FileNotFoundError:
        raise SceneDocumentError(f"scene document '{p}' does not exist") from None
    except OSError as exc:
        raise SceneDocumentError(f"cannot read scene document '{p}': {exc}") from None
    except SceneDocumentError as exc:
        raise SceneDocumentError(f"scene document '{p}': {exc}") from None
    try:
        return loads(raw, base=p.parent)
    except SceneDocumentError as exc:
        raise SceneDocumentError(f"scene document '{p}': {exc}") from None

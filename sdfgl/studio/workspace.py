"""What a studio page edits: one scene document, its compiled browser view, its file.

The document (a dict in the versioned JSON format) is decoded by :mod:`sdfgl.scene_io`
and compiled by the same ``build`` as the one-file HTML view (:mod:`sdfgl.web.spec`), so
the page draws the same WebGL2 shaders. Compiles are counted (:attr:`Workspace.compiles`):
moving a live parameter changes only its value and never recompiles. The only file a
workspace reads or writes is the document it was opened with.
"""
from __future__ import annotations

import json
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import ParameterError, SceneDocumentError, SdfglError
from ..files import write_text_atomically
from ..scene_io import FORMAT, VERSION, load_scene
from ..scene_io.decode import Document, from_document

EMPTY: dict[str, Any] = {"format": FORMAT, "version": VERSION, "scene": {"kind": "sphere", "radius": 1.0}}
"""The document a studio opened on no file (or on a file that does not exist yet) starts with."""
PREVIEW_SIZE = (120, 80)  # a node's own preview, in pixels
PREVIEW_SLAB = 0.1        # a 2D shape's preview: the shape extruded this thick (scene units)
EXPORTS = ("png", "html", "stl", "3mf", "mp4")
TURNTABLE_S = 4.0  # the length of the exported MP4: one turn about the scene
"""The formats the page's export buttons ask for."""
PARAMETRIC_TIMEOUT_S = 20.0  # the longest a parametric surface of the primitives panel may take to implicitize


@dataclass
class CompileError:
    """A document the decoder or compiler refused: the JSON path at fault and the message."""

    path: str
    message: str

    def to_json(self) -> dict[str, Any]:
        """The error as the page receives it."""
        return {"type": "error", "path": self.path, "message": self.message}


def error_of(exc: SdfglError) -> CompileError:
    """The :class:`CompileError` of an exception (a document error's text starts with its JSON path)."""
    text = str(exc)
    if isinstance(exc, SceneDocumentError) and ": " in text:
        path, _, rest = text.partition(": ")
        if " " not in path or path == "(document)":
            return CompileError(path, rest)
    return CompileError("", text)


def _bounds(kind: str, bounds: Any) -> Any:
    """The panel's bounds (two corners of 3 numbers, or None) as tuples."""
    try:
        return None if bounds is None else tuple(tuple(float(v) for v in corner) for corner in bounds)
    except (TypeError, ValueError):
        raise ParameterError(f"{kind}: bounds must be two corners of 3 numbers, got {bounds!r}") from None


class Workspace:
    """One edited document: the last document that compiled, its view spec, the file it saves to."""

    def __init__(self, path: str | Path | None = None, doc: dict[str, Any] | None = None,
                 size: tuple[int, int] = (640, 400)) -> None:
        self.path = Path(path) if path is not None else None
        if doc is None and self.path is not None and self.path.exists():
            load_scene(self.path)  # refuse a bad file now, with its JSON path
            doc = json.loads(self.path.read_text(encoding="utf-8"))
        self.doc: dict[str, Any] = doc if doc is not None else json.loads(json.dumps(EMPTY))
        self.size = size
        self.compiles = 0
        self.preview_compiles = 0  # node previews compiled (a slider move compiles none)
        self.document: Document = from_document(self.doc)  # decoded, not compiled: the page asks for that
        self._lock = threading.Lock()

    def compile(self, doc: dict[str, Any]) -> dict[str, Any]:
        """Decode and compile ``doc``; on success it becomes the workspace's document and the
        page's view spec is returned. Raises :class:`SdfglError` (the last good one stays)."""
        from ..web.spec import build
        document = from_document(doc)
        spec, _ = build(document.scene, document.camera, self.size, **document.settings)
        with self._lock:
            self.compiles += 1
            self.doc = json.loads(json.dumps(doc))
            self.document = document
        return spec

    def set_values(self, values: dict[str, Any]) -> None:
        """Set live parameters by name (a slider moved): the document and the compiled scene
        take the values; nothing is recompiled."""
        with self._lock:
            table = self.doc.get("params", {})
            for name, value in values.items():
                if name not in table:
                    raise ParameterError(f"studio: no live parameter named {name!r} in the document")
                if name in self.document.params:
                    self.document.params[name].value = value
                table[name]["value"] = value

    def save(self, doc: dict[str, Any] | None = None) -> Path:
        """Write the document (after checking it decodes) to the file the workspace was opened on."""
        if self.path is None:
            raise SdfglError("this studio was started without a file: run `sdfgl studio FILE.json` to save")
        doc = self.doc if doc is None else doc
        from_document(doc)
        return write_text_atomically(self.path, json.dumps(doc, indent=1, allow_nan=False) + "\n", "scene document")

    def python(self) -> str:
        """The document as Python code (see :mod:`sdfgl.studio.python_code`)."""
        from .python_code import to_python
        return to_python(self.doc)

    @staticmethod
    def parametric(x: str, y: str, z: str, bounds: Any = None, timeout: float = PARAMETRIC_TIMEOUT_S) -> dict[str, Any]:
        """The document node of the rational parametric surface (x, y, z)(s, t): implicitized by
        :func:`sdfgl.parametric` (a Groebner basis, in a subprocess with ``timeout``), so the
        page gets an ``implicit`` node like the built-ins."""
        return Workspace.primitive("parametric", {"x": x, "y": y, "z": z, "bounds": bounds}, None, timeout)["node"]

    @staticmethod
    def primitive(kind: str, fields: Any, declarations: Any = None,
                  timeout: float = PARAMETRIC_TIMEOUT_S) -> dict[str, Any]:
        """A primitive of the page's panel as a document node: ``kind`` "implicit" (fields
        ``expr``, ``bounds``), "parametric" (``x``, ``y``, ``z``, ``bounds``: implicitized into an
        ``implicit`` node) or "glsl" (``code``, ``bounds``, ``lipschitz``, ``exact``,
        ``implicit``), with the named parameters ``declarations`` declares (one ``name =
        default in [lo, hi]`` a line, :func:`sdfgl.nodes.named_params.parse_declarations`),
        each a live parameter. The node is built, so everything is checked here. Returns
        {"node": the node's document object, "params": its parameter table}."""
        from ..nodes.implicit import implicit, parametric
        from ..nodes.named_params import parse_declarations
        from ..nodes.user_glsl import glsl
        from ..params import Param
        from ..scene_io import to_dict
        if kind not in ("implicit", "parametric", "glsl"):
            raise ParameterError(f"primitive: kind must be implicit, parametric or glsl, got {kind!r}")
        if not isinstance(fields, dict):
            raise ParameterError(f"{kind}: the fields must be an object, got {type(fields).__name__}")
        params = [[n, Param(value, n, rng)] for n, value, rng in parse_declarations(declarations, kind, kind == "glsl")]
        text = {"implicit": ("expr",), "parametric": ("x", "y", "z"), "glsl": ("code",)}[kind]
        for name in text:
            if not isinstance(fields.get(name), str):
                raise ParameterError(f"{kind}: {name} must be text, got {type(fields.get(name)).__name__}")
        box = _bounds(kind, fields.get("bounds"))
        if kind == "implicit":
            node = implicit(fields["expr"], box, params or None)
        elif kind == "parametric":
            node = parametric(fields["x"], fields["y"], fields["z"], box, timeout=timeout, params=params or None)
        else:
            extra = {k: fields[k] for k in ("lipschitz", "exact", "implicit") if fields.get(k) is not None}
            node = glsl(fields["code"], bounds=box, params=params or None, **extra)
        doc = to_dict(node)
        return {"node": doc["scene"], "params": doc.get("params", {})}

    def preview(self, doc: dict[str, Any]) -> dict[str, Any]:
        """The view spec of a node's own preview: the document ``doc`` (that node's subtree;
        a 2D shape is shown extruded PREVIEW_SLAB thick) compiled by the same ``build`` as
        the page's view, at PREVIEW_SIZE, one sample a pixel, no shadows or AO, one shader
        (no toggles). The page draws it with the output
        view's camera and live parameters. Counted in :attr:`preview_compiles`."""
        from ..web.spec import build
        scene = from_document(as_solid(doc)).scene
        spec, _ = build(scene, None, PREVIEW_SIZE, toggles=False, aa=1, shadows=False, ao=False)
        with self._lock:
            self.preview_compiles += 1
        return spec

    def export(self, fmt: str) -> tuple[str, bytes]:
        """The current scene as a file of format ``fmt`` through the existing exporters: ``png``
        (``sg.render`` at the page's size, camera and settings), ``html`` (the one-file WebGL2
        page), ``stl`` or ``3mf`` (``sg.mesh``, the ``mesh`` extra), ``mp4`` (``sg.animate``:
        a turntable of TURNTABLE_S seconds, the ``video`` extra). Returns (file name, bytes);
        the file is made in a temporary folder, never beside the document."""
        if fmt not in EXPORTS:
            raise ParameterError(f"studio export: format must be one of {', '.join(EXPORTS)}, got {fmt!r}")
        document = self.document
        stem = self.path.stem if self.path is not None else "scene"
        if fmt == "png":
            from ..png import encode_png
            from ..render import render
            data = encode_png(render(document.scene, document.camera, self.size, **document.settings).color)
        elif fmt == "html":
            from ..web.html import to_html
            data = to_html(document.scene, document.camera, self.size, **document.settings).encode("utf-8")
        else:
            with tempfile.TemporaryDirectory(prefix="sdfgl-studio-") as tmp:
                target = Path(tmp) / f"{stem}.{fmt}"
                if fmt == "mp4":
                    from ..animate import animate, turntable
                    cam = document.camera
                    spin = turntable(getattr(cam, "distance", None), getattr(cam, "pitch", 20.0),
                                     getattr(cam, "target", None), getattr(cam, "fov", 45.0), getattr(cam, "yaw", 30.0))
                    animate(document.scene, target, TURNTABLE_S, camera=spin, size=self.size, **document.settings)
                else:
                    from ..mesh import mesh
                    mesh(document.scene).save(target)
                data = target.read_bytes()
        return f"{stem}.{fmt}", data


def as_solid(doc: dict[str, Any]) -> dict[str, Any]:
    """``doc``, or, where its root is a 2D shape, the document of that shape extruded
    PREVIEW_SLAB thick (a 2D shape has no 3D field to draw; its preview shows the slab)."""
    from ..nodes.record import registry
    from ..nodes.shapes2d import Shape2D
    root = doc.get("scene") if isinstance(doc, dict) else None
    cls = registry().get(root.get("kind")) if isinstance(root, dict) else None
    if isinstance(cls, type) and issubclass(cls, Shape2D):
        return {**doc, "scene": {"kind": "extrude", "shape": root, "height": PREVIEW_SLAB}}
    return doc

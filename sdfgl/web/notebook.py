"""Inline images in Jupyter: a small rendered preview of a node (turn it off with set_preview)."""
from __future__ import annotations

import os

from ..errors import SdfglError
from ..nodes.base import IMPLICIT, Node

_preview = {"enabled": os.environ.get("SDFGL_PREVIEW", "1") not in ("0", "false", "no", "off"),
            "size": (256, 160)}


def set_preview(enabled: bool = True, size: tuple[int, int] | None = None) -> None:
    """Turn the inline preview of nodes in notebooks on or off (``SDFGL_PREVIEW=0`` starts with it off),
    and set its size in pixels."""
    if not isinstance(enabled, bool):
        raise SdfglError(f"set_preview: 'enabled' must be True or False, got {enabled!r}")
    _preview["enabled"] = enabled
    if size is not None:
        try:
            w, h = (int(x) for x in size)
        except (TypeError, ValueError):
            raise SdfglError(f"set_preview: 'size' must be two integers in 16..2048, got {size!r}") from None
        if not (16 <= w <= 2048 and 16 <= h <= 2048):
            raise SdfglError(f"set_preview: 'size' must be two integers in 16..2048, got {size!r}")
        _preview["size"] = (w, h)


def preview_png(node: Node) -> bytes | None:
    """PNG of a small headless render of ``node``, or None (preview off, or the node cannot be
    rendered on its own: Jupyter then shows the text repr)."""
    if not _preview["enabled"]:
        return None
    from ..render import render
    implicit = node.exactness == IMPLICIT
    try:
        res = render(node, size=_preview["size"], aa=1, shadows="soft", ao=not implicit,
                     **({"method": "newton"} if implicit else {}))
    except SdfglError:
        return None
    return res._repr_png_()


def in_kernel() -> bool:
    """Whether this code runs in a Jupyter kernel (where a blocking window would hang the notebook)."""
    import sys
    if "IPython" not in sys.modules:
        return False
    from IPython import get_ipython
    ip = get_ipython()
    return ip is not None and "IPKernelApp" in getattr(ip, "config", {})

"""The optional dependencies of sdfgl.mesh, imported lazily with a clear message when missing."""
from __future__ import annotations

import importlib
from typing import Any

from ..errors import SdfglError

_PIP = {"trimesh": "trimesh", "scipy": "scipy", "lxml": "lxml", "pyfqmr": "pyfqmr", "meshoptimizer": "meshoptimizer"}


def require(module: str) -> Any:
    """Import ``module`` or say how to install sdfgl's mesh extra."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        raise SdfglError(f"mesh export needs the '{_PIP.get(module, module)}' package: "
                         f"pip install 'sdfgl[mesh]' ({exc})") from None

"""Mesh export: the scene's generated map() sampled sparsely on the GPU, extracted to a
watertight triangle mesh (marching cubes, or dual contouring for sharp features),
projected onto the surface, written as STL / OBJ / PLY / glTF / 3MF, with an accuracy report.

    m = sg.mesh(scene, step=0.01)        # this package is callable: sg.mesh(...) is mesh(...)
    m.save("part.stl"); print(m.report())
"""
import sys
import types

from .build import MODES, mesh
from .result import Mesh

__all__ = ["mesh", "Mesh", "MODES"]


class _CallableModule(types.ModuleType):
    """``sdfgl.mesh`` is both this package and the function: ``sg.mesh(scene, step=0.01)``."""

    def __call__(self, *args, **kwargs):  # noqa: ANN002, ANN003, ANN204
        return mesh(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule

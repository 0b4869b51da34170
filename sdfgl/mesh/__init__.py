"""Mesh export: the scene's generated map() sampled sparsely on the GPU, extracted to a
watertight triangle mesh (marching cubes, or dual contouring for sharp features),
projected onto the surface, written as STL / OBJ / PLY / glTF / 3MF, with an accuracy report.

    m = sg.mesh(scene, step=0.01)
    m.save("part.stl"); print(m.report())
"""
from .build import MODES, mesh
from .result import Mesh

__all__ = ["mesh", "Mesh", "MODES"]

"""Triangle meshes in: files and trimesh objects as exact signed-distance nodes.

    part = sg.load_mesh("bracket.stl", units="mm")     # STL, OBJ, PLY, GLB/glTF, 3MF
    drilled = part - sg.cylinder(0.1, 2)

See :mod:`sdfgl.nodes.mesh_field` for the field itself.
"""
from .load import from_mesh, load_mesh

__all__ = ["from_mesh", "load_mesh"]

"""Data strategies: how big parts of a scene are kept as tables a shader reads instead of code.

- :mod:`.instances` and :mod:`.grid`: a hard union of many instances, sorted into types and
  listed per cell of a uniform grid; :mod:`.grid_code` writes its GLSL, :mod:`.grid_record`
  packs each instance's move, :mod:`.slots` reads a primitive's numbers from its record;
  :mod:`.blend_lists` lists a smooth union's children per cell, its ordered fold pruned exactly;
- :mod:`.bvh`: the same instances in a bounding volume hierarchy (setting ``grid="bvh"``);
- :mod:`.ray_entry`: balls and boxes that hold a subtree, for the free way along the ray;
- :mod:`.polygrid`: a polygon of many vertices, its edges listed per cell;
- :mod:`.textgrid`: a long text, its placed glyphs listed per cell (both on :mod:`.grid2`);
- :mod:`.triangles`: a closed triangle mesh, its triangles in a bounding volume hierarchy.

A union's, a polygon's and a text's layouts bound the field far from their parts (the cells' cap),
so the nodes' float64 twins use them too: this package registers them with
:mod:`sdfgl.nodes.layouts` (the nodes never import the compiler).
"""
from ...nodes.layouts import register_layout
from . import instances, polygrid, textgrid, triangles

register_layout("union", instances.build)
register_layout("polygon", polygrid.build)
register_layout("text", textgrid.build)
register_layout("mesh", triangles.build)

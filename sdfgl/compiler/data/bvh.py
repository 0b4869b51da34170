"""A bounding volume hierarchy over a grid union's instances: the structure measured
against the uniform grid (setting ``grid="bvh"``; the grid stays the default, see the
benchmark's structure table and docs/design/big-scenes.md).

The instances of a ``Grid`` (its types and records are shared) are split at the median of
their box centres along the widest axis until at most LEAF remain; each leaf lists its
instances per type like a grid cell. A node stores both children's boxes, so the shader
(``shaders/templates/bvh_union.glsl``) visits the nearer child first and pushes the farther one
while it could hold something nearer than the best so far. The field starts from a
truncation ``T = max(TRUNCATE * cell, distance to the root box)`` and skips every box
at least the best so far away, so it is min(all instances, T): a distance bound, exact
wherever it is below T. Unlike the grid every instance is listed once, so there is no
cap inside the scene: steps are those of the exact union.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ... import shaderlib
from ...errors import SdfglError
from .grid import LIST_WIDTH, Grid

if TYPE_CHECKING:  # pragma: no cover
    from ..emitter import Emitter

LEAF = 4          # instances per leaf at most
STACK = 24        # the shader's traversal stack (the tree is balanced: depth ~ log2(n / LEAF))
TRUNCATE = 1.0    # the field's truncation, in grid cells (see the module docstring)


class Bvh:
    """The tree over ``grid``'s instances: node boxes, leaves and their per-type lists."""

    def __init__(self, grid: Grid) -> None:
        self.grid = grid
        los, his = grid.los, grid.his
        centre = 0.5 * (los + his)
        nodes: list[list] = []    # [lo_a, hi_a, child_a, lo_b, hi_b, child_b]
        leaves: list[np.ndarray] = []

        def child(idx: np.ndarray) -> int:
            if len(idx) <= LEAF:
                leaves.append(idx)
                return -len(leaves)  # leaf k is -1 - k
            nodes.append([])
            return len(nodes) - 1

        root = np.arange(len(los))
        todo = [(child(root), root)]
        while todo:
            at, idx = todo.pop()
            if at < 0:
                continue
            c = centre[idx]
            axis = int(np.argmax(c.max(axis=0) - c.min(axis=0)))
            order = idx[np.argsort(c[:, axis], kind="stable")]
            halves = (order[:len(order) // 2], order[len(order) // 2:])
            entry = []
            for half in halves:
                k = child(half)
                entry += [los[half].min(axis=0), his[half].max(axis=0), k]
                todo.append((k, half))
            nodes[at] = entry
        self.nodes, self.leaves = nodes, leaves
        self.depth = _depth(nodes)
        if self.depth >= STACK:
            raise SdfglError(f"union: a bounding volume hierarchy {self.depth} deep exceeds the shader's stack of {STACK}")
        self._textures: dict[tuple, dict[str, np.ndarray]] = {}

    def textures(self, default_color: tuple[float, float, float]) -> dict[str, np.ndarray]:
        """float32 RGBA arrays: "Nodes" (4 texels a node: (lo_a, child_a), (hi_a, child_b),
        (lo_b, 0), (hi_b, 0), boxes relative to the grid's centre), "Cells" (per leaf and
        type (first, count) pairs, as a grid cell) and "List" (the records, by leaf)."""
        key = tuple(default_color)
        if key in self._textures:
            return self._textures[key]
        g = self.grid
        nodes = np.zeros((len(self.nodes), 4, 4), dtype=np.float64)
        for i, (lo_a, hi_a, a, lo_b, hi_b, b) in enumerate(self.nodes):
            nodes[i, 0, :3], nodes[i, 0, 3] = lo_a - g.centre, a
            nodes[i, 1, :3], nodes[i, 1, 3] = hi_a - g.centre, b
            nodes[i, 2, :3], nodes[i, 3, :3] = lo_b - g.centre, hi_b - g.centre
        type_of = np.zeros(len(g.children), dtype=np.int64)
        local = np.zeros(len(g.children), dtype=np.int64)
        for ti, t in enumerate(g.types):
            type_of[t.members] = ti
            local[t.members] = np.arange(len(t.members))
        recs = [g.records(t, default_color) for t in g.types]
        ntypes = len(g.types)
        per_leaf = -(-ntypes // 2)
        table = np.zeros((len(self.leaves), per_leaf * 2, 2), dtype=np.float64)
        rows: list[np.ndarray] = []
        at = 0
        for li, idx in enumerate(self.leaves):
            for ti in range(ntypes):
                mine = idx[type_of[idx] == ti]
                table[li, ti] = (at, len(mine))
                if len(mine):
                    block = recs[ti][local[mine]].reshape(-1, 4)
                    rows.append(block)
                    at += len(block)
        lst = np.concatenate(rows) if rows else np.zeros((1, 4))
        out = {"Nodes": _rows(nodes.reshape(-1, 4), LIST_WIDTH), "Cells": _rows(table.reshape(-1, 4), LIST_WIDTH),
               "List": _rows(lst, LIST_WIDTH)}
        self._textures[key] = out
        return out

    def emit_function(self, em: "Emitter", fn: str, color: bool, loops: list[tuple[str, str]], owner: str) -> list[tuple[str, str]]:
        """The GLSL lines of the union function ``fn``: traversal around the per-type
        ``loops`` (from sdfgl.compiler.data.grid_code, reading pairs s0, s1, ... and updating ``best``)."""
        g = self.grid
        gid = em.grid_name(g)
        tex = self.textures(em.grids[id(g)][2])
        em.require("data_table")
        nodes, cells, lists = (em.data.add(tex[k]) for k in ("Nodes", "Cells", "List"))
        defs = (f"#define {gid}_NODES {nodes}\n#define {gid}_CELLS {cells}\n#define {gid}_LIST {lists}\n"
                f"#define {gid}_PER_LEAF {-(-len(g.types) // 2)}\n#define {gid}_STACK {STACK}\n"
                f"#define {gid}_ROOT_LO vec3({', '.join(em.num(x) for x in g.los.min(axis=0) - g.centre)})\n"
                f"#define {gid}_ROOT_HI vec3({', '.join(em.num(x) for x in g.his.max(axis=0) - g.centre)})\n"
                f"#define {gid}_TRUNCATE {em.num(TRUNCATE * g.cell)}")
        em.helper(f"{gid}_bvh", defs + "\n" + shaderlib.read("templates/bvh_union").replace("GRIDID", gid))
        w = ".w" if color else ""
        rtype = "vec4" if color else "float"
        init = f"vec4(0.0, 0.0, 0.0, {gid}Truncate(p))" if color else f"{gid}Truncate(p)"
        head = [f"{rtype} {fn}(vec3 p) {{",
                f"    {rtype} best = {init};",
                f"    int stack[{gid}_STACK];",
                f"    float near[{gid}_STACK];",
                "    int sp = 0;",
                "    int node = 0;",
                f"    for (int it = 0; it < {4 * len(self.nodes) + 4}; it++) {{",
                "        if (node >= 0) {",
                "            float da, db;",
                "            int a, b;",
                f"            {gid}Children(p, node, da, db, a, b);",
                f"            if (da > db) {{ float dt = da; da = db; db = dt; int t = a; a = b; b = t; }}",
                f"            if (db < best{w}) {{ stack[sp] = b; near[sp++] = db; }}",
                f"            if (da < best{w}) {{ node = a; continue; }}",
                "        } else {",
                f"            int leaf = (-1 - node) * {gid}_PER_LEAF;"]
        head += [f"            vec4 s{j} = dataFetch({gid}_CELLS + leaf + {j});" for j in range(-(-len(g.types) // 2))]
        tail = ["        }",
                f"        while (sp > 0 && near[sp - 1] >= best{w}) sp--;",
                "        if (sp == 0) break;",
                "        node = stack[--sp];",
                "    }",
                "    return best;",
                "}"]
        return [(line, owner) for line in head] + loops + [(line, owner) for line in tail]


def _depth(nodes: list[list]) -> int:
    """Levels of internal nodes below and including the root (the stack a traversal needs)."""
    level = {0: 1}
    for i, entry in enumerate(nodes):  # children come after their parent
        for k in (entry[2], entry[5]):
            if k >= 0:
                level[k] = level[i] + 1
    return max(level.values())


def _rows(texels: np.ndarray, width: int) -> np.ndarray:
    out = np.zeros((max(1, -(-len(texels) // width)) * width, 4), dtype=np.float32)
    out[:len(texels)] = texels
    return out.reshape(-1, width, 4)


def of(grid: Grid) -> Bvh:
    """The tree of ``grid``, built once."""
    hit = grid.__dict__.get("_bvh")
    if hit is None:
        hit = grid.__dict__["_bvh"] = Bvh(grid)
    return hit

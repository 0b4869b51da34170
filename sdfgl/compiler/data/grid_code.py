"""The GLSL of a union kept as data: its function, the per-type loops over a cell's lists
and the free way along the ray (shaders/templates/grid_union.glsl, grid_ray.glsl; with
setting grid="bvh" the hierarchy of sdfgl.compiler.data.bvh walks the same loops).
"""
from __future__ import annotations

import functools
from typing import TYPE_CHECKING

import numpy as np

from ... import shaderlib
from ...nodes.booleans import smooth_glsl
from ...nodes.primitives import Sphere
from . import blend_lists, bvh, grid_record, ray_entry
from ..emitter import Emitter
from .grid import Grid, bounds_of
from .slots import component, slot_expr, slot_values, template

if TYPE_CHECKING:  # pragma: no cover
    from .instances import InstanceType


def emit(grid: Grid, em: "Emitter", p: str) -> str:
    """Call this grid's union function at point ``p``: (rgb, d) in colour mode, else d
    (through the cells, or with setting grid="bvh" the hierarchy of sdfgl.compiler.data.bvh)."""
    gid = em.grid_name(grid)
    channel = "Color" if em.channel == "albedo" else em.channel.capitalize()
    fn = f"{gid}{channel if em.mode == 'color' else ('Detail' if em.detail else 'Dist')}"
    key = ("grid", gid, em.mode, em.channel, em.detail)
    if key not in em.functions:
        color = em.mode == "color"
        owner = f"union of {len(grid.children)} instances ({gid})"
        loops: list[tuple[str, str]] = []
        entries: list[tuple[str, str]] = []  # after the grid's helpers: they call its ray tests
        for ti, t in enumerate(grid.types):
            loops += _loop(grid, em, t, ti, color, owner, entries)
        if grid.blend is not None:  # the cells keep the union's order; a hierarchy would not
            make = functools.partial(_blend_function, grid)
        elif em.use_grids == "bvh":
            make = bvh.of(grid).emit_function
        else:
            make = functools.partial(_cell_function, grid)
        em.functions[key] = (fn, make(em, fn, color, loops, owner))
        for name, code in entries:
            em.helper(name, code)
    pt = em.point(em.shift(p, -grid.centre))
    return em.assign("vec4" if em.mode == "color" else "float", f"{fn}({pt})")


def _grid_defines(grid: Grid, em: "Emitter", gid: str, extra: list[str]) -> str:
    """The grid's tables added to the data texture, and its #defines (``extra`` after the cell size)."""
    tex = grid.textures(em.grids[id(grid)][2])
    em.require("data_table")
    cells, lists = em.data.add(tex["Cells"]), em.data.add(tex["List"])
    return "\n".join([f"#define {gid}_LO vec3({', '.join(em.num(x) for x in grid.lo - grid.centre)})",
                      f"#define {gid}_CELL {em.num(grid.cell)}", *extra,
                      f"#define {gid}_DIMS ivec3({', '.join(str(int(x)) for x in grid.dims)})",
                      f"#define {gid}_PER_CELL {-(-len(grid.types) // 2)}",
                      f"#define {gid}_CELLS {cells}", f"#define {gid}_LIST {lists}"])


def _cell_function(grid: Grid, em: "Emitter", fn: str, color: bool, loops: list[tuple[str, str]],
                   owner: str) -> list[tuple[str, str]]:
    """The union function ``fn``: find p's cell, then run the per-type ``loops`` over its lists."""
    gid = em.grid_name(grid)
    head = shaderlib.read("templates/grid_union").replace("GRIDID", gid)
    defs = _grid_defines(grid, em, gid, [f"#define {gid}_MARGIN {em.num(grid.margin)}"])
    ray = _ray_free(grid, em, color)
    if ray:
        em.require("ray_free")
        head += "\n" + shaderlib.read("templates/grid_ray").replace("GRIDID", gid)
    em.helper(f"{gid}_grid", defs + "\n" + head)
    rtype = "vec4" if color else "float"
    best = "vec4(0.0, 0.0, 0.0, cap)" if color else "cap"
    fetch = [(f"    vec4 s{j} = dataFetch({gid}_CELLS + cell + {j});", owner) for j in range(-(-len(grid.types) // 2))]
    free = [(f"    float free = {gid}Exit(p, gRayInv, cellLo);", owner),
            ("    bool inGrid = free >= 0.0;  // outside the grid box gFree is the field's value", owner)] if ray else []
    done = [("    gFree = inGrid ? max(free, best) : best;", owner)] if ray else []
    return [(f"{rtype} {fn}(vec3 p) {{", owner),
            ("    float cap;", owner),
            ("    vec3 cellLo;", owner),
            (f"    int cell = {gid}Cell(p, cap, cellLo) * {gid}_PER_CELL;", owner),
            (f"    {rtype} best = {best};", owner),
            *free, *fetch, *loops, *done,
            ("    return best;", owner), ("}", owner)]


def _blend_function(grid: Grid, em: "Emitter", fn: str, color: bool, loops: list[tuple[str, str]],
                    owner: str) -> list[tuple[str, str]]:
    """The smooth union function ``fn``: outside the grid box the distance to it plus the
    offset that keeps it below the union's fold; inside, the per-type ``loops`` fold p's
    cell lists from 3e38, and the cap (shaders/templates/grid_blend.glsl)."""
    gid = em.grid_name(grid)
    blend = grid.blend
    assert blend is not None
    head = shaderlib.read("templates/grid_blend").replace("GRIDID", gid)
    defs = _grid_defines(grid, em, gid, [f"#define {gid}_OUTSIDE {em.num(blend.pad - blend.support)}",
                                         f"#define {gid}_CAP {em.num(blend_lists.cap(grid))}"])
    em.helper(f"{gid}_grid", defs + "\n" + head)
    rtype = "vec4" if color else "float"
    outside = f"vec4(0.0, 0.0, 0.0, away + {gid}_OUTSIDE)" if color else f"away + {gid}_OUTSIDE"
    start = "vec4(0.0, 0.0, 0.0, 3.0e38)" if color else "3.0e38"
    fetch = [(f"    vec4 s{j} = dataFetch({gid}_CELLS + cell + {j});", owner) for j in range(-(-len(grid.types) // 2))]
    return [(f"{rtype} {fn}(vec3 p) {{", owner),
            ("    float away;", owner),
            (f"    int cell = {gid}Cell(p, away) * {gid}_PER_CELL;", owner),
            (f"    if (away > 0.0) return {outside};", owner),
            (f"    {rtype} best = {start};  // smin(3e38, d) = d", owner),
            *fetch, *loops,
            (f"    return {'vec4(best.rgb, min(best.w, ' + gid + '_CAP))' if color else 'min(best, ' + gid + '_CAP)'};",
             owner), ("}", owner)]


def _blend_step(grid: Grid, em: "Emitter", d: str, rgb: str | None) -> list[str]:
    """The lines that fold one listed child (distance ``d``, colour ``rgb`` in colour mode)
    into ``best`` as the union's code does (Union._combine)."""
    blend = grid.blend
    assert blend is not None
    if rgb is None:
        return [f"        best = {smooth_glsl(em, 'best', d, blend.k, blend.kind)};"]
    em.require("op_smin_color")
    lines = [f"        vec4 mixed = opSminColor(best, vec4({rgb}, {d}), {em.num(blend.k)});"]
    if blend.kind == "quadratic":
        return lines + ["        best = mixed;"]
    return lines + [f"        best = vec4(mixed.rgb, {smooth_glsl(em, 'best.w', d, blend.k, blend.kind)});"]


def _ray_free(grid: Grid, em: "Emitter", color: bool) -> bool:
    """Whether this grid's distance function also leaves the free way along the ray
    (shaders/templates/grid_ray.glsl): for the marchers' primary rays where the scene is this union."""
    return not color and em.leaves_free_way(grid)


def _free_way(grid: Grid, em: "Emitter", t: InstanceType, move: str, d: str) -> str:
    """GLSL for how far along the ray from q (the point in a listed instance's frame, whose
    distance is ``d``) nothing of that instance lies: an unscaled sphere's entry (q is
    relative to its centre, its radius |q| - d), a subtree's entry into its bounding box
    (translated: the ray's direction is the world's in its frame; turned: the direction
    turned into its frame, ``_boxed``; the nearest such instance is refined by its parts
    after the loop: _refined_entry), any other instance its distance (a primitive's
    bounds depend on its data)."""
    gid = em.grid_name(grid)
    if move == "translate" and type(t.inner) is Sphere:
        return f"{gid}RayBall(q, gRayDir, length(q) - ({d}))"
    if _boxed(t, move):
        lo, hi = bounds_of(t.inner)
        return f"{gid}RayBox(q, {_ray(move)[1]}, {em.vec(lo)}, {em.vec(hi)})"
    return d


def _boxed(t: InstanceType, move: str) -> bool:
    """Whether type ``t``'s instances bound the free way by their box: subtrees and
    primitives of fixed size, translated or turned (a quaternion record) and unscaled."""
    return t.slots is None and type(t.inner) is not Sphere and not t.scaled and move in ("translate", "quat")


def _loop(grid: Grid, em: "Emitter", t: InstanceType, ti: int, color: bool, owner: str,
          entries: list[tuple[str, str]]) -> list[tuple[str, str]]:
    """The loop over the (cell, type ti) list: fetch, transform, evaluate, keep the min
    (and the free way: a refined entry's function goes to ``entries``, as (name, code))."""
    sizes = [len(v) for _, v in slot_values(t.inner)] if t.slots is not None else []
    move = grid_record.kind(t, np.array([grid.peeled[i][2] for i in t.members]))
    scale_at, slots_at, color_at, texels = t.layout(sizes, move)
    need = texels if color else -(-(color_at if t.color_in_record else texels * 4) // 4)
    need = max(need, 1)
    gid = em.grid_name(grid)
    span = f"s{ti // 2}"
    lines = [f"    {{  // type {ti}: {t.inner.label()[:60]} x {len(t.members)}"]
    first, count = (f"{span}.x", f"{span}.y") if ti % 2 == 0 else (f"{span}.z", f"{span}.w")
    lines.append(f"    int first = int({first});")
    lines.append(f"    int count = int({count});")
    refined = _refined_entry(grid, em, t, ti, move, color, entries)
    if refined:
        lines.append("    float enterNear = 3.0e38;  // the smallest box entry, and its instance's point")
        lines.append("    vec3 qNear = vec3(0.0);")
        if move == "quat":  # ... and the ray in its frame
            lines.append("    vec3 dirNear = gRayDir;")
            lines.append("    vec3 invNear = gRayInv;")
    lines.append("    for (int k = 0; k < count; k++) {")
    lines.append(f"        int e = {gid}_LIST + first + k * {texels};")
    for j in range(need):
        lines.append(f"        vec4 d{j} = dataFetch(e + {j});")
    lines.append(grid_record.glsl(move, component(scale_at, 0) if t.scaled else None))
    out = [(line, owner) for line in lines]
    # the type's field at q
    if t.slots is not None:
        tpl = template(t.inner, t.slots, slots_at)
        sub = Emitter("dist", parent=em)
        sub._count = 0
        d = tpl._emit(sub, "q")
        out += [("    " + code, owner) for code, _ in sub.lines]
        result_color = None
    elif color and t.color_in_code is not None:
        own = em.grids[id(grid)][2] if t.color_in_code == ("default",) else t.color_in_code
        with em.colored({"albedo": own}):
            name = em.function(t.inner)
        out.append((f"        vec4 r = {name}(q);", owner))
        d, result_color = "r.w", "r.rgb"
    else:
        mode = em.mode
        em.mode = "dist"
        try:
            name = em.function(t.inner)
        finally:
            em.mode = mode
        out.append((f"        float dd = {name}(q);", owner))
        d, result_color = "dd", None
    if t.scaled:
        d = f"({d}) * {component(scale_at, 0)}"
    if color:
        rgb = result_color or _record_color(grid, em, t, color_at)
        out.append((f"        float dist = {d};", owner))
        if grid.blend is not None:
            out += [(line, owner) for line in _blend_step(grid, em, "dist", rgb)]
        else:
            out.append((f"        if (dist < best.w) best = vec4({rgb}, dist);", owner))
    elif grid.blend is not None:
        out.append((f"        float dist = {d};", owner))
        out += [(line, owner) for line in _blend_step(grid, em, "dist", None)]
    else:
        out.append((f"        best = min(best, {d});", owner))
        turned = _ray_free(grid, em, color) and _boxed(t, move) and move == "quat"
        if turned:  # the ray's direction in the instance's frame (the record's quaternion), and 1 / it
            out += [(line, owner) for line in (
                "        vec3 dirQ = gRayDir + 2.0 * cross(d0.xyz, cross(d0.xyz, gRayDir) + d0.w * gRayDir);",
                "        vec3 invQ = 1.0 / (dirQ + vec3(equal(dirQ, vec3(0.0))) * 1e-30);")]
        if refined:
            out += [(line, owner) for line in (
                f"        float enter = {_free_way(grid, em, t, move, d)};",
                "        free = min(free, enter < enterNear ? enterNear : enter);  // every entry but the smallest",
                "        bool nearer = enter < enterNear;",
                "        qNear = nearer ? q : qNear;",
                *(["        dirNear = nearer ? dirQ : dirNear;", "        invNear = nearer ? invQ : invNear;"]
                  if turned else []),
                "        enterNear = min(enterNear, enter);")]
        elif _ray_free(grid, em, color):
            out.append((f"        free = min(free, {_free_way(grid, em, t, move, d)});", owner))
    out.append(("    }", owner))
    if refined:
        ray = "invNear, dirNear" if move == "quat" else "gRayInv, gRayDir"
        out.append((f"    free = min(free, max(enterNear, {refined}(qNear, {ray})));  // the nearest by its parts", owner))
    out.append(("    }", owner))
    return out


def _record_color(grid: Grid, em: "Emitter", t: InstanceType, color_at: int) -> str:
    """The GLSL colour of a listed instance of type ``t`` in this pass's channel: the albedo
    from its record, or the type's one colour written in code; other channels the current value."""
    if em.channel != "albedo":
        return em.vec(em.current())
    if t.one_color:
        return em.vec(t.color if t.color is not None else em.grids[id(grid)][2])
    return slot_expr(color_at, 3)


def _refined_entry(grid: Grid, em: "Emitter", t: InstanceType, ti: int, move: str, color: bool,
                   entries: list[tuple[str, str]]) -> str | None:
    """The name of the GLSL function for where the ray enters type ``t`` by its parts
    (sdfgl.compiler.data.ray_entry; its code goes to ``entries``), where the free way may refine its
    nearest instance that way: a subtree entered by its box (``_boxed``) that holds parts
    with room between them; else None. Only the instance with the smallest box entry is
    refined, once a call after the list's loop: every entry test costs about what a call
    saves. The function takes the point, 1 / the direction and the direction, all in
    the instance's frame."""
    if not _ray_free(grid, em, color) or not _boxed(t, move):
        return None
    found = ray_entry.pieces(t.inner)
    if found is None:
        return None
    gid = em.grid_name(grid)
    name = f"{gid}Enter{ti}"
    entries.append((name, f"float {name}(vec3 q, vec3 inv, vec3 dir) {{\n"
                          f"    return {ray_entry.entry_glsl(em, gid, found, 'q', 'inv', 'dir')};\n}}"))
    return name


def _ray(move: str) -> tuple[str, str]:
    """The GLSL of the ray's direction and 1 / it in a listed instance's frame (see _loop)."""
    return ("dirQ", "invQ") if move == "quat" else ("gRayDir", "gRayInv")

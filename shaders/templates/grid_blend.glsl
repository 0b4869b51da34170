// A smooth union kept as data (sdfgl/compiler/data/blend_lists.py): each cell of a uniform
// grid lists, per type and in the union's order, the children the blend may need there,
// so folding the list from 3e38 gives the union's own fold at every point of the cell;
// the field is min(fold, GRIDID_CAP), and a cell whose fold lies above the cap lists nothing.
// Outside the grid box (which reaches beyond every child by more than the blend's
// support) nothing is listed: the field is the distance to the box plus GRIDID_OUTSIDE.
// GRIDID is replaced per union; p is relative to the grid's centre. Its tables are in the
// shader's data texture (lib/data_table.glsl): from GRIDID_CELLS, per cell and type pair
// (first, count, first, count); from GRIDID_LIST, the records.

// The index of p's cell (clamped to the grid) and how far p lies outside the grid box
// (0 inside it: measured to the box, not to the cell, which rounding may put beside p).
int GRIDIDCell(vec3 p, out float away) {
    vec3 rel = (p - GRIDID_LO) / GRIDID_CELL;
    ivec3 cell = clamp(ivec3(floor(rel)), ivec3(0), GRIDID_DIMS - 1);
    away = length(max(max(GRIDID_LO - p, p - (GRIDID_LO + vec3(GRIDID_DIMS) * GRIDID_CELL)), 0.0));
    return (cell.z * GRIDID_DIMS.y + cell.y) * GRIDID_DIMS.x + cell.x;
}

// A big union kept as data (sdfgl/nodes/grid.py): instances listed per cell of a uniform
// grid, per type, with their data inline. A point looks only at its cell's lists (loops
// whose lengths are the lists', so work follows what is near, not the scene's size).
// Anything not listed is at least margin - e away (e: how far the point lies outside its
// cell, which is 0 inside the grid box and the distance to the box outside it) and at
// least as far as the grid box (e again), so the min of the listed ones and that cap
// is a distance bound equal to the exact min wherever the min is below the cap.
// GRIDID is replaced per union; p is relative to the grid's centre.
// Its tables are in the shader's data texture (lib/data_table.glsl): from GRIDID_CELLS,
// per cell and type pair (first, count, first, count); from GRIDID_LIST, the records.

// The index of p's cell (clamped to the grid), the cap on unlisted instances and the
// cell's low corner.
int GRIDIDCell(vec3 p, out float cap, out vec3 cellLo) {
    vec3 rel = (p - GRIDID_LO) / GRIDID_CELL;
    ivec3 cell = clamp(ivec3(floor(rel)), ivec3(0), GRIDID_DIMS - 1);
    cellLo = GRIDID_LO + vec3(cell) * GRIDID_CELL;
    // outside its (clamped) cell only outside the grid box, and then by the distance to the box
    float away = length(max(max(cellLo - p, p - (cellLo + GRIDID_CELL)), 0.0));
    cap = max(GRIDID_MARGIN - away, away);
    return (cell.z * GRIDID_DIMS.y + cell.y) * GRIDID_DIMS.x + cell.x;
}

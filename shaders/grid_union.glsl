// A big union of simple primitives kept as data (Model only what a scene needs, at
// scale): the primitives live in a texture and a uniform grid lists, per cell, those
// whose bounds come within one cell size (the margin) of it. A point looks only at its
// cell's list, a loop whose length is the list's, so work follows what is near, not the
// scene's size. Anything not listed is at least margin - e away (e: how far the point
// lies outside its cell) and at least as far as the grid box, so the min of the listed
// ones and that cap is a distance bound that equals the exact min wherever the min is
// below the cap. GRIDID is replaced per union.
uniform sampler2D uGRIDIDPrims;  // 4 texels per primitive, one row each (see sdfgl/nodes/grid.py)
uniform sampler2D uGRIDIDCells;  // per cell: (first list entry, count)
uniform sampler2D uGRIDIDList;   // primitive indices, GRID_LIST_WIDTH per row

// The distance of primitive i at p, and (in .rgb) its colour.
vec4 GRIDIDPrim(int i, vec3 p) {
    vec4 a = texelFetch(uGRIDIDPrims, ivec2(0, i), 0);  // type, scale, translation.xy
    vec4 b = texelFetch(uGRIDIDPrims, ivec2(1, i), 0);  // translation.z, size.xyz
    vec4 c = texelFetch(uGRIDIDPrims, ivec2(2, i), 0);  // rotation column 0, rounding
    vec4 e = texelFetch(uGRIDIDPrims, ivec2(3, i), 0);  // rotation column 1, unused
    vec3 col2 = cross(c.xyz, e.xyz);
    vec3 q = (transpose(mat3(c.xyz, e.xyz, col2)) * (p - vec3(a.zw, b.x))) / a.y;
    float d;
    int type = int(a.x);
    if (type == 0) {
        d = length(q) - b.y;                                           // sphere: radius
    } else if (type == 1) {
        vec3 k = abs(q) - b.yzw + c.w;                                 // (rounded) box: half size, rounding
        d = length(max(k, 0.0)) + min(max(k.x, max(k.y, k.z)), 0.0) - c.w;
    } else if (type == 2) {
        d = length(vec2(length(q.xz) - b.y, q.y)) - b.z;               // torus: radii
    } else {
        vec2 k = abs(vec2(length(q.xz), q.y)) - b.yz;                  // cylinder: radius, half height
        d = min(max(k.x, k.y), 0.0) + length(max(k, 0.0));
    }
    vec4 f = texelFetch(uGRIDIDPrims, ivec2(4, i), 0);
    return vec4(f.rgb, d * a.y);
}

// (rgb, distance) of the union at p (p relative to the shader origin).
vec4 GRIDIDUnion(vec3 p) {
    vec3 rel = (p - GRIDID_LO) / GRIDID_CELL;
    ivec3 cell = clamp(ivec3(floor(rel)), ivec3(0), GRIDID_DIMS - 1);
    vec3 cellLo = GRIDID_LO + vec3(cell) * GRIDID_CELL;
    vec3 outside = max(max(cellLo - p, p - (cellLo + GRIDID_CELL)), 0.0);
    // unlisted primitives are at least (margin - e) away, and outside the grid box
    vec3 gridHalf = 0.5 * vec3(GRIDID_DIMS) * GRIDID_CELL;
    vec3 k = abs(p - (GRIDID_LO + gridHalf)) - gridHalf;
    float boxDist = length(max(k, 0.0)) + min(max(k.x, max(k.y, k.z)), 0.0);
    vec4 best = vec4(0.0, 0.0, 0.0, max(GRIDID_CELL - length(outside), boxDist));
    int index = (cell.z * GRIDID_DIMS.y + cell.y) * GRIDID_DIMS.x + cell.x;
    vec4 span = texelFetch(uGRIDIDCells, ivec2(index % GRID_LIST_WIDTH, index / GRID_LIST_WIDTH), 0);
    int first = int(span.x);
    int count = int(span.y);
    for (int k = 0; k < count; k++) {
        int entry = first + k;
        int i = int(texelFetch(uGRIDIDList, ivec2(entry % GRID_LIST_WIDTH, entry / GRID_LIST_WIDTH), 0).x);
        vec4 v = GRIDIDPrim(i, p);
        if (v.w < best.w) best = v;
    }
    return best;
}

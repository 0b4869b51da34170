// The cell of a 2D uniform grid (origin lo, square cells of side `cell`, dims cells) that
// holds p, clamped to the grid, and the cap of the grid's lists there: every part not
// listed in that cell lies at least `margin` from it, so at least
// max(margin - |p's way outside the cell|, distance outside the whole grid) from p.
// Shared by the edge grid of polygons and the glyph grid of text.
float grid2Cap(vec2 p, vec2 lo, float cell, ivec2 dims, float margin, out ivec2 c, out float boxDist) {
    c = clamp(ivec2(floor((p - lo) / cell)), ivec2(0), dims - 1);
    vec2 cellLo = lo + vec2(c) * cell;
    vec2 outside = max(max(cellLo - p, p - (cellLo + cell)), 0.0);
    vec2 halfExt = 0.5 * vec2(dims) * cell;
    vec2 k = abs(p - (lo + halfExt)) - halfExt;
    boxDist = length(max(k, 0.0)) + min(max(k.x, k.y), 0.0);
    return max(margin - length(outside), boxDist);
}

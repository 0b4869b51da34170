// Sierpinski tetrahedron by mirror folding (the seed thesis's linear-cost recursion):
// each level folds space across the three planes x+y=0, x+z=0, y+z=0 (so one copy stands
// for three) and scales by 2 about a vertex; the distance to the base tetrahedron is
// divided back. Cost grows with the number of levels, not with the 4^levels copies.
float sdSierpinski(vec3 p, int levels, float size) {
    float scale = 1.0;
    for (int i = 0; i < levels; i++) {
        if (p.x + p.y < 0.0) p.xy = -p.yx;
        if (p.x + p.z < 0.0) p.xz = -p.zx;
        if (p.y + p.z < 0.0) p.yz = -p.zy;
        p = 2.0 * p - vec3(size);
        scale *= 2.0;
    }
    // regular tetrahedron with vertices (1,1,1), (1,-1,-1), (-1,1,-1), (-1,-1,1) times size
    float d = (max(abs(p.x + p.y) - p.z, abs(p.x - p.y) + p.z) - size) * 0.57735027;
    return d / scale;
}

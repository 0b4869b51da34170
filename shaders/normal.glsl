// Surface normal by the tetrahedron technique (Inigo Quilez, MIT): four map() calls.
// The offset follows the pixel footprint, and a vanishing gradient (e.g. at the
// centre of a sphere) falls back to facing the viewer instead of normalize(0) = NaN.
vec3 calcNormal(vec3 pos, float t, vec3 rd) {
    float h = max(0.5 * pixelAngle() * t, 1e-5 * SCENE_SCALE);
    const vec2 k = vec2(1.0, -1.0);
    vec3 g = k.xyy * map(pos + k.xyy * h) + k.yyx * map(pos + k.yyx * h)
           + k.yxy * map(pos + k.yxy * h) + k.xxx * map(pos + k.xxx * h);
    float len = length(g);
    return len > 1e-20 ? g / len : -rd;
}

// Surface normal by central differences: six map() calls. (The four-tap tetrahedron
// technique is cheaper but its error is first order in the offset wherever the
// Hessian has off-diagonal terms: 0.3 degrees on a unit sphere at a half-pixel
// offset, against 0.01 here.) The offset follows the pixel footprint, and a vanishing
// gradient (e.g. at the centre of a sphere) falls back to facing the viewer instead of
// normalize(0) = NaN.
vec3 calcNormal(vec3 pos, float t, vec3 rd) {
    float h = max(0.5 * pixelAngle() * t, 1e-5 * SCENE_SCALE);
    vec3 g = vec3(map(pos + vec3(h, 0.0, 0.0)) - map(pos - vec3(h, 0.0, 0.0)),
                  map(pos + vec3(0.0, h, 0.0)) - map(pos - vec3(0.0, h, 0.0)),
                  map(pos + vec3(0.0, 0.0, h)) - map(pos - vec3(0.0, 0.0, h)));
    float len = length(g);
    return len > 1e-20 ? g / len : -rd;
}

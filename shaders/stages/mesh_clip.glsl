// The mesh exporter's field: map() cut by the sampling box, so a solid that runs out of the
// box is closed there. uClipLo/uClipHi are the box shrunk by half a cell (shader coordinates).
uniform vec3 uClipLo;
uniform vec3 uClipHi;

float clippedMap(vec3 p) {
    vec3 c = 0.5 * (uClipLo + uClipHi);
    vec3 q = abs(p - c) - 0.5 * (uClipHi - uClipLo);
    float box = length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
    return max(map(p), box);
}

// (gradient, value) of the clipped field at p: the value at p and the tetrahedral central
// difference of IQ's normal, with spacing eps. bend: the mean of the four samples minus the
// value at p; zero where the field is linear across the stencil, about eps^2 / 2 times the
// Laplacian where it is smooth, and of order eps where the stencil straddles a crease of the
// field (a box edge, a CSG cut): there the difference mixes the two sides' gradients.
vec4 clippedGradient(vec3 p, float eps, out float bend) {
    const vec2 k = vec2(1.0, -1.0);
    float a = clippedMap(p + k.xyy * eps);
    float b = clippedMap(p + k.yyx * eps);
    float c = clippedMap(p + k.yxy * eps);
    float d = clippedMap(p + k.xxx * eps);
    float f = clippedMap(p);
    bend = 0.25 * (a + b + c + d) - f;
    return vec4((k.xyy * a + k.yyx * b + k.yxy * c + k.xxx * d) / (4.0 * eps), f);
}

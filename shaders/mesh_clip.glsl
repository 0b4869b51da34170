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

// The coarse pass: one fragment per tile of the image, writing the ray parameter from which
// the tile's rays march (coneStart: no surface lies before it on any of them).
layout(location = 0) out float outStart;

void main() {
    vec2 lo = floor(gl_FragCoord.xy) * float(COARSE_TILE);
    outStart = coneStart(tileCone(lo, lo + float(COARSE_TILE)));
}

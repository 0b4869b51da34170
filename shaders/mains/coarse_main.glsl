// The coarse pass: one fragment per tile of the image, writing the ray parameter from which
// the tile's rays march (coneStart: no surface lies before it on any of them).
// uCoarseMargin widens each tile by that many pixels a side: the viewer draws the pass once
// for all its jittered samples (uJitter 0 here, up to half a pixel each way in the image).
layout(location = 0) out float outStart;
uniform float uCoarseMargin;  // pixels (0 unless set)

void main() {
    vec2 lo = floor(gl_FragCoord.xy) * float(COARSE_TILE) - uCoarseMargin;
    outStart = coneStart(tileCone(lo, lo + float(COARSE_TILE) + 2.0 * uCoarseMargin));
}

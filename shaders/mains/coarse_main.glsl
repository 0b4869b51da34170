// The coarse pass: one fragment per tile of the image, writing the ray parameter from which
// the tile's rays march (coneStart: no surface lies before it on any of them); SKY_TILE for an
// empty tile where no ray meets the ground either, LIT_TILE for one whose ground needs no
// map() call to shade (tileGroundLit).
layout(location = 0) out float outStart;

void main() {
    vec2 lo = floor(gl_FragCoord.xy) * float(COARSE_TILE);
    vec2 hi = lo + float(COARSE_TILE);
    float start = coneStart(tileCone(lo, hi));
    if (start >= EMPTY_TILE) start = !tileSeesGround(lo, hi) ? SKY_TILE : (tileGroundLit(lo, hi) ? LIT_TILE : start);
    outStart = start;
}

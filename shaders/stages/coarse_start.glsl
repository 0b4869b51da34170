// The coarse pass's result, read per pixel: the ray parameter before which no surface lies
// on any ray of the pixel's tile (coarse_cone.glsl), where the march starts; past the ray's
// range where the tile's cone crossed the scene without meeting it.
uniform sampler2D uCoarseStart;

float coarseStart() {
    return texelFetch(uCoarseStart, ivec2(gl_FragCoord.xy) / COARSE_TILE, 0).r;
}

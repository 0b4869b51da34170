// Field samples on a list of lattice blocks in one draw, four consecutive samples a texel.
// Block b starts at integer lattice coordinates texel b of uBlocks; sample (i, j, k) of it is
// at uStart + (corner + (i, j, k)) * uStep, so a sample shared by two blocks is computed from
// the same numbers, to the same float. The framebuffer (RGBA) is read as one flat array:
// index = ((b * uBlock + i) * uBlock + j) * uBlock + k.
// Integer division has no vector instruction on llvmpipe, so quotients are taken in float
// (every index here is below 2^23, MAX_TEXELS) and corrected by one where rounding missed.
uniform sampler2D uBlocks;
uniform int uBlocksWidth;  // texels per row of uBlocks
uniform int uWidth;        // framebuffer width
uniform vec3 uStart;       // lattice origin (shader coordinates)
uniform float uStep;
uniform int uBlock;        // samples per block side
layout(location = 0) out vec4 outValue;

// (n / d, n % d) for 0 <= n < 2^23, 0 < d
ivec2 divmod(int n, int d) {
    int q = int(floor((float(n) + 0.5) / float(d)));
    int r = n - q * d;
    q += r < 0 ? -1 : (r >= d ? 1 : 0);
    return ivec2(q, n - q * d);
}

float sampleAt(int idx) {
    ivec2 bk = divmod(idx, uBlock);         // (rest, k)
    ivec2 bj = divmod(bk.x, uBlock);        // (rest, j)
    ivec2 bi = divmod(bj.x, uBlock);        // (block, i)
    ivec2 row = divmod(bi.x, uBlocksWidth); // (row, column) of the block's texel
    vec3 corner = texelFetch(uBlocks, ivec2(row.y, row.x), 0).xyz;
    return clippedMap(uStart + (corner + vec3(bi.y, bj.y, bk.y)) * uStep);
}

void main() {
    int idx = 4 * (int(gl_FragCoord.y) * uWidth + int(gl_FragCoord.x));
    outValue = vec4(sampleAt(idx), sampleAt(idx + 1), sampleAt(idx + 2), sampleAt(idx + 3));
}

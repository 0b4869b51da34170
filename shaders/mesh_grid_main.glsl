// Field samples on a list of lattice blocks in one draw. Block b starts at integer lattice
// coordinates texel b of uBlocks; sample (i, j, k) of it is at uStart + (corner + (i, j, k)) * uStep,
// so a sample shared by two blocks is computed from the same numbers, to the same float.
// The framebuffer is read as one flat array: index = ((b * uBlock + i) * uBlock + j) * uBlock + k.
uniform sampler2D uBlocks;
uniform int uBlocksWidth;  // texels per row of uBlocks
uniform int uWidth;        // framebuffer width
uniform vec3 uStart;       // lattice origin (shader coordinates)
uniform float uStep;
uniform int uBlock;        // samples per block side
layout(location = 0) out float outValue;

void main() {
    int idx = int(gl_FragCoord.y) * uWidth + int(gl_FragCoord.x);
    int per = uBlock * uBlock * uBlock;
    int b = idx / per;
    int r = idx - b * per;
    ivec3 ijk = ivec3(r / (uBlock * uBlock), (r / uBlock) % uBlock, r % uBlock);
    vec3 corner = texelFetch(uBlocks, ivec2(b % uBlocksWidth, b / uBlocksWidth), 0).xyz;
    outValue = clippedMap(uStart + (corner + vec3(ijk)) * uStep);
}

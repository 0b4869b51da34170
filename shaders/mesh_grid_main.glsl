// Field samples on a list of lattice blocks in one draw. Block b has its first sample at
// texel b of uBlocks (xyz, shader coordinates); it holds uBlock^3 samples uStep apart. The
// framebuffer is read as one flat array: index = ((b * uBlock + i) * uBlock + j) * uBlock + k
// for the sample at offset (i, j, k) * uStep.
uniform sampler2D uBlocks;
uniform int uBlocksWidth;  // texels per row of uBlocks
uniform int uWidth;        // framebuffer width
uniform float uStep;
uniform int uBlock;        // samples per block side
layout(location = 0) out float outValue;

void main() {
    int idx = int(gl_FragCoord.y) * uWidth + int(gl_FragCoord.x);
    int per = uBlock * uBlock * uBlock;
    int b = idx / per;
    int r = idx - b * per;
    ivec3 ijk = ivec3(r / (uBlock * uBlock), (r / uBlock) % uBlock, r % uBlock);
    vec3 o = texelFetch(uBlocks, ivec2(b % uBlocksWidth, b / uBlocksWidth), 0).xyz;
    outValue = clippedMap(o + vec3(ijk) * uStep);
}

// The shader's data tables (sdfgl.codegen.DataPool): one texture, texel i at
// (i % DATA_WIDTH, i / DATA_WIDTH), read by index.
uniform sampler2D uData;

vec4 dataFetch(int i) {
    return texelFetch(uData, ivec2(i & 1023, i >> 10), 0);
}

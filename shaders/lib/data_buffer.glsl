// The shader's data tables (sdfgl.codegen.DataPool) as one buffer texture, texel i read by
// index: the desktop form of data_table.glsl (GLSL ES 3.00 has no samplerBuffer), a
// cheaper fetch than a 2D texture's on llvmpipe (sdfgl/gl/buffer_texture.py).
uniform samplerBuffer uData;

vec4 dataFetch(int i) {
    return texelFetch(uData, i);
}

// The raster meshes drawn before the march, read per pixel: the ray parameter t of the
// nearest mesh (a miss: a huge value), where the march and the ground stop, and its
// gamma-encoded colour, which a sample that reaches the mesh takes.
#define MESH_DEPTH
uniform sampler2D uMeshDepth;
uniform sampler2D uMeshColor;

float meshDepth() {
    float t = texelFetch(uMeshDepth, ivec2(gl_FragCoord.xy), 0).r;
    return t > 0.0 ? t : 3.0e38;
}

// The mesh's linear colour (alpha 1) at this pixel; alpha 0 where no mesh is drawn.
vec4 meshColor() {
    vec4 c = texelFetch(uMeshColor, ivec2(gl_FragCoord.xy), 0);
    return vec4(pow(c.rgb, vec3(2.2)), c.a);
}

// The depth of the raster meshes drawn before the march: the ray parameter t of the
// nearest mesh at this pixel (a miss: a huge value). The march and the ground stop there.
#define MESH_DEPTH
uniform sampler2D uMeshDepth;

float meshDepth() {
    float t = texelFetch(uMeshDepth, ivec2(gl_FragCoord.xy), 0).r;
    return t > 0.0 ? t : 3.0e38;
}

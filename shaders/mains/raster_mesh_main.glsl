// A raster mesh's fragment: the point of the triangle the pixel's ray meets, shaded with
// the scene's lights, shadows and ambient occlusion (the SDF scene casts onto the mesh).
// Writes the gamma-encoded colour, the ray parameter t (the render's depth convention)
// and the unit normal facing the eye.
in vec3 vPos;
in vec3 vNormal;
layout(location = 0) out vec4 outColor;
layout(location = 1) out float outT;
layout(location = 2) out vec4 outNormal;
uniform vec3 uMeshAlbedo;
uniform vec4 uMeshSurface;   // specular, shininess, metallic, unused
uniform vec3 uMeshEmission;

void main() {
    vec3 ro = rayOrigin(gl_FragCoord.xy);
#ifdef ORTHOGRAPHIC
    vec3 rd = uForward;
    float t = dot(vPos - uEye, uForward);
#else
    vec3 rd = normalize(vPos - ro);
    float t = length(vPos - ro);
#endif
    vec3 nor = normalize(vNormal);
    if (dot(nor, rd) > 0.0) nor = -nor;  // two-sided: the side the eye sees
    Surface s = Surface(uMeshAlbedo, uMeshSurface.x, uMeshSurface.y, uMeshSurface.z, uMeshEmission);
    vec3 col = shadeSurface(vPos, nor, rd, s, t);
#ifdef FOG_DISTANCE
    col = mix(background(rd), col, exp(-t / FOG_DISTANCE));
#endif
    outColor = vec4(gammaEncode(col), 1.0);
    outT = t;
    outNormal = vec4(nor, 0.0);
}

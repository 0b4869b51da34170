// Surfaces and their shading: Blinn-Phong lights written by sdfgl.look.shading
// (shadeSurface), hemisphere ambient light, ambient occlusion, and the material fields.
struct Surface {
    vec3 albedo;
    float specular;   // highlight strength
    float shininess;  // Blinn-Phong exponent
    float metallic;   // 0: dielectric, 1: highlight tinted by albedo and no diffuse part
    vec3 emission;    // added unlit
};

// A surface with the default material fields and the given albedo (the ground plane).
Surface defaultSurface(vec3 albedo) {
    return Surface(albedo, DEFAULT_SPECULAR, DEFAULT_SHININESS, 0.0, vec3(0.0));
}

float occlusion(vec3 pos, vec3 nor) {
#if defined(AO) && !defined(LIT_TILES)  // the coarse pass proved AO 1 on a lit tile's ground
    return calcAO(pos, nor);
#else
    return 1.0;
#endif
}

// Linear colour of surface s from the sums of the lights' diffuse and highlight terms
// and the ambient light (the lights' code is generated, see shadeSurface). A metal has no
// diffuse part; it reflects its surroundings tinted by its albedo instead (shadeSurface
// puts the background seen along the mirror direction into ambient for metals).
vec3 combineLight(Surface s, vec3 diffuse, vec3 ambient, vec3 highlight) {
    vec3 specColor = mix(vec3(s.specular), s.albedo, s.metallic);
    return s.albedo * ((1.0 - s.metallic) * diffuse + ambient) + specColor * highlight + s.emission;
}

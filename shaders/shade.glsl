// Lighting: Blinn-Phong key light, sky fill, back light, optional shadows and AO,
// sky gradient background and an optional analytic ground plane.
const vec3 KEY_DIR = vec3(0.52704628, 0.73786479, 0.42163702);  // normalize(0.5, 0.7, 0.4)
const vec3 KEY_COLOR = vec3(1.0, 0.92, 0.8);
const vec3 SKY_COLOR = vec3(0.3, 0.38, 0.5);
const vec3 BACK_COLOR = vec3(0.16, 0.14, 0.12);

vec3 background(vec3 rd) {
    float h = clamp(rd.y, -1.0, 1.0);
    vec3 horizon = vec3(0.86, 0.88, 0.91);
    vec3 zenith = vec3(0.38, 0.56, 0.84);
    vec3 below = vec3(0.55, 0.54, 0.52);
    return h >= 0.0 ? mix(horizon, zenith, sqrt(h)) : mix(horizon, below, sqrt(-h));
}

float lightVisibility(vec3 pos, vec3 nor, float t) {
    float vis = 1.0;
#ifdef SHADOWS
    vec2 range = sceneRange(pos, KEY_DIR);
    float start = max(range.x, 4.0 * hitEpsilon(t));
    if (range.x <= range.y) {
        vis = shadow(pos + nor * 2.0 * hitEpsilon(t), KEY_DIR, start, range.y);
    }
#endif
    return vis;
}

float occlusion(vec3 pos, vec3 nor) {
#ifdef AO
    return calcAO(pos, nor);
#else
    return 1.0;
#endif
}

// Linear-space colour of a surface point with normal nor and albedo, seen along rd.
vec3 shadeSurface(vec3 pos, vec3 nor, vec3 rd, vec3 albedo, float t) {
    float dif = clamp(dot(nor, KEY_DIR), 0.0, 1.0);
    float vis = dif > 0.0 ? lightVisibility(pos, nor, t) : 0.0;
    float occ = occlusion(pos, nor);
    float sky = 0.5 + 0.5 * nor.y;
    float back = clamp(dot(nor, normalize(vec3(-KEY_DIR.x, 0.0, -KEY_DIR.z))), 0.0, 1.0);
    vec3 hv = normalize(KEY_DIR - rd);
    float spe = pow(clamp(dot(nor, hv), 0.0, 1.0), 48.0) * dif * vis;
    vec3 light = KEY_COLOR * dif * vis + SKY_COLOR * sky * occ + BACK_COLOR * back * occ;
    return albedo * light + 0.25 * spe * KEY_COLOR;
}

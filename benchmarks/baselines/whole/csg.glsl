// A whole fragment shader written by hand for the CSG scene (examples/csg.py), the way a
// Shadertoy author would type it (after Inigo Quilez's articles, MIT): a fixed march, the
// tetrahedron normal, the improved soft shadow and five-tap ambient occlusion, and the
// same lights, colours and sky as sdfgl's default look. Nothing in it knows where the
// scene is. Its uniforms are the camera ones sdfgl sets on every program.
uniform vec2 uResolution;
uniform vec3 uEye;
uniform vec3 uRight;
uniform vec3 uUp;
uniform vec3 uForward;
uniform float uTanHalfFov;

layout(location = 0) out vec4 outColor;

float sdBox(vec3 p, vec3 b) {
    vec3 q = abs(p) - b;
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

float sdCylinder(vec3 p, float r, float h) {
    vec2 d = abs(vec2(length(p.xz), p.y)) - vec2(r, h);
    return min(max(d.x, d.y), 0.0) + length(max(d, 0.0));
}

// map() and mapColor(): benchmarks/baselines/csg.glsl, inserted here by the bench
#include "../csg.glsl"

float march(vec3 ro, vec3 rd) {
    float t = 0.0;
    for (int i = 0; i < 128; i++) {
        float h = map(ro + rd * t);
        if (h < 0.0005 * t) return t;
        t += h;
        if (t > 20.0) break;
    }
    return -1.0;
}

vec3 calcNormal(vec3 p) {
    const vec2 k = vec2(1.0, -1.0);
    const float e = 0.0005;
    return normalize(k.xyy * map(p + k.xyy * e) + k.yyx * map(p + k.yyx * e)
                     + k.yxy * map(p + k.yxy * e) + k.xxx * map(p + k.xxx * e));
}

float softShadow(vec3 ro, vec3 rd, float tmin, float tmax) {
    float res = 1.0;
    float t = tmin;
    float ph = 1e20;
    for (int i = 0; i < 64; i++) {
        float h = map(ro + rd * t);
        float y = h * h / (2.0 * ph);
        float d = sqrt(max(h * h - y * y, 0.0));
        res = min(res, 8.0 * d / max(t - y, 1e-6));
        ph = h;
        t += clamp(h, 0.003, 0.375);
        if (res < 1e-4 || t > tmax) break;
    }
    res = clamp(res, 0.0, 1.0);
    return res * res * (3.0 - 2.0 * res);
}

float calcAO(vec3 pos, vec3 nor) {
    float occ = 0.0;
    float sca = 1.0;
    for (int i = 0; i < 5; i++) {
        float h = (0.01 + 0.12 * float(i) / 4.0) * 0.75;
        float d = map(pos + h * nor);
        occ += (h - d) * sca / 0.75;
        sca *= 0.95;
    }
    return clamp(1.0 - 3.0 * occ, 0.0, 1.0);
}

vec3 background(vec3 rd) {
    float h = clamp(rd.y, -1.0, 1.0);
    vec3 horizon = vec3(0.86, 0.88, 0.91);
    vec3 zenith = vec3(0.38, 0.56, 0.84);
    vec3 below = vec3(0.55, 0.54, 0.52);
    return h >= 0.0 ? mix(horizon, zenith, sqrt(h)) : mix(horizon, below, sqrt(-h));
}

vec3 shade(vec3 pos, vec3 nor, vec3 rd) {
    vec3 albedo = mapColor(pos);
    float occ = calcAO(pos, nor);
    vec3 L = vec3(0.527046263, 0.737864792, 0.421637028);
    float dif = clamp(dot(nor, L), 0.0, 1.0);
    if (dif > 0.0) dif *= softShadow(pos + nor * 0.001, L, 0.01, 4.0);
    vec3 key = vec3(1.0, 0.92, 0.8) * dif;
    vec3 highlight = key * pow(clamp(dot(nor, normalize(L - rd)), 0.0, 1.0), 48.0);
    vec3 fill = vec3(0.16, 0.14, 0.12) * clamp(dot(nor, vec3(-0.780868828, 0.0, -0.624695063)), 0.0, 1.0) * occ;
    vec3 ambient = vec3(0.3, 0.38, 0.5) * ((0.5 + 0.5 * nor.y) * occ);
    return albedo * (key + fill + ambient) + vec3(0.25) * highlight;
}

void main() {
    vec2 ndc = (2.0 * gl_FragCoord.xy - uResolution) / uResolution.y;
    vec3 rd = normalize(uForward + uTanHalfFov * (ndc.x * uRight + ndc.y * uUp));
    float t = march(uEye, rd);
    vec3 col = background(rd);
    if (t > 0.0) {
        vec3 pos = uEye + rd * t;
        col = shade(pos, calcNormal(pos), rd);
    }
    outColor = vec4(pow(clamp(col, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}

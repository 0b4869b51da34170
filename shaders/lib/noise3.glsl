// 3D gradient noise (quintic fade, gradients at the eight cube corners (+-1, +-1, +-1)
// picked by three bits of an integer hash: pcg3d, Jarzynski & Olano 2020), so the GPU and
// the float64 twin pick the same gradients. A gradient table indexed per pixel would be
// 30x slower on llvmpipe. Values lie in about [-1.5, 1.5].
uvec3 pcg3d(uvec3 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    return v;
}

vec3 noiseGradient(ivec3 cell) {
    uint h = pcg3d(uvec3(cell)).x;
    return vec3(float(h & 1u), float((h >> 1u) & 1u), float((h >> 2u) & 1u)) * 2.0 - 1.0;
}

float gradientNoise3(vec3 p) {  // not "noise3": desktop GLSL has a built-in vec3 noise3()
    ivec3 i = ivec3(floor(p));
    vec3 f = p - floor(p);
    vec3 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    float n000 = dot(noiseGradient(i), f);
    float n100 = dot(noiseGradient(i + ivec3(1, 0, 0)), f - vec3(1, 0, 0));
    float n010 = dot(noiseGradient(i + ivec3(0, 1, 0)), f - vec3(0, 1, 0));
    float n110 = dot(noiseGradient(i + ivec3(1, 1, 0)), f - vec3(1, 1, 0));
    float n001 = dot(noiseGradient(i + ivec3(0, 0, 1)), f - vec3(0, 0, 1));
    float n101 = dot(noiseGradient(i + ivec3(1, 0, 1)), f - vec3(1, 0, 1));
    float n011 = dot(noiseGradient(i + ivec3(0, 1, 1)), f - vec3(0, 1, 1));
    float n111 = dot(noiseGradient(i + ivec3(1, 1, 1)), f - vec3(1, 1, 1));
    return mix(mix(mix(n000, n100, u.x), mix(n010, n110, u.x), u.y),
               mix(mix(n001, n101, u.x), mix(n011, n111, u.x), u.y), u.z);
}

// Fractal sum of `octaves` noise layers, each twice the frequency and half the
// amplitude of the last; a fixed offset per octave decorrelates the layers.
float fbm3(vec3 p, int octaves) {
    float sum = 0.0;
    float amp = 1.0;
    for (int o = 0; o < octaves; o++) {
        sum += amp * gradientNoise3(p + float(o) * vec3(17.13, 31.71, 47.37));
        p *= 2.0;
        amp *= 0.5;
    }
    return sum;
}

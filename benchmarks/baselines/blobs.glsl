// Hand-written map() for the "blobs" scene (sdfgl/bench_model.py): four spheres blended
// smoothly, a rounded box turned 30 degrees about Y, and a torus.
float blobs(vec3 p) {
    float d = opSmin(length(p - vec3(-0.6, 0.0, 0.0)) - 0.5, length(p - vec3(0.1, 0.3, 0.2)) - 0.45, 0.3);
    d = opSmin(d, length(p - vec3(0.7, -0.1, -0.1)) - 0.4, 0.3);
    return opSmin(d, length(p - vec3(0.0, 0.6, -0.3)) - 0.35, 0.3);
}

float map(vec3 p) {
    vec3 q = p - vec3(0.0, -0.9, 0.0);
    q.xz = mat2(0.8660254, -0.5, 0.5, 0.8660254) * q.xz;
    float box = sdRoundBox(q, vec3(1.2, 0.15, 0.6), 0.1);
    float ring = sdTorus(p - vec3(0.0, 0.2, 0.0), vec2(1.2, 0.08));
    return min(min(blobs(p), box), ring);
}

vec3 mapColor(vec3 p) {
    vec3 q = p - vec3(0.0, -0.9, 0.0);
    q.xz = mat2(0.8660254, -0.5, 0.5, 0.8660254) * q.xz;
    float b = blobs(p);
    float box = sdRoundBox(q, vec3(1.2, 0.15, 0.6), 0.1);
    float ring = sdTorus(p - vec3(0.0, 0.2, 0.0), vec2(1.2, 0.08));
    if (b < box && b < ring) return vec3(0.3, 0.6, 0.9);
    return box < ring ? vec3(0.6, 0.5, 0.4) : vec3(0.9, 0.75, 0.2);
}

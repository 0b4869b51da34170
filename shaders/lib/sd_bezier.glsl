// Two Newton steps on the nearest-point condition (B(t) - pos) . B'(t) = 0: the closed-form
// cubic loses digits to cancellation in float32. d = A - pos, c = 2 (B - A), b = A - 2B + C.
float bezierPolish(float t, vec3 b, vec3 c, vec3 d) {
    for (int i = 0; i < 2; i++) {
        vec3 e = d + (c + b * t) * t;
        vec3 de = c + 2.0 * b * t;
        float g = dot(e, de);
        float dg = dot(de, de) + 2.0 * dot(e, b);
        t = clamp(t - (dg > 0.0 ? g / dg : 0.0), 0.0, 1.0);
    }
    return t;
}

// Distance to the quadratic Bezier curve A B C: the nearest parameter solves a cubic,
// in closed form (Inigo Quilez, MIT; 3D version), then polished.
float sdBezier(vec3 pos, vec3 A, vec3 B, vec3 C) {
    vec3 a = B - A;
    vec3 b = A - 2.0 * B + C;
    vec3 c = a * 2.0;
    vec3 d = A - pos;
    float kk = 1.0 / dot(b, b);
    float kx = kk * dot(a, b);
    float ky = kk * (2.0 * dot(a, a) + dot(d, b)) / 3.0;
    float kz = kk * dot(d, a);
    float p = ky - kx * kx;
    float q = kx * (2.0 * kx * kx - 3.0 * ky) + kz;
    float h = q * q + 4.0 * p * p * p;
    float res;
    if (h >= 0.0) {
        h = sqrt(h);
        vec2 x = (vec2(h, -h) - q) / 2.0;
        vec2 uv = sign(x) * pow(abs(x), vec2(1.0 / 3.0));
        float t = bezierPolish(clamp(uv.x + uv.y - kx, 0.0, 1.0), b, c, d);
        vec3 e = d + (c + b * t) * t;
        res = dot(e, e);
    } else {
        float z = sqrt(-p);
        float v = acos(clamp(q / (p * z * 2.0), -1.0, 1.0)) / 3.0;
        float m = cos(v);
        float n = sin(v) * 1.732050808;
        vec3 t = clamp(vec3(m + m, -n - m, n - m) * z - kx, 0.0, 1.0);
        t.x = bezierPolish(t.x, b, c, d);
        t.y = bezierPolish(t.y, b, c, d);
        vec3 e = d + (c + b * t.x) * t.x;
        vec3 f = d + (c + b * t.y) * t.y;
        res = min(dot(e, e), dot(f, f));
    }
    return sqrt(res);
}

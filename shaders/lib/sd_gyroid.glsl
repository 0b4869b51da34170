// A gyroid sheet of thickness 2 h: |g| / (f sqrt 6) - h with g = sin x cos y + sin y cos z
// + sin z cos x at frequency f; |grad g| <= f sqrt 6, so this is a 1-Lipschitz bound.
float sdGyroid(vec3 p, float f, float h) {
    vec3 q = p * f;
    float g = dot(sin(q), cos(q.yzx));
    return abs(g) / (f * 2.44948974) - h;
}

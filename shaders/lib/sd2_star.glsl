// Exact signed distance to a star with n points of outer radius r; m in [2, n] sets the
// inner angle (m = 2: a regular n-gon) (Inigo Quilez, MIT).
float sd2Star(vec2 p, float r, float n, float m) {
    float an = 3.14159265 / n;
    float en = 3.14159265 / m;
    vec2 acs = vec2(cos(an), sin(an));
    vec2 ecs = vec2(cos(en), sin(en));
    float bn = mod(atan(p.x, (p.x == 0.0 && p.y == 0.0) ? 1.0 : p.y), 2.0 * an) - an;
    p = length(p) * vec2(cos(bn), abs(sin(bn)));
    p -= r * acs;
    p += ecs * clamp(-dot(p, ecs), 0.0, r * acs.y / ecs.y);
    return length(p) * sign(p.x);
}

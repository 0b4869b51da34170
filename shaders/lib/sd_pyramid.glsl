// Exact distance to a pyramid of height h over the unit square [-0.5, 0.5]^2 in XZ at
// y = 0 (Inigo Quilez, MIT). Below the base the nearest point is on the base square (the
// faces lean inward), and inside the base plane bounds the distance too: both added here,
// where the slanted faces alone would overstate it.
float sdPyramid(vec3 p, float h) {
    if (p.y < 0.0) return length(vec3(max(abs(p.x) - 0.5, 0.0), p.y, max(abs(p.z) - 0.5, 0.0)));
    float m2 = h * h + 0.25;
    p.xz = abs(p.xz);
    p.xz = (p.z > p.x) ? p.zx : p.xz;
    p.xz -= 0.5;
    vec3 q = vec3(p.z, h * p.y - 0.5 * p.x, h * p.x + 0.5 * p.y);
    float s = max(-q.x, 0.0);
    float t = clamp((q.y - 0.5 * p.z) / (m2 + 0.25), 0.0, 1.0);
    float a = m2 * (q.x + s) * (q.x + s) + q.y * q.y;
    float b = m2 * (q.x + 0.5 * t) * (q.x + 0.5 * t) + (q.y - m2 * t) * (q.y - m2 * t);
    float d2 = min(q.y, -q.x * m2 - q.y * 0.5) > 0.0 ? 0.0 : min(a, b);
    return max(sqrt((d2 + q.z * q.z) / m2) * sign(max(q.z, -p.y)), -p.y);
}

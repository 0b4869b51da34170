// Regular solids as the largest distance to their face planes (a 1-Lipschitz bound, exact
// inside): faces at distance r from the centre. Normals: the classic ones (e.g. in Inigo
// Quilez's and fogleman/sdf's solids); the sign-symmetric sets are folded by abs(p).
const float PHI = 1.6180339887;

float sdTetrahedron(vec3 p, float r) {
    float a = max(p.x + p.y + p.z, -p.x - p.y + p.z);
    float b = max(p.x - p.y - p.z, -p.x + p.y - p.z);
    return max(a, b) * 0.57735027 - r;
}

float sdDodecahedron(vec3 p, float r) {
    vec3 q = abs(p);
    vec3 n = normalize(vec3(0.0, 1.0, PHI));
    return max(max(dot(q, n), dot(q, n.zxy)), dot(q, n.yzx)) - r;
}

float sdIcosahedron(vec3 p, float r) {
    vec3 q = abs(p);
    vec3 n = normalize(vec3(0.0, 1.0 / PHI, PHI));
    float a = max(max(dot(q, n), dot(q, n.zxy)), dot(q, n.yzx));
    return max(a, dot(q, vec3(0.57735027))) - r;
}

// Exact signed distance to the plane through point o with unit normal n (solid below).
float sdPlane(vec3 p, vec3 n, vec3 o) {
    return dot(p - o, n);
}

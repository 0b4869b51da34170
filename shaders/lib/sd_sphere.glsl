// Exact distance to a sphere of radius r at the origin.
float sdSphere(vec3 p, float r) {
    return length(p) - r;
}

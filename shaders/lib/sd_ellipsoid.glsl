// Distance bound to an ellipsoid with semi-axes r: the larger of two 1-Lipschitz lower
// bounds, (|p/r| - 1) min(r) (tight near the surface along the short axis) and
// |p| - max(r) (tight far away). Finite everywhere, the centre included.
float sdEllipsoid(vec3 p, vec3 r) {
    float near = (length(p / r) - 1.0) * min(r.x, min(r.y, r.z));
    float far = length(p) - max(r.x, max(r.y, r.z));
    return max(near, far);
}

// The inverse of the rotation by angle a (radians) about unit axis k, applied to p
// (Rodrigues' formula with -a): takes a world point into the rotated child's frame.
vec3 opRotateInverse(vec3 p, vec3 k, float a) {
    float c = cos(a);
    float s = sin(a);
    return p * c - cross(k, p) * s + k * dot(k, p) * (1.0 - c);
}

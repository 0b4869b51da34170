// Twist about the Y axis: the XZ plane turns by k radians per unit of y.
vec3 opTwist(vec3 p, float k) {
    float a = k * p.y;
    float c = cos(a);
    float s = sin(a);
    return vec3(c * p.x - s * p.z, p.y, s * p.x + c * p.z);
}

// Bend in the XY plane: the point turns about the Z axis by k radians per unit of x
// (Inigo Quilez's cheap bend, MIT).
vec3 opBend(vec3 p, float k) {
    float a = k * p.x;
    float c = cos(a);
    float s = sin(a);
    return vec3(c * p.x - s * p.y, s * p.x + c * p.y, p.z);
}

// Turn p about the Y axis by -k * angle (k a whole number of sectors): the sector-local point.
vec3 opPolarSector(vec3 p, float k, float angle) {
    float a = -k * angle;
    float c = cos(a);
    float s = sin(a);
    return vec3(c * p.x - s * p.z, p.y, s * p.x + c * p.z);
}

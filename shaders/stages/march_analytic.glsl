// A lone sphere or plane is intersected in closed form, not marched (0 map() calls).
// ANALYTIC_SPHERE (centre, radius) or ANALYTIC_PLANE (unit normal, offset: dot(n, p) = d
// on the plane, solid where dot(n, p) < d). A ray starting inside hits at tmin, as for
// the marchers.
float march(vec3 ro, vec3 rd, float tmin, float tmax, inout int steps) {
#ifdef ANALYTIC_SPHERE
    vec3 oc = ro + rd * tmin - ANALYTIC_SPHERE.xyz;
    float b = dot(oc, rd);
    float c = dot(oc, oc) - ANALYTIC_SPHERE.w * ANALYTIC_SPHERE.w;
    if (c < 0.0) return tmin;
    float h = b * b - c;
    if (h < 0.0 || b > 0.0) return -1.0;
    float t = tmin + c / (-b + sqrt(h));  // the near root, in the form without cancellation
#else
    float side = dot(ANALYTIC_PLANE.xyz, ro + rd * tmin) - ANALYTIC_PLANE.w;
    if (side < 0.0) return tmin;
    float den = dot(ANALYTIC_PLANE.xyz, rd);
    if (den >= 0.0) return -1.0;
    float t = tmin - side / den;
#endif
    return t <= tmax ? t : -1.0;
}

// A tube of radius r along the polyline through the TUBEN points v: the nearest of its
// segments (exact outside, like any union). TUBEN is replaced per point count.
// requires: sd_segment
float sdTubeTUBEN(vec3 p, vec3 v[TUBEN], float r) {
    float d = sdSegment(p, v[0], v[1]);
    for (int i = 2; i < TUBEN; i++) {
        d = min(d, sdSegment(p, v[i - 1], v[i]));
    }
    return d - r;
}

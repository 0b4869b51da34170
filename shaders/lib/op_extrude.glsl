// Extrude a 2D distance d2 (in the XY plane) along Z to half length h (IQ, MIT): exact
// where d2 is.
float opExtrude(float d2, float pz, float h) {
    vec2 w = vec2(d2, abs(pz) - h);
    return min(max(w.x, w.y), 0.0) + length(max(w, 0.0));
}

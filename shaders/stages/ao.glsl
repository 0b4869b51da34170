// Ambient occlusion from five distance samples along the normal (Inigo Quilez, MIT),
// the sample spacing scaled to the scene size. On implicit fields the samples are
// clamped to [0, h], so the estimate stays in range where f is far from a distance.
// The samples are taken farthest first. Where the field is a distance bound with Lipschitz
// factor AO_LIPSCHITZ (L), sample i lies at d_i >= d_4 - L (h_4 - h_i); so where d_4 reaches
// max over i of h_i + L (h_4 - h_i), every sample lies at least its own height from the
// surface, every term is <= 0 and the occlusion is 1: the other four samples are not taken
// (a block of pixels whose lanes all find that leaves the loop). The test allows a thousandth
// of the bound for float32's rounding of d_4, which moves the occlusion by less than 0.002.
// One map() call site, in a loop that cannot be unrolled: Mesa inlines every call.
float calcAO(vec3 pos, vec3 nor) {
    float occ = 0.0;
    float sca = 0.81450625;  // 0.95^4: the farthest sample's weight
    bool open = false;
    for (int i = uZero; i < 5 && !open; i++) {
        float h = aoSampleHeight(4 - i);
        float d = map(pos + h * nor);
#ifdef IMPLICIT_FIELD
        d = clamp(d, 0.0, h);  // an implicit field is no distance: a safe estimate, never NaN
#endif
        occ += (h - d) * sca / (SCENE_SCALE * 0.5);
        sca /= 0.95;
#ifdef AO_LIPSCHITZ
        if (i == 0) open = d >= 0.999 * (aoSampleHeight(0) + AO_LIPSCHITZ * (h - aoSampleHeight(0)));
#endif
    }
    return open ? 1.0 : clamp(1.0 - 3.0 * occ, 0.0, 1.0);
}

// Ambient occlusion from five distance samples along the normal (Inigo Quilez, MIT),
// the sample spacing scaled to the scene size. On implicit fields the samples are
// clamped to [0, h], so the estimate stays in range where f is far from a distance.
float calcAO(vec3 pos, vec3 nor) {
    float occ = 0.0;
    float sca = 1.0;
    for (int i = uZero; i < 5; i++) {
        float h = aoSampleHeight(i);
        float d = map(pos + h * nor);
#ifdef IMPLICIT_FIELD
        d = clamp(d, 0.0, h);  // an implicit field is no distance: a safe estimate, never NaN
#endif
        occ += (h - d) * sca / (SCENE_SCALE * 0.5);
        sca *= 0.95;
    }
    return clamp(1.0 - 3.0 * occ, 0.0, 1.0);
}

// How much of a light in direction L (up to distance tmax) reaches pos: the shadow march
// from just above the surface, clipped to the scene box. The code generator writes one
// copy per shadow kind, named after that kind's (renamed) shadow function.
float SHADOWFNVisibility(vec3 pos, vec3 nor, float t, vec3 L, float tmax) {
    float vis = 1.0;
#ifndef LIT_TILES  // the coarse pass proved no shadow ray of a lit tile's ground enters the box
    vec2 range = sceneRange(pos, L);
    range.y = min(range.y, tmax);
    float start = max(range.x, 4.0 * hitEpsilon(t));
    if (range.x <= range.y) {
        vis = SHADOWFN(pos + nor * 2.0 * hitEpsilon(t), L, start, range.y);
    }
#endif
    return vis;
}

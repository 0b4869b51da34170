// Soft shadow with Inigo Quilez's improved penumbra estimate (MIT), generalised to steps
// that are not the previous distance: 1 lit, 0 in shadow. The previous unbounding sphere
// (radius ph, one step dt behind) and the current one (radius h) meet on a circle at
// y = (h^2 + dt^2 - ph^2) / (2 dt) behind the current sample and radius
// sqrt(h^2 - y^2); that circle bounds how close an occluder can pass. Where the spheres
// do not meet (|y| >= h: the step grew faster than the distance, as it does leaving a
// surface towards the light), the plain estimate h / t applies. (IQ's y = h^2 / (2 ph)
// assumes dt = ph and gives 0 there: a dark speck where the normal faces the light.)
float shadow(vec3 ro, vec3 rd, float tmin, float tmax) {
    float res = 1.0;
    float t = tmin;
    float ph = -1.0;
    float dt = 0.0;
    for (int i = 0; i < 96; i++) {
        float h = map(ro + rd * t);
        float d = h;
        float tt = t;
        if (ph > 0.0 && h > 0.0) {
            float y = (h * h + dt * dt - ph * ph) / (2.0 * dt);
            if (abs(y) < h) {
                d = sqrt(h * h - y * y);
                tt = t - y;
            }
        }
        res = min(res, 8.0 * d / max(tt, 1e-6 * SCENE_SCALE));
        ph = h;
        dt = clamp(h, 0.002 * SCENE_SCALE, 0.25 * SCENE_SCALE);
        t += dt;
        if (res < 1e-4 || t > tmax) break;
    }
    res = clamp(res, 0.0, 1.0);
    return res * res * (3.0 - 2.0 * res);
}

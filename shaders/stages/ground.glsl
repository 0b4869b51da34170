// The analytic ground plane y = GROUND_Y: intersected in closed form, never marched.
// Ray parameter where rd meets the ground plane y = GROUND_Y, or -1.0.
float groundHit(vec3 ro, vec3 rd) {
    if (rd.y >= 0.0 || ro.y <= GROUND_Y) return -1.0;
    float t = (GROUND_Y - ro.y) / rd.y;
    return t <= MAX_DIST * 10.0 ? t : -1.0;
}

vec3 groundAlbedo(vec3 pos) {
    vec2 cell = floor(pos.xz / SCENE_SCALE * 2.0);
    float checker = mod(cell.x + cell.y, 2.0);
    return mix(vec3(0.62, 0.61, 0.58), vec3(0.72, 0.71, 0.68), checker);
}

// Hand-written map() for the demo scene (sdfgl/demo.py): nine objects, each a few lines.
float demoCsg(vec3 p, out bool drilled) {
    vec3 q = p - vec3(0.0, 0.75, 0.0);
    float ball = max(length(q) - 1.0, sdBox(q, vec3(0.75)));
    float drill = min(min(sdCylinder(q.yxz, 0.5, 2.0), sdCylinder(q, 0.5, 2.0)), sdCylinder(q.xzy, 0.5, 2.0));
    drilled = ball <= -drill;
    return max(ball, -drill);
}

float demoPart(int i, vec3 p) {
    if (i == 1) {
        vec3 q = p - vec3(2.2, 0.65, 0.0);
        q.yz = mat2(0.93969262, -0.34202014, 0.34202014, 0.93969262) * q.yz;
        return sdTorus(q, vec2(0.5, 0.15));
    }
    if (i == 2) return sdCapsule(p - vec3(-2.2, 0.2, 0.0), vec3(-0.4, 0.0, 0.0), vec3(0.4, 0.5, 0.0), 0.2);
    if (i == 3) return sdRoundBox(p - vec3(0.0, 0.4, -2.2), vec3(0.4), 0.15);
    if (i == 4) return sdCone(p - vec3(2.0, 0.5, -1.8), 0.5, 0.45, 0.1);
    if (i == 5) return sdEllipsoid(p - vec3(-2.0, 0.3, -1.8), vec3(0.6, 0.3, 0.4));
    if (i == 6) return sdOctahedron(p - vec3(2.0, 0.5, 1.9), 0.5);
    if (i == 7) return sdHexPrism(p - vec3(-2.0, 0.4, 1.9), 0.4, 0.4);
    vec3 q = p - vec3(0.0, 0.45, 2.1);
    return opSmin(length(q - vec3(-0.25, 0.0, 0.0)) - 0.45, length(q - vec3(0.3, 0.15, 0.0)) - 0.35, 0.3);
}

float map(vec3 p) {
    bool drilled;
    float d = demoCsg(p, drilled);
    d = min(d, demoPart(1, p));
    d = min(d, demoPart(2, p));
    d = min(d, demoPart(3, p));
    d = min(d, demoPart(4, p));
    d = min(d, demoPart(5, p));
    d = min(d, demoPart(6, p));
    d = min(d, demoPart(7, p));
    return min(d, demoPart(8, p));
}

vec3 mapColor(vec3 p) {
    const vec3 colors[9] = vec3[9](vec3(0.85, 0.3, 0.2), vec3(0.9, 0.75, 0.2), vec3(0.4, 0.8, 0.4),
                                   vec3(0.6, 0.4, 0.8), vec3(0.9, 0.5, 0.2), vec3(0.8, 0.8, 0.85),
                                   vec3(0.2, 0.7, 0.7), vec3(0.75, 0.3, 0.5), vec3(0.3, 0.6, 0.9));
    bool drilled;
    float best = demoCsg(p, drilled);
    int k = 0;
    for (int i = 1; i < 9; i++) {
        float d = demoPart(i, p);
        if (d < best) {
            best = d;
            k = i;
        }
    }
    return k == 0 && drilled ? vec3(0.95, 0.8, 0.3) : colors[k];
}

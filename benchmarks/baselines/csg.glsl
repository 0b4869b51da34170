// Hand-written map() for the CSG scene (examples/csg.py): what a person would type.
float map(vec3 p) {
    float ball = max(length(p) - 1.0, sdBox(p, vec3(0.75)));
    float drill = min(min(sdCylinder(p.yxz, 0.5, 2.0), sdCylinder(p, 0.5, 2.0)), sdCylinder(p.xzy, 0.5, 2.0));
    return max(ball, -drill);
}

vec3 mapColor(vec3 p) {
    float ball = max(length(p) - 1.0, sdBox(p, vec3(0.75)));
    float drill = min(min(sdCylinder(p.yxz, 0.5, 2.0), sdCylinder(p, 0.5, 2.0)), sdCylinder(p.xzy, 0.5, 2.0));
    return ball > -drill ? vec3(0.85, 0.3, 0.2) : vec3(0.95, 0.8, 0.3);
}

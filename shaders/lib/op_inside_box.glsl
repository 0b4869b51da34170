// True where p lies inside the axis-aligned box [lo, hi].
bool opInsideBox(vec3 p, vec3 lo, vec3 hi) {
    return all(greaterThanEqual(p, lo)) && all(lessThanEqual(p, hi));
}

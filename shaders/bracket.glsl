// Root of f(t) = map(ro + t rd) in [a, b] where f(a) > 0 >= f(b): the Illinois variant
// of regula falsi, at most 24 map() calls, stopping when the bracket is below a
// hundredth of the hit threshold. Returns an exact root if it meets one, else the
// middle of the final bracket.
float bracketRoot(vec3 ro, vec3 rd, float a, float fa, float b, float fb, inout int steps) {
    int side = 0;
    for (int i = 0; i < 24; i++) {
        if (fb == 0.0) return b;
        if (b - a < 0.01 * hitEpsilon(b)) break;
        float c = (fa - fb) != 0.0 ? b - fb * (b - a) / (fb - fa) : 0.5 * (a + b);
        c = clamp(c, a + 0.01 * (b - a), b - 0.01 * (b - a));
        float fc = map(ro + rd * c);
        steps++;
        if (fc <= 0.0) {
            b = c;
            fb = fc;
            if (side == -1) fa *= 0.5;
            side = -1;
        } else {
            a = c;
            fa = fc;
            if (side == 1) fb *= 0.5;
            side = 1;
        }
    }
    return 0.5 * (a + b);
}

// Smooth minimum of (rgb, distance) pairs: the colours blend across the blend region
// with a weight that is 0.5 where a = b and 0 where |a - b| >= k, so it never jumps.
vec4 opSminColor(vec4 a, vec4 b, float k) {
    float h = max(k - abs(a.w - b.w), 0.0) / k;
    float m = 0.5 * h * h;
    float d = min(a.w, b.w) - h * h * k * 0.25;
    return (a.w < b.w) ? vec4(mix(a.rgb, b.rgb, m), d) : vec4(mix(b.rgb, a.rgb, m), d);
}

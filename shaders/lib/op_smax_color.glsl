// Smooth maximum of (rgb, distance) pairs, colours blended as in opSminColor.
vec4 opSmaxColor(vec4 a, vec4 b, float k) {
    float h = max(k - abs(a.w - b.w), 0.0) / k;
    float m = 0.5 * h * h;
    float d = max(a.w, b.w) + h * h * k * 0.25;
    return (a.w > b.w) ? vec4(mix(a.rgb, b.rgb, m), d) : vec4(mix(b.rgb, a.rgb, m), d);
}

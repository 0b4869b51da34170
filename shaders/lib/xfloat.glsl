// Extended-range floats for implicit fields whose values overflow float32 (x^64 beyond
// |x| = 4, an exp of a large argument). A value is vec2(m, e) = m * 2^e with 1 <= |m| < 2
// (zero: m = 0, e = XF_ZERO) and e an integer held in a float. Scaling by exact powers of
// two keeps plain float32 rounding; the range is 2^(+-1e7). Only the implicit fields that
// can overflow use it (sdfgl/nodes/xfloat.py decides and writes the calls).
const float XF_ZERO = -1.0e6;

// 2^k for an integer -126 <= k <= 127, built from its bits (cheaper than exp2)
float xfPow2(float k) {
    return intBitsToFloat((int(k) + 127) << 23);
}

vec2 xfNorm(float m, float e) {
    if (m == 0.0) return vec2(0.0, XF_ZERO);
    if (isinf(m) || isnan(m)) return vec2(m, e);
    int bits = floatBitsToInt(m);
    int k = ((bits >> 23) & 255) - 127;  // the float's own exponent (a subnormal m: via log2)
    if (k == -127) return vec2(m * 8388608.0 * 2.0, e - 24.0);
    return vec2(intBitsToFloat((bits & ~0x7F800000) | 0x3F800000), max(e + float(k), XF_ZERO));
}

// the plain float (clamped to +-2^127 instead of overflowing)
float xfVal(vec2 a) {
    return a.x * exp2(clamp(a.y, -149.0, 125.0));
}

vec2 xfAdd(vec2 a, vec2 b) {
    float e = max(a.y, b.y);
    return xfNorm(a.x * xfPow2(max(a.y - e, -126.0)) + b.x * xfPow2(max(b.y - e, -126.0)), e);
}

vec2 xfMul(vec2 a, vec2 b) {
    return xfNorm(a.x * b.x, a.y + b.y);
}

vec2 xfDiv(vec2 a, vec2 b) {
    return xfNorm(a.x / b.x, a.y - b.y);
}

// a^n for an integer 0 < n <= 32 (|m|^n < 2^64 stays a float); the sign kept for odd n
vec2 xfPowi(vec2 a, float n) {
    float m = pow(abs(a.x), n);
    return xfNorm(mod(n, 2.0) == 1.0 ? sign(a.x) * m : m, a.y * n);
}

// |a|^r for any real r, through the logarithm (as GLSL's pow, meant for a > 0)
vec2 xfPow(vec2 a, float r) {
    if (a.x == 0.0) return r > 0.0 ? vec2(0.0, XF_ZERO) : vec2(1.0, -XF_ZERO);  // 0^-r: huge
    float l = r * (log2(abs(a.x)) + a.y);
    float e = floor(l);
    return vec2(exp2(l - e), e);
}

vec2 xfSqrt(vec2 a) {
    float odd = a.y - 2.0 * floor(0.5 * a.y);
    return xfNorm(sqrt(a.x * exp2(odd)), 0.5 * (a.y - odd));
}

vec2 xfExp(vec2 a) {
    float l = xfVal(a) * 1.4426950408889634;
    float e = floor(l);
    return vec2(exp2(l - e), e);
}

vec2 xfLog(vec2 a) {
    return xfNorm(log(a.x) + a.y * 0.6931471805599453, 0.0);
}

vec2 xfNeg(vec2 a) {
    return vec2(-a.x, a.y);
}

vec2 xfAbs(vec2 a) {
    return vec2(abs(a.x), a.y);
}

// f / |g| as a plain float: the first-order distance estimate of an implicit surface,
// with |g| taken no smaller than 1e-12 (as the plain path does)
float xfRatio(vec2 f, vec2 gx, vec2 gy, vec2 gz) {
    float e = max(max(gx.y, gy.y), gz.y);
    vec3 g = vec3(gx.x * xfPow2(max(gx.y - e, -126.0)), gy.x * xfPow2(max(gy.y - e, -126.0)),
                  gz.x * xfPow2(max(gz.y - e, -126.0)));
    vec2 len = xfNorm(length(g), e);
    if (len.x == 0.0 || len.y < -40.0) len = vec2(1.0e-12, 0.0);
    return xfVal(xfDiv(f, len));
}

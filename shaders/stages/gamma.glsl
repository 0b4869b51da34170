// The pixel's gamma encoding, x^(1/2.2) of a linear colour clamped to [0, 1], without pow():
// llvmpipe evaluates pow() as exp2(log2()) with two polynomials a channel, about a third of the
// time of a pixel of sky. The fit, in x^(1/2), x^(1/4) and their products with x, was found by
// least squares reweighted towards the largest error over [0, 1] (with points down to 1e-9);
// it is off by at most 0.05 of an 8-bit level and is 0 at 0 (tests/test_gamma.py measures
// both on the GPU; benchmarks/gamma_encode.py times it against pow()).
vec3 gammaEncode(vec3 linear) {
    vec3 x = clamp(linear, 0.0, 1.0);
    vec3 s1 = sqrt(x);
    vec3 s2 = sqrt(s1);
    return clamp(1.356524813 * s1 + 0.022951297 * s2 + 0.61423321 * x - 0.792051057 * s1 * s2
                 - 0.201846473 * x * s2, 0.0, 1.0);
}

// Quadratic smooth minimum with blend radius k > 0 (Inigo Quilez, MIT). The result is
// a convex combination of the operands' gradients, so it keeps their Lipschitz bound.
float opSmin(float a, float b, float k) {
    float h = max(k - abs(a - b), 0.0) / k;
    return min(a, b) - h * h * k * 0.25;
}

// Circular smooth minimum: the blend is a quarter circle of radius k (Inigo Quilez's
// smooth-minimum article, MIT); like opSmin it never exceeds min(a, b).
float opCircular(float a, float b, float k) {
    k *= 1.0 / (1.0 - sqrt(0.5));
    float h = max(k - abs(a - b), 0.0) / k;
    return min(a, b) - k * 0.5 * (1.0 + h - sqrt(1.0 - h * (h - 2.0)));
}

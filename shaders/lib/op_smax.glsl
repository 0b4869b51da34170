// Quadratic smooth maximum with blend radius k > 0: -smin(-a, -b).
float opSmax(float a, float b, float k) {
    float h = max(k - abs(a - b), 0.0) / k;
    return max(a, b) + h * h * k * 0.25;
}

// Chamfered minimum: a 45-degree bevel where the two fields meet (the chamfer of Inigo
// Quilez's smooth-minimum article, MIT). The bevel term is (a + b - k) / 2 rather than
// / sqrt(2): the same surface, but a slope of at most 1 where a and b rise together.
float opChamfer(float a, float b, float k) {
    return min(min(a, b), (a + b - k) * 0.5);
}

// The image: trace each sample, shade, average, gamma-correct (or, in a debug view, the
// view of the pixel-centre ray); write depth, normal and step count of the pixel-centre
// ray when those outputs are on.
void main() {
    vec3 ro = rayOrigin(gl_FragCoord.xy);
#ifdef DEBUG_VIEW
    vec3 rd = rayDir(gl_FragCoord.xy);
    Hit h = tracePrimary(ro, rd);
    outColor = vec4(gammaEncode(debugView(ro, rd, h)), 1.0);
#else
#if AA == 1
    vec3 rd = rayDir(gl_FragCoord.xy);
    Hit h = tracePrimary(ro, rd);
    vec4 col = sampleColor(ro, rd, h);
#else
    vec4 col = vec4(0.0);
    for (int j = 0; j < AA; j++) {
        for (int i = 0; i < AA; i++) {
            vec2 off = (vec2(float(i), float(j)) + 0.5) / float(AA) - 0.5;
            vec3 ros = rayOrigin(gl_FragCoord.xy + off);
            vec3 rds = rayDir(gl_FragCoord.xy + off);
            col += sampleColor(ros, rds, tracePrimary(ros, rds));
        }
    }
    col /= float(AA * AA);
#ifdef AUX_OUTPUTS
    vec3 rd = rayDir(gl_FragCoord.xy);
    Hit h = tracePrimary(ro, rd);
#endif
#endif
    outColor = pixelColor(col);
#endif
#ifdef OUT_DEPTH
    outDepth = h.t;
#endif
#ifdef OUT_NORMAL
    outNormal = vec4(h.t >= 0.0 ? hitNormal(ro, rd, h) : vec3(0.0), 0.0);
#endif
#ifdef OUT_STEPS
    outSteps = float(h.steps);
#endif
}

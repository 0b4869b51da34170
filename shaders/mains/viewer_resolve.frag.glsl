#version 330 core
// The viewer's render thread: turns its working image (a low-resolution frame, or the sum of
// accumulated jittered full-resolution samples) into the display image the window presents.
uniform sampler2D uSource;
uniform float uWeight;      // 1 / number of accumulated samples (1 for a low-resolution frame)
uniform vec2 uSize;         // display image size in pixels
out vec4 outColor;

void main() {
    outColor = vec4(texture(uSource, gl_FragCoord.xy / uSize).rgb * uWeight, 1.0);
}

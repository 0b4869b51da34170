#version 330 core
// Shows the viewer's image (a low-resolution frame stretched, or the running average of
// accumulated full-resolution samples) with the text overlay on top.
uniform sampler2D uImage;
uniform sampler2D uOverlay;
uniform float uWeight;      // 1 / number of accumulated samples
uniform vec2 uWindow;       // framebuffer size in pixels
out vec4 outColor;

void main() {
    vec2 uv = gl_FragCoord.xy / uWindow;
    vec3 c = texture(uImage, uv).rgb * uWeight;
    vec4 o = texture(uOverlay, vec2(uv.x, 1.0 - uv.y));
    outColor = vec4(mix(c, o.rgb, o.a), 1.0);
}

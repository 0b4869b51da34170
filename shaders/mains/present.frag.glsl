#version 330 core
// Shows the viewer's display image (drawn by its render thread) in the view rectangle right
// of the side panel, with the text overlay on top of the whole window.
uniform sampler2D uImage;
uniform sampler2D uOverlay;
uniform vec2 uWindow;       // framebuffer size in pixels
uniform vec4 uView;         // view rectangle: x, y, width, height in pixels
uniform float uHasImage;    // 0 until the first image arrives
out vec4 outColor;

void main() {
    vec2 uv = (gl_FragCoord.xy - uView.xy) / uView.zw;
    bool inside = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0)));
    vec3 c = (inside && uHasImage > 0.5) ? texture(uImage, uv).rgb : vec3(0.1, 0.1, 0.12);
    vec4 o = texture(uOverlay, vec2(gl_FragCoord.x / uWindow.x, 1.0 - gl_FragCoord.y / uWindow.y));
    outColor = vec4(mix(c, o.rgb, o.a), 1.0);
}

#version 330 core
// A raster mesh's vertices through the camera the ray march uses: the same eye, basis and
// pixel centres (see rayDir() in stages/common.glsl), so a pixel shows the triangle point
// its ray meets. Positions are relative to the shader origin.
in vec3 inPos;
in vec3 inNormal;
out vec3 vPos;
out vec3 vNormal;
uniform vec2 uResolution;
uniform vec3 uEye;
uniform vec3 uRight;
uniform vec3 uUp;
uniform vec3 uForward;
uniform float uTanHalfFov;
uniform float uOrthoHalfHeight;
uniform float uOrtho;     // 1.0: orthographic, 0.0: perspective
uniform vec2 uNearFar;    // view depth range of the mesh (near > 0 for perspective)

void main() {
    vec3 rel = inPos - uEye;
    float x = dot(rel, uRight), y = dot(rel, uUp), z = dot(rel, uForward);
    float aspect = uResolution.x / uResolution.y;
    float n = uNearFar.x, f = uNearFar.y;
    if (uOrtho > 0.5) {
        float zn = 2.0 * (z - n) / (f - n) - 1.0;
        gl_Position = vec4(x / (uOrthoHalfHeight * aspect), y / uOrthoHalfHeight, zn, 1.0);
    } else {
        float a = (f + n) / (f - n), b = -2.0 * f * n / (f - n);
        gl_Position = vec4(x / (uTanHalfFov * aspect), y / uTanHalfFov, a * z + b, z);
    }
    vPos = inPos;
    vNormal = inNormal;
}

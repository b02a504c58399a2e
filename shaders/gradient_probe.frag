#version 450
// engine/gl/gradient_probe.cpp, the raster's case (gbuffer.frag's sampling): textureGrad with the
// fragment's own fine derivatives of uv = (uStep.x x + uProduct x y, uStep.y y) texels at window
// position (x, y). With uProduct 0 the derivatives are the same at every pixel; with it the x
// derivative changes from row to row and the y derivative from column to column, so a level taken
// once per 2x2 quad differs from one taken per pixel.
layout(binding = 0) uniform sampler2D uLevels;  // level k: red k / 4
uniform vec2 uStep;
uniform float uProduct;
layout(location = 0) out vec4 outLevel;

void main() {
    vec2 w = gl_FragCoord.xy;
    vec2 uv = vec2(uStep.x * w.x + uProduct * w.x * w.y, uStep.y * w.y) / vec2(textureSize(uLevels, 0));
    outLevel = vec4(4.0 * textureGrad(uLevels, uv, dFdxFine(uv), dFdyFine(uv)).r);
}

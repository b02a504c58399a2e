#version 450
// The separable Gaussian as a fragment pass (seed-style, for bench/post_effects.sh): the same
// taps and clamp-to-edge as bloom_blur.comp.
layout(binding = 0) uniform sampler2D uSource;
uniform float uWeights[51];
uniform int uRadius;
uniform ivec2 uDirection;
layout(location = 0) out vec4 outColor;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 hi = textureSize(uSource, 0) - 1;
    vec3 sum = texelFetch(uSource, p, 0).rgb * uWeights[0];
    for (int i = 1; i <= uRadius; ++i) {
        vec3 a = texelFetch(uSource, clamp(p - i * uDirection, ivec2(0), hi), 0).rgb;
        vec3 b = texelFetch(uSource, clamp(p + i * uDirection, ivec2(0), hi), 0).rgb;
        sum += (a + b) * uWeights[i];
    }
    outColor = vec4(sum, 1.0);
}

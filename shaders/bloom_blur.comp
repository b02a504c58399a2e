#version 450
// One direction of the separable Gaussian: taps -r..r with weights uWeights[|i|], clamp-to-edge.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uSource;
layout(rgba16f, binding = 0) uniform writeonly image2D uTarget;
uniform float uWeights[51];
uniform int uRadius;
uniform ivec2 uDirection;  // (1, 0) horizontal, (0, 1) vertical

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uTarget);
    if (p.x >= size.x || p.y >= size.y) return;
    ivec2 hi = size - 1;
    vec3 sum = texelFetch(uSource, p, 0).rgb * uWeights[0];
    for (int i = 1; i <= uRadius; ++i) {
        vec3 a = texelFetch(uSource, clamp(p - i * uDirection, ivec2(0), hi), 0).rgb;
        vec3 b = texelFetch(uSource, clamp(p + i * uDirection, ivec2(0), hi), 0).rgb;
        sum += (a + b) * uWeights[i];
    }
    imageStore(uTarget, p, vec4(sum, 1.0));
}

#version 450
// --aa taa: the resolve (common/taa.glsl). Reads this frame's jittered HDR image (output size), its
// motion vectors (render size, uv_current - uv_previous, v up) and last frame's result and motion
// (the history); writes this frame's result, which is shown and becomes the next history.
#include "common/taa.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uCurrent;
layout(binding = 1) uniform sampler2D uVelocity;
layout(binding = 2) uniform sampler2D uHistory;
layout(binding = 3) uniform sampler2D uHistoryVelocity;
layout(rgba16f, binding = 0) uniform writeonly image2D uResolved;
layout(rg16f, binding = 1) uniform writeonly image2D uResolvedVelocity;
uniform bool uHistoryValid;
uniform float uCurrentWeight;  // --taa-history-weight: the current frame's share

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uResolved);
    if (p.x >= size.x || p.y >= size.y) return;
    vec2 uv = (vec2(p) + 0.5) / vec2(size);
    ivec2 velocitySize = textureSize(uVelocity, 0);
    vec2 velocity = texelFetch(uVelocity, clamp(ivec2(uv * vec2(velocitySize)), ivec2(0), velocitySize - 1), 0).xy;
    velocity = mix(velocity, vec2(0.0), isnan(velocity));
    imageStore(uResolvedVelocity, p, vec4(velocity, 0.0, 0.0));

    vec3 current = sanitizeHdr(texelFetch(uCurrent, p, 0).rgb);
    TaaNeighbourhood n = taaNeighbourhood(uCurrent, p);
    vec3 result = current;
    vec2 previous = (uv - velocity) * vec2(size);  // in pixels, centres at i + 0.5
    bool onScreen = all(greaterThanEqual(previous, vec2(0.0))) && all(lessThanEqual(previous, vec2(size)));
    if (uHistoryValid && onScreen) {
        ivec2 h = clamp(ivec2(floor(previous)), ivec2(0), size - 1);
        vec2 historyVelocity = texelFetch(uHistoryVelocity, h, 0).xy;
        if (taaMotionAgrees(velocity * vec2(size), historyVelocity * vec2(size))) {
            vec3 history = taaBilinear(uHistory, previous).rgb;
            result = taaBlend(current, taaClipHistory(history, n), uCurrentWeight);
        }
    }
    imageStore(uResolved, p, vec4(result, 1.0));
}

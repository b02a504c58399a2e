#version 450
// Mip-chain bloom downsample (Jimenez, SIGGRAPH 2014): the 13-tap filter as five 2x2-box
// groups (centre 0.5, corners 0.125 each) over the 6x6 source texels 2x-2..2x+3, clamp-to-edge.
// The first level reads the full-resolution HDR buffer through the bright pass and may weight the
// groups by 1 / (1 + luma) (Karis average) against fireflies.
#include "common/tonemap.glsl"
#include "common/post.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uSource;
layout(rgba16f, binding = 0) uniform writeonly image2D uTarget;
uniform int uSourceLevel;
uniform bool uFirst;   // bright pass on the source texels
uniform bool uKaris;
uniform float uThreshold;
uniform float uKnee;
uniform float uHighlight;

vec3 t[36];

vec3 cornerBox(int ox, int oy) {
    int i = ox + 2, j = oy + 2;
    return ((t[j * 6 + i] + t[j * 6 + i + 1]) + (t[(j + 1) * 6 + i] + t[(j + 1) * 6 + i + 1])) * 0.25;
}

vec3 group4(vec3 a, vec3 b, vec3 c, vec3 d) { return ((a + b) + (c + d)) * 0.25; }

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uTarget);
    if (p.x >= size.x || p.y >= size.y) return;
    ivec2 hi = textureSize(uSource, uSourceLevel) - 1;
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i) {
            ivec2 s = clamp(2 * p + ivec2(i - 2, j - 2), ivec2(0), hi);
            vec3 c = texelFetch(uSource, s, uSourceLevel).rgb;
            t[j * 6 + i] = uFirst ? bloomBright(c, uThreshold, uKnee, uHighlight) : c;
        }
    vec3 g[5];
    g[0] = group4(cornerBox(-1, -1), cornerBox(1, -1), cornerBox(-1, 1), cornerBox(1, 1));
    g[1] = group4(cornerBox(-2, -2), cornerBox(0, -2), cornerBox(-2, 0), cornerBox(0, 0));
    g[2] = group4(cornerBox(0, -2), cornerBox(2, -2), cornerBox(0, 0), cornerBox(2, 0));
    g[3] = group4(cornerBox(-2, 0), cornerBox(0, 0), cornerBox(-2, 2), cornerBox(0, 2));
    g[4] = group4(cornerBox(0, 0), cornerBox(2, 0), cornerBox(0, 2), cornerBox(2, 2));
    const float base[5] = float[5](0.5, 0.125, 0.125, 0.125, 0.125);
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    bool karis = uFirst && uKaris;
    for (int k = 0; k < 5; ++k) {
        float w = karis ? base[k] * karisWeight(g[k]) : base[k];
        sum += g[k] * w;
        wsum += w;
    }
    imageStore(uTarget, p, vec4(sum * (1.0 / wsum), 1.0));
}

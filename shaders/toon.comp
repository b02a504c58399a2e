#version 450
// Toon: the luminance ramp of common/post.glsl on every covered texel, and black outlines where the
// depth steps (depthEdge: the relative step, 0 on any plane) or the Sobel gradient of the eye-space
// normal exceeds its threshold. Uncovered texels (G-buffer background) read depth uFarDepth and
// normal 0.
#include "common/tonemap.glsl"
#include "common/post.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba16f, binding = 0) uniform image2D uHdr;
uniform int uLevels;
uniform float uDepthEdge;
uniform float uNormalEdge;
uniform float uFarDepth;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    float z[9], nx[9], ny[9], nz[9];
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            ivec2 q = clamp(p + ivec2(i - 1, j - 1), ivec2(0), size - 1);
            bool background = gbufferIsBackground(q);
            vec3 n = background ? vec3(0.0) : gbufferNormal(q);
            z[j * 3 + i] = background ? uFarDepth : -gbufferEyeZ(q);
            nx[j * 3 + i] = n.x;
            ny[j * 3 + i] = n.y;
            nz[j * 3 + i] = n.z;
        }
    bvec2 inside = bvec2(p.x > 0 && p.x < size.x - 1, p.y > 0 && p.y < size.y - 1);
    bool edge = depthEdge(z, inside) > uDepthEdge ||
                sobelSquared(nx) + sobelSquared(ny) + sobelSquared(nz) > uNormalEdge * uNormalEdge;
    vec3 c = sanitizeHdr(imageLoad(uHdr, p).rgb);
    bool covered = !gbufferIsBackground(p);
    if (edge) c = vec3(0.0);
    else if (covered) c *= toonScale(postLuminance(c), uLevels);
    imageStore(uHdr, p, vec4(sanitizeHdr(c), 1.0));
}

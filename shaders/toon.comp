#version 450
// Toon: the luminance ramp of common/post.glsl on every covered texel, and black outlines
// where the Sobel gradient of eye depth (relative to the centre depth) or of the eye-space normal
// exceeds its threshold. Uncovered texels (position.w = 0) read depth uFarDepth and normal 0.
#include "common/tonemap.glsl"
#include "common/post.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uPosition;
layout(binding = 1) uniform sampler2D uNormal;
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
            vec4 pos = texelFetch(uPosition, q, 0);
            vec3 n = texelFetch(uNormal, q, 0).xyz;
            z[j * 3 + i] = pos.w > 0.0 ? -pos.z : uFarDepth;
            nx[j * 3 + i] = n.x;
            ny[j * 3 + i] = n.y;
            nz[j * 3 + i] = n.z;
        }
    float zc = max(z[4], 1e-6);
    bool edge = sobelSquared(z) / (zc * zc) > uDepthEdge * uDepthEdge ||
                sobelSquared(nx) + sobelSquared(ny) + sobelSquared(nz) > uNormalEdge * uNormalEdge;
    vec3 c = sanitizeHdr(imageLoad(uHdr, p).rgb);
    bool covered = texelFetch(uPosition, p, 0).w > 0.0;
    if (edge) c = vec3(0.0);
    else if (covered) c *= toonScale(postLuminance(c), uLevels);
    imageStore(uHdr, p, vec4(sanitizeHdr(c), 1.0));
}

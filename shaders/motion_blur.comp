#version 450
// Motion blur, step 3 (the reconstruction filter's gather): uSamples taps along the neighbourhood's
// longest half blur vector, each weighted by depth order and by whether its blur covers this pixel
// (McGuire et al. 2012, with a centre weight of 1 / |V|). Where the neighbourhood moves less than
// half a pixel the pixel is copied unchanged.
#include "common/motion_blur.glsl"
#include "common/depth_reconstruct.glsl"
#include "common/tonemap.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uHdr;
layout(binding = 1) uniform sampler2D uVelocity;
layout(binding = 2) uniform sampler2D uDepth;      // gbuffer.depth (window depth)
layout(binding = 3) uniform sampler2D uNeighbors;  // half blur vectors, pixels, one per tile
layout(rgba16f, binding = 0) uniform writeonly image2D uOut;
uniform int uTileSize;
uniform int uSamples;
uniform float uShutter;
uniform vec2 uNearFar;
uniform bool uReversedZ;

const float kSoftDepth = 0.02;  // depth order blends over 2% of the depth

float distanceAt(ivec2 p) {
    float d = texelFetch(uDepth, p, 0).r;
    return -(uReversedZ ? eyeZFromReversedDepth(d, uNearFar.x, uNearFar.y)
                        : eyeZFromStandardDepth(min(d, 1.0), uNearFar.x, uNearFar.y));
}

vec2 halfVectorAt(ivec2 p, vec2 size) {
    return motionBlurHalfVector(texelFetch(uVelocity, p, 0).xy, size, uShutter, float(uTileSize));
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(uHdr, 0);
    if (p.x >= size.x || p.y >= size.y) return;
    vec4 centre = texelFetch(uHdr, p, 0);
    vec2 vn = texelFetch(uNeighbors, p / uTileSize, 0).xy;
    if (length(vn) <= 0.5) {  // nothing here moves by more than half a pixel
        imageStore(uOut, p, centre);
        return;
    }
    vec2 sizeF = vec2(size);
    vec2 vx = halfVectorAt(p, sizeF);
    float lx = max(length(vx), 0.5);
    float zx = distanceAt(p);
    float weight = 1.0 / lx;
    vec3 sum = centre.rgb * weight;
    // Interleaved gradient noise (Jimenez 2014): the taps' offset changes from pixel to pixel, so
    // banding between taps turns into fine noise.
    float j = fract(52.9829189 * fract(dot(vec2(p), vec2(0.06711056, 0.00583715)))) - 0.5;
    for (int i = 0; i < uSamples; ++i) {
        float t = motionBlurTap(i, uSamples, j);
        ivec2 q = clamp(ivec2(floor(vec2(p) + 0.5 + vn * t)), ivec2(0), size - 1);
        if (q == p) continue;
        float dist = length(vec2(q - p));
        float zy = distanceAt(q);
        float ly = length(halfVectorAt(q, sizeF));
        float yInFront = motionBlurInFront(zy, zx, kSoftDepth);
        float xInFront = motionBlurInFront(zx, zy, kSoftDepth);
        float a = yInFront * motionBlurCone(dist, ly)             // a blurred Y in front of X
                  + xInFront * motionBlurCone(dist, lx)           // X blurred over what lies behind it
                  + motionBlurCylinder(dist, ly) * motionBlurCylinder(dist, lx) * 2.0;  // both blurred
        weight += a;
        sum += a * texelFetch(uHdr, q, 0).rgb;
    }
    imageStore(uOut, p, vec4(sanitizeHdr(sum / weight), centre.a));
}

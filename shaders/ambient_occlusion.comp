#version 450
// GTAO (common/ambient_occlusion.glsl): for raw texel q, the G-buffer pixel p = q * uScale, its
// horizons along uDirections screen slices (rotated per pixel by a 4x4 pattern), uSteps depth samples
// per side out to uRadius metres, integrated cosine-weighted. Writes (AO, eye depth) to the raw
// RG16F target; the denoise pass filters (and upsamples) it by depth. Sky pixels: AO 1, depth 0.
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"
#include "common/ambient_occlusion.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rg16f, binding = 0) uniform writeonly image2D uRaw;

uniform int uScale;             // 1: full size, 2: half size
uniform float uRadius;          // view-space search radius, metres
uniform int uDirections;        // slices per pixel
uniform int uSteps;             // samples per side of a slice
uniform float uPixelsPerMetre;  // G-buffer pixels a metre spans at eye depth 1: height / (2 tan(fov/2))

void main() {
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uRaw);
    if (q.x >= size.x || q.y >= size.y) return;
    ivec2 full = textureSize(uGbufferDepth, 0);
    ivec2 p = min(q * uScale, full - 1);
    if (gbufferIsBackground(p)) {
        imageStore(uRaw, q, vec4(1.0, 0.0, 0.0, 0.0));
        return;
    }
    vec3 P = gbufferPosition(p);
    float depth = max(-P.z, 1e-6);
    vec3 N = normalize(gbufferNormal(p));
    vec3 V = normalize(-P);
    // The radius on screen; below a pixel nothing but the pixel itself is in reach.
    float radiusPx = min(uRadius * uPixelsPerMetre / depth, float(max(full.x, full.y)));
    if (!(radiusPx >= 1.0) || uDirections < 1 || uSteps < 1) {
        imageStore(uRaw, q, vec4(1.0, depth, 0.0, 0.0));
        return;
    }
    // Samples fade out of the horizon search over the last 40% of the radius (no hard edge).
    float falloffRange = 0.4 * uRadius;
    float rotation = aoTileNoise(q);
    float jitter = aoTileNoise(ivec2(q.y + 1, q.x + 2));
    // The same slices with nothing above the tangent plane: the estimate is divided by it, so a
    // surface open to the sky reads exactly 1 whatever the slice count (off the view axis a slice's
    // open value |Np| (cos n + n sin n) is not 1; only its mean over all azimuths is).
    float visibility = 0.0, open = 0.0;
    for (int d = 0; d < uDirections; ++d) {
        float psi = (float(d) + rotation) * LP_AO_PI / float(uDirections);
        vec3 w = gtaoSliceDirection(V, psi);
        vec2 dir = gtaoScreenDirection(P, w);  // GL pixels and eye space both have y up
        float n, npLength;
        gtaoProjectNormal(N, V, w, n, npLength);
        if (npLength < 1e-6) continue;  // normal along the slice's axis: this slice adds nothing
        // Horizon cosines start at the tangent plane: index 0 the -dir side, 1 the +dir side.
        vec2 low = vec2(cos(n - LP_AO_HALF_PI), cos(n + LP_AO_HALF_PI));
        vec2 horizonCos = low;
        for (int s = 0; s < uSteps; ++s) {
            float t = (float(s) + jitter) / float(uSteps);
            float px = mix(1.0, radiusPx, t * t);  // denser near the pixel
            for (int side = 0; side < 2; ++side) {
                vec2 at = vec2(p) + 0.5 + (side == 0 ? -px : px) * dir;
                ivec2 sp = ivec2(floor(at));
                if (any(lessThan(sp, ivec2(0))) || any(greaterThanEqual(sp, full)) || sp == p) continue;
                if (gbufferIsBackground(sp)) continue;  // the sky occludes nothing
                vec3 delta = gbufferPosition(sp) - P;
                float dist = length(delta);
                if (!(dist > 1e-6)) continue;
                float weight = clamp((uRadius - dist) / falloffRange, 0.0, 1.0);
                // A pixel centre is up to half a pixel off the slice: a sample on the pixel's own
                // tangent plane then reads as a horizon above it (a flat floor would lose ~4%).
                // Samples less than 2-6 degrees above the tangent plane fade out (they hold at most
                // sin^2(6 deg) = 1% of the cosine-weighted hemisphere).
                weight *= clamp((dot(delta, N) / dist - 0.035) / 0.07, 0.0, 1.0);
                float c = mix(low[side], dot(delta, V) / dist, weight);
                horizonCos[side] = max(horizonCos[side], c);
            }
        }
        float h0 = -acos(clamp(horizonCos[0], -1.0, 1.0));
        float h1 = acos(clamp(horizonCos[1], -1.0, 1.0));
        visibility += gtaoSliceVisibility(h0, h1, n, npLength);
        open += gtaoSliceVisibility(n - LP_AO_HALF_PI, n + LP_AO_HALF_PI, n, npLength);
    }
    float ao = open > 1e-6 ? clamp(visibility / open, 0.0, 1.0) : 1.0;
    imageStore(uRaw, q, vec4(ao, depth, 0.0, 0.0));
}

#version 450
// GTAO (common/ambient_occlusion.glsl) at raw texel q, which stands for G-buffer pixel p = q * uScale:
// the horizons along uDirections slices, uSteps samples per side out to uRadius metres, integrated
// cosine-weighted about the normal projected into each slice. The slices' rotation and the steps'
// offset come from an 8x8 pattern, one period of which ao_blur and ao_denoise average. The samples
// read the raw-size eye depth of ambient_occlusion_depth.comp. Writes the AO to the R16F raw target;
// sky texels: 1.
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"
#include "common/ambient_occlusion.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 12) uniform sampler2D uAoDepth;  // eye depth per raw texel, 0 on the sky
layout(r16f, binding = 0) uniform writeonly image2D uRaw;

uniform int uScale;             // 1: full size, 2: half size
uniform float uRadius;          // view-space search radius, metres
uniform int uDirections;        // slices per texel
uniform int uSteps;             // samples per side of a slice
uniform float uPixelsPerMetre;  // G-buffer pixels a metre spans at eye depth 1: height / (2 tan(fov/2))

vec3 texelPosition(ivec2 t, float z) {
    return aoTexelPosition(t, z, uScale, vec2(textureSize(uGbufferDepth, 0)), uGbufferCamera);
}

// The plane of the surface's own facet through P: spanned by P's nearest neighbours in depth on each
// axis of the texel grid the samples come from, facing the eye (a visible surface does). On a convex
// tessellated object every other texel of the grid lies on or below it, while the interpolated normal
// N can tilt several degrees from the facet, and at a silhouette face away from the eye: samples of
// the object itself then read as horizons above N's tangent plane (a lone sphere's rim lost up to
// 30%). N where an axis has no neighbour on a surface.
vec3 facetNormal(ivec2 q, ivec2 size, vec3 P, vec3 N, vec3 V) {
    vec3 span[2];
    for (int axis = 0; axis < 2; ++axis) {
        ivec2 e = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
        float nearest = 1e30;
        for (int s = -1; s <= 1; s += 2) {
            ivec2 t = q + s * e;
            if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, size))) continue;
            float z = texelFetch(uAoDepth, t, 0).r;
            if (!(z > 0.0) || abs(z + P.z) >= nearest) continue;
            nearest = abs(z + P.z);
            span[axis] = texelPosition(t, z) - P;
        }
        if (nearest > 1e29) return N;
    }
    vec3 g = cross(span[0], span[1]);
    float len = length(g);
    if (!(len > 0.0)) return N;
    return dot(g, V) < 0.0 ? -g / len : g / len;
}

void main() {
    ivec2 q = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uRaw);
    if (q.x >= size.x || q.y >= size.y) return;
    float depth = texelFetch(uAoDepth, q, 0).r;
    if (!(depth > 0.0)) {
        imageStore(uRaw, q, vec4(1.0));
        return;
    }
    ivec2 full = textureSize(uGbufferDepth, 0);
    vec3 P = texelPosition(q, depth);
    vec3 N = normalize(gbufferNormal(min(q * uScale, full - 1)));
    vec3 V = normalize(-P);
    // The radius on screen in raw texels; below a texel nothing but the texel itself is in reach.
    float radiusTexels = min(uRadius * uPixelsPerMetre / (depth * float(uScale)), float(max(size.x, size.y)));
    if (!(radiusTexels >= 1.0) || uDirections < 1 || uSteps < 1) {
        imageStore(uRaw, q, vec4(1.0));
        return;
    }
    vec3 facet = facetNormal(q, size, P, N, V);
    // Samples fade out of the horizon search over the last 40% of the radius (no hard edge).
    float falloffRange = 0.4 * uRadius;
    int k = aoPatternIndex(q);
    float rotation = aoSliceRotation(k), offset = aoStepOffset(k);
    // The same slices with nothing above the tangent plane: the estimate is divided by it, so a
    // surface open to the sky reads exactly 1 whatever the slice count (off the view axis a slice's
    // open value |Np| (cos n + n sin n) is not 1; only its mean over all azimuths is).
    float visibility = 0.0, open = 0.0;
    for (int d = 0; d < uDirections; ++d) {
        float psi = (float(d) + rotation) * LP_AO_PI / float(uDirections);
        vec3 w = gtaoSliceDirection(V, psi);
        vec2 dir = gtaoScreenDirection(P, w);  // GL texels and eye space both have y up
        float n, npLength;
        gtaoProjectNormal(N, V, w, n, npLength);
        if (npLength < 1e-6) continue;  // normal along the slice's axis: this slice adds nothing
        // Horizon cosines start at the tangent plane: index 0 the -dir side, 1 the +dir side.
        vec2 low = vec2(cos(n - LP_AO_HALF_PI), cos(n + LP_AO_HALF_PI));
        vec2 horizonCos = low;
        for (int s = 0; s < uSteps; ++s) {
            float t = (float(s) + offset) / float(uSteps);
            float texels = mix(1.0, radiusTexels, t * t);  // denser near the texel
            for (int side = 0; side < 2; ++side) {
                // Off screen the border texel stands in (the surface there continues it), so a sample
                // leaving the screen does not switch an occluder off.
                vec2 at = vec2(q) + 0.5 + (side == 0 ? -texels : texels) * dir;
                ivec2 t = clamp(ivec2(floor(at)), ivec2(0), size - 1);
                if (t == q) continue;
                float z = texelFetch(uAoDepth, t, 0).r;
                if (!(z > 0.0)) continue;  // the sky occludes nothing
                vec3 delta = texelPosition(t, z) - P;
                float dist = length(delta);
                if (!(dist > 1e-6)) continue;
                float weight = clamp((uRadius - dist) / falloffRange, 0.0, 1.0);
                // An occluder lies above both the shading normal's tangent plane and the facet's. A
                // texel centre is up to half a texel off the slice, so a sample on the surface's own
                // plane would read as a horizon above it (a flat floor would lose ~4%): samples less
                // than 2-6 degrees above fade out (they hold at most sin^2(6 deg) = 1% of the
                // cosine-weighted hemisphere).
                float elevation = min(dot(delta, N), dot(delta, facet)) / dist;
                weight *= clamp((elevation - 0.035) / 0.07, 0.0, 1.0);
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
    imageStore(uRaw, q, vec4(ao, 0.0, 0.0, 0.0));
}

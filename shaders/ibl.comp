#version 450
// Image-based lighting added into the HDR buffer: diffuse kd (1 - Fss) E / pi from the SH (or the
// irradiance cube) and specular prefiltered(R, roughness) * Fss, Fss = F0 A + f90 B from the DFG LUT
// (F0 = the material's specular colour, f90 as in the analytic GGX: Ks = 0 is exactly Lambertian).
// The (1 - Fss) keeps a white surface in a white environment at exactly the environment's radiance
// (white furnace). With ambient occlusion on, the diffuse term is multiplied by the AO and the
// specular by the specular occlusion derived from it. The math is common/ibl_shading.glsl's.
#include "common/ibl_shading.glsl"
#include "common/tonemap.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 7) uniform samplerCube uIrradiance;
layout(binding = 8) uniform samplerCube uPrefiltered;
layout(binding = 9) uniform sampler2D uDfg;
layout(rgba16f, binding = 0) uniform image2D uHdr;

uniform bool uLightingOnly;   // debug: white albedo
layout(binding = 14) uniform sampler2D uAo;  // passes/ambient_occlusion_pass
uniform bool uAmbientOcclusion;

// Position difference to the neighbour along `step` on the same surface as p: of the two sides, the
// one whose next pixel continues the line from that neighbour through p best (across an edge, or where
// a grazing floor meets an object, the neighbour belongs to another surface and the line breaks; the
// nearer depth alone picks the object over a grazing floor's next row); zero where neither side has one.
bool surfaceAt(ivec2 q, ivec2 size) {
    return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size)) && !gbufferIsBackground(q);
}
vec3 neighbourDelta(ivec2 p, ivec2 size, ivec2 step, vec3 P) {
    vec3 best = vec3(0.0);
    float bestBreak = 3.0e38;
    for (int side = -1; side <= 1; side += 2) {
        ivec2 q = p + side * step, q2 = p + 2 * side * step;
        if (!surfaceAt(q, size)) continue;
        vec3 Q = gbufferPosition(q);
        // How far the pixel beyond q is from the line P -> Q continued (0 on a plane seen in perspective
        // up to the line's curvature; an unknown pixel counts as a break as large as the step).
        float lineBreak = surfaceAt(q2, size) ? length(gbufferPosition(q2) - (2.0 * Q - P)) : length(Q - P);
        if (lineBreak < bestBreak) {
            bestBreak = lineBreak;
            best = (Q - P) * float(side);
        }
    }
    return best;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    if (gbufferIsBackground(p)) return;
    if (!uLightingOnly && gbufferIsFlat(p)) return;  // flat-lit: no light adds to it
    vec3 N = gbufferNormal(p);
    vec3 P = gbufferPosition(p);
    vec4 spec = vec4(gbufferSpecular(p), gbufferShininess(p));
    vec3 kd = uLightingOnly ? vec3(1.0) : gbufferDiffuse(p);
    float pl = length(P);
    vec3 V = pl > 0.0 ? -P / pl : vec3(0.0, 0.0, 1.0);
    float occlusion = uLightingOnly ? 1.0 : gbufferOcclusion(p);  // the material's ambient occlusion
    float screenAo = uAmbientOcclusion ? texelFetch(uAo, p, 0).r : 1.0;
    // The geometric normal from the depth of the pixel's neighbours (the G-buffer keeps only the mapped one).
    // Only the sampled specular and the extracted sources use it: the split sum alone skips the 16 reads.
    vec3 Ng = uSpecularSamples > 0 || uIblLightCount > 0
                  ? lpIblFaceNormal(neighbourDelta(p, size, ivec2(1, 0), P), neighbourDelta(p, size, ivec2(0, 1), P), N, V)
                  : N;
    vec3 c = lpIblRadiance(uIrradiance, uPrefiltered, uDfg, N, Ng, V, kd, gbufferFresnel(p), spec.a, occlusion, screenAo,
                           uAmbientOcclusion, gbufferClearcoat(p));
    vec3 hdr = imageLoad(uHdr, p).rgb;
    imageStore(uHdr, p, vec4(sanitizeHdr(hdr + c), 1.0));
}

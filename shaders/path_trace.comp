#version 450
// The path tracer (passes/path_trace_pass, docs/path-tracer.md): one sample per pixel per dispatch,
// added into the accumulation image (rgb: sum of radiance, a: sum of squared luminance, for the noise
// estimate); the HDR target gets the mean so far. Materials and lights are lightpass's own: the BRDF
// of common/brdf.glsl (uBrdf, uSpecularMasking), the suns' irradiance, the local lights' ranged
// falloff and spot cones of common/local_light.glsl; the environment (map or colour) lights every
// ray that leaves the scene. A map is also sampled by its luminance at every surface (next-event
// estimation, common/path_trace_environment.glsl), combined with the BRDF's own samples by multiple
// importance sampling (the power heuristic), so a small bright lamp in a map converges.
#include "common/brdf.glsl"
#include "common/ibl.glsl"
#include "common/local_light.glsl"
#include "common/path_trace.glsl"
#include "common/path_trace_environment.glsl"
#include "common/normal_map.glsl"
#include "common/tonemap.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform image2D uAccumulation;
layout(rgba16f, binding = 1) uniform writeonly image2D uHdr;
layout(std430, binding = LP_PT_BIND_LIGHTS) readonly buffer PtLights { LpLocalLight uPtLights[]; };
layout(binding = 0) uniform sampler2D uEnvironmentMap;  // equirectangular, linear radiance

uniform mat4 uClipToWorld;     // inverse of projection x view
uniform vec3 uCameraPosition;
uniform int uSample;           // index of this dispatch's sample (0 .. N - 1)
uniform bool uTrace;           // false: no new sample, the HDR target gets the sums over uSample + 1
uniform bool uPixelCentre;     // every sample through the pixel's centre; else jittered over the pixel
uniform int uBounces;          // surface interactions whose scattered light counts (1: direct light only)
uniform int uRouletteFrom;     // Russian roulette from this interaction on
#define MAX_SUNS 16
uniform int uSunCount;
uniform vec3 uSunToLight[MAX_SUNS];     // unit, world space, towards the sun
uniform vec3 uSunIrradiance[MAX_SUNS];  // colour x intensity: irradiance at normal incidence
uniform int uLocalLightCount;
uniform int uSpecularMode;     // LP_LOCAL_SPECULAR_*, as the local-light passes
uniform bool uHasEnvironmentMap;
uniform vec3 uEnvironmentColor;  // colour x intensity, without a map
uniform float uEnvironmentIntensity;
uniform float uEnvironmentRotation;  // radians about +Y
uniform float uRayEpsilon;     // offset of secondary rays, scaled to the scene

// PCG hash (Jarzynski and Olano 2020) -> uniform floats in [0, 1).
uint lpPcg(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
uint gRng = 0u;  // set per invocation in main()
float rand() {
    gRng = lpPcg(gRng);
    return float(gRng >> 8) * (1.0 / 16777216.0);
}

vec3 environmentRadiance(vec3 d) {
    if (!uHasEnvironmentMap) return uEnvironmentColor;
    return textureLod(uEnvironmentMap, equirectUv(rotateY(d, -uEnvironmentRotation)), 0.0).rgb * uEnvironmentIntensity;
}

// The density per steradian of the next-direction mixture below (cosine-weighted diffuse and GGX
// half-vector specular) for direction L.
float mixturePdf(vec3 N, vec3 V, vec3 L, float pSpecular, float alpha) {
    float nl = dot(N, L);
    if (nl <= 0.0) return 0.0;
    vec3 H = brdfHalfVector(N, V, L);
    float vh = max(dot(V, H), 1e-6);
    return (1.0 - pSpecular) * nl / LP_PI + pSpecular * ggxDistribution(N, H, alpha) * max(dot(N, H), 0.0) / (4.0 * vh);
}

// The same with KHR_materials_clearcoat's lobe as a third strategy, drawn with probability pCoat
// (GGX half vectors about the coat's normal and alpha).
float coatedMixturePdf(vec3 N, vec3 V, vec3 L, float pSpecular, float alpha, ClearcoatLayer coat, float pCoat) {
    float pdf = (1.0 - pCoat) * mixturePdf(N, V, L, pSpecular, alpha);
    if (pCoat <= 0.0) return pdf;
    vec3 H = brdfHalfVector(coat.normal, V, L);
    float vh = max(dot(V, H), 1e-6);
    if (dot(coat.normal, L) > 0.0)
        pdf += pCoat * ggxDistribution(coat.normal, H, coat.alpha) * max(dot(coat.normal, H), 0.0) / (4.0 * vh);
    return pdf;
}

// f cos of the coated material towards L: the base's (kd and ks already under the coat) with N.L, the
// coat's lobe with Nc.L (each cosine on its own normal, as the raster passes).
vec3 coatedBrdfCosine(vec3 N, vec3 V, vec3 L, vec3 kd, FresnelEnds ks, float shininess, ClearcoatLayer coat) {
    float nl = dot(N, L);
    vec3 base = nl > 0.0 ? (brdfDiffuse(uBrdf, N, V, L, kd, ks) + brdfSpecular(uBrdf, N, V, L, ks, shininess)) * nl : vec3(0.0);
    return base + vec3(clearcoatSpecular(coat, V, L) * max(dot(coat.normal, L), 0.0));
}

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
float maxComponent(vec3 c) { return max(c.r, max(c.g, c.b)); }

// An orthonormal basis around unit n (Duff et al. 2017).
void basis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

bool visible(vec3 P, vec3 L, float distance) {
    float t;
    vec2 uv;
    gLpPtAlphaSeed = lpPcg(gRng + 0x9e3779b9u);  // each shadow ray its own BLEND draws
    gRng = gLpPtAlphaSeed;
    return lpPtTrace(P, L, 0.0, distance, true, t, uv) < 0;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uAccumulation);
    if (p.x >= size.x || p.y >= size.y) return;
    if (!uTrace) {
        imageStore(uHdr, p, vec4(sanitizeHdr(imageLoad(uAccumulation, p).rgb / float(uSample + 1)), 1.0));
        return;
    }
    gRng = lpPcg(uint(p.x) + lpPcg(uint(p.y) + lpPcg(uint(uSample))));
    vec2 jitter = uPixelCentre ? vec2(0.5) : vec2(rand(), rand());
    // Pixel (0, 0) is the bottom-left one, as in every GL target of the frame.
    vec2 ndc = (vec2(p) + jitter) / vec2(size) * 2.0 - 1.0;
    vec4 far = uClipToWorld * vec4(ndc, 1.0, 1.0);
    vec3 origin = uCameraPosition;
    vec3 dir = normalize(far.xyz / far.w - origin);

    vec3 radiance = vec3(0.0), throughput = vec3(1.0);
    float tMin = 0.0;
    // With the map's tables its light comes by two strategies; each is weighted by the power heuristic.
    bool sampleEnvironment = uHasEnvironmentMap && uEnvironmentCells.x > 0;
    float lastPdf = 0.0;  // the mixture's density of the ray being traced (0: the camera's ray)
    // KHR_materials_volume: the ray is inside a transmissive volume that absorbs as medium.rgb^(d / medium.w).
    bool inMedium = false;
    vec4 medium = vec4(1.0, 1.0, 1.0, 0.0);
    for (int bounce = 0; bounce <= uBounces; ++bounce) {
        float t;
        vec2 bary;
        gLpPtAlphaSeed = lpPcg(gRng + 0x85ebca6bu);
        gRng = gLpPtAlphaSeed;
        int tri = lpPtTrace(origin, dir, tMin, 3.0e38, false, t, bary);
        if (tri < 0) {
            float weight = 1.0;
            if (sampleEnvironment && lastPdf > 0.0) {
                float pe = lpPtEnvironmentPdf(rotateY(dir, -uEnvironmentRotation));
                weight = lastPdf * lastPdf / (lastPdf * lastPdf + pe * pe);
            }
            radiance += throughput * environmentRadiance(dir) * weight;
            break;
        }
        if (inMedium && medium.w > 0.0) throughput *= pow(max(medium.rgb, vec3(0.0)), vec3(t / medium.w));  // Beer-Lambert
        LpPathTraceTriangle T = uPtTriangles[tri];
        LpPathTraceMaterial m = uPtMaterials[int(T.position[0].w)];
        vec3 P = origin + t * dir;
        vec3 V = -dir;
        vec3 Ng = normalize(cross(T.position[1].xyz - T.position[0].xyz, T.position[2].xyz - T.position[0].xyz));
        vec3 N = normalize((1.0 - bary.x - bary.y) * T.normal[0].xyz + bary.x * T.normal[1].xyz + bary.y * T.normal[2].xyz);
        // Both normals on the side the ray came from (a double-sided material's back face is lit
        // like its front, as in the raster passes; a single-sided one is never hit from behind).
        bool backFace = dot(Ng, V) < 0.0;
        if (backFace) Ng = -Ng;
        if (dot(N, Ng) < 0.0) N = -N;
        // KHR_materials_clearcoat's layer on the interpolated normal (the base's normal map leaves it
        // alone; its own map is not sampled): the factors.
        ClearcoatLayer coat = m.clearcoat.x > 0.0 ? clearcoatLayer(m.clearcoat.x, m.clearcoat.y, N, V) : noClearcoat();
        // The maps (lp::PathTraceMap): base colour, metallic-roughness, normal, emissive, as
        // common/material.glsl applies them (no height map, no vertex colour).
        vec3 base = m.baseOpacity.rgb;
        if (m.maps.x >= 0.0) base = clamp(base * lpPtSampleMap(m, T, bary, 0, true).rgb, 0.0, 1.0);
        float metallic = m.specularMetallic.w;
        float shininess = m.emissionShininess.w;
        if (m.maps.y >= 0.0) {
            vec4 mr = lpPtSampleMap(m, T, bary, 1, false);
            metallic = clamp(metallic * mr.b, 0.0, 1.0);
            shininess = shininessFromRoughnessToFloor(m.mapParams.y * mr.g);
        }
        vec3 emission = m.emissionShininess.rgb;
        if (m.maps.w >= 0.0) emission *= lpPtSampleMap(m, T, bary, 3, true).rgb;
        if (m.maps.z >= 0.0) {
            vec4 tw = (1.0 - bary.x - bary.y) * T.tangent[0] + bary.x * T.tangent[1] + bary.y * T.tangent[2];
            vec3 Tn = tw.xyz - N * dot(N, tw.xyz);
            float tl = length(Tn);
            if (tl > 1e-20) {
                Tn /= tl;
                vec3 Bn = cross(N, Tn) * (tw.w < 0.0 ? -1.0 : 1.0);
                N = normalMapNormal(N, Tn, Bn, lpPtSampleMap(m, T, bary, 2, false).xyz * 2.0 - 1.0, m.mapParams.x);
            }
        }
        if (m.flags.x != 0.0) {  // flat-lit: its colour, untouched by light (material.glsl)
            radiance += throughput * base * (1.0 - metallic);
            break;
        }
        radiance += throughput * emission * (1.0 - coat.weight);  // the coat lies over the emission too
        if (bounce == uBounces) break;
        vec3 dielectricF0 = m.specularMetallic.rgb;
        bool givenF90 = m.mapParams.w >= 0.0;  // KHR_materials_specular
        vec3 kd = materialDiffuseAlbedo(uBrdf, base, metallic, dielectricF0, givenF90) * (1.0 - coat.weight);
        FresnelEnds ks = clearcoatBaseEnds(materialFresnelEnds(base, metallic, dielectricF0, max(m.mapParams.w, 0.0), givenF90), coat);
        vec3 Po = P + Ng * uRayEpsilon * (1.0 + maxComponent(abs(P)));
        vec3 Pi = P - Ng * uRayEpsilon * (1.0 + maxComponent(abs(P)));  // on the far side, for refracted rays

        // KHR_materials_transmission: the share tw of the dielectric base that refracts (metals do not),
        // through a GGX-sampled microfacet normal (smooth: the shading normal). Inside a volume the
        // boundary only reflects (Fresnel, total internal reflection) or lets the ray out; from outside
        // the refracted branch is taken with probability pT and weighted tw (1 - F) base / pT, the
        // diffuse keeps 1 - tw, and the reflection branch is divided by 1 - pT. Thin-walled (thickness
        // 0): the ray passes straight through.
        float tw = clamp(m.transmission.x, 0.0, 1.0) * (1.0 - metallic);
        bool volume = m.transmission.z > 0.0;
        float ior = max(m.transmission.y, 1.0);
        float alphaT = ggxAlphaFromShininess(shininess);
        if (tw > 0.0 && volume && backFace) {
            vec3 tx, ty;
            basis(N, tx, ty);
            float u1 = rand(), u2 = rand();
            float a2 = alphaT * alphaT;
            float cosTheta = sqrt((1.0 - u1) / (1.0 + (a2 - 1.0) * u1));
            float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
            vec3 H = normalize(tx * (sinTheta * cos(2.0 * LP_PI * u2)) + ty * (sinTheta * sin(2.0 * LP_PI * u2)) + N * cosTheta);
            float F = lpPtDielectricFresnel(clamp(dot(V, H), 0.0, 1.0), ior);
            vec3 L = rand() < F ? reflect(-V, H) : refract(-V, H, ior);
            bool leaves = dot(L, Ng) < 0.0;
            if (dot(L, L) < 0.5) break;
            origin = leaves ? Pi : Po;
            inMedium = !leaves;
            dir = normalize(L);
            lastPdf = 0.0;
            continue;
        }
        float pT = 0.0;
        if (tw > 0.0) {
            pT = clamp(tw * (1.0 - lpPtDielectricFresnel(clamp(dot(N, V), 0.0, 1.0), 1.0 / ior)), 0.0, 0.95);
            kd *= 1.0 - tw;
            if (rand() < pT) {
                vec3 tx, ty;
                basis(N, tx, ty);
                float u1 = rand(), u2 = rand();
                float a2 = alphaT * alphaT;
                float cosTheta = sqrt((1.0 - u1) / (1.0 + (a2 - 1.0) * u1));
                float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
                vec3 H = normalize(tx * (sinTheta * cos(2.0 * LP_PI * u2)) + ty * (sinTheta * sin(2.0 * LP_PI * u2)) + N * cosTheta);
                float F = lpPtDielectricFresnel(clamp(dot(V, H), 0.0, 1.0), 1.0 / ior);
                vec3 L = volume ? refract(-V, H, 1.0 / ior) : -V;
                if (dot(L, L) < 0.5 || dot(L, Ng) >= 0.0) break;
                throughput *= tw * (1.0 - F) * base * (1.0 - coat.weight) / pT;
                if (volume) {
                    inMedium = true;
                    medium = vec4(m.attenuation.rgb, m.transmission.w);
                }
                origin = Pi;
                dir = normalize(L);
                lastPdf = 0.0;
                if (bounce + 1 >= uRouletteFrom) {
                    float survive = min(maxComponent(throughput), 0.95);
                    if (!(rand() < survive)) break;
                    throughput /= survive;
                }
                continue;
            }
        }
        float branch = 1.0 - pT;  // the reflection branch's probability

        // Direct light from the suns and the local lights (delta lights: no other way to reach them).
        for (int i = 0; i < uSunCount; ++i) {
            vec3 L = uSunToLight[i];
            if ((dot(N, L) <= 0.0 && (coat.weight <= 0.0 || dot(coat.normal, L) <= 0.0)) || dot(Ng, L) <= 0.0) continue;
            if (visible(Po, L, 3.0e38))
                radiance += throughput * (brdfRadiance(uBrdf, N, V, L, kd, ks, shininess, uSunIrradiance[i]) +
                                          clearcoatRadiance(coat, V, L, uSunIrradiance[i]));
        }
        for (int i = 0; i < uLocalLightCount; ++i) {
            LpLocalLight l = uPtLights[i];
            vec3 toLight = l.positionRange.xyz - P;
            float d = length(toLight);
            if (d >= l.positionRange.w && uSpecularMode != LP_LOCAL_SPECULAR_UNRANGED) continue;
            vec3 L = d > 0.0 ? toLight / d : N;
            if (dot(Ng, L) <= 0.0) continue;
            float spot = lpSpotFalloff(dot(-L, l.directionCos.xyz), l.directionCos.w, l.intensity.w);
            if (spot <= 0.0) continue;
            vec3 c = lpLocalLightRadiance(l.positionRange.xyz, l.positionRange.w, l.intensity.rgb, P, N, V, kd, ks,
                                          shininess, uSpecularMode, coat) * spot;
            if (maxComponent(c) <= 0.0) continue;
            vec3 toLightO = l.positionRange.xyz - Po;
            float dO = length(toLightO);
            if (dO > 0.0 && visible(Po, toLightO / dO, dO * (1.0 - 1e-4))) radiance += throughput * c;
        }

        // The next direction: a mixture of cosine-weighted (diffuse) and GGX half-vector (specular)
        // sampling, weighted by the mixture's pdf; emitters are reached this way, the environment this
        // way and by its own samples.
        float alpha = ggxAlphaFromShininess(shininess);
        float wd = maxComponent(kd), ws = maxComponent(ks.f0);
        if (wd + ws + coat.weight <= 0.0) break;
        float pSpecular = wd <= 0.0 ? 1.0 : (ws <= 0.0 ? 0.0 : clamp(ws / (wd + ws), 0.1, 0.9));
        // KHR_materials_clearcoat's lobe: its share of the reflection, at least 5% and at most 90%.
        float pCoat = coat.weight <= 0.0 ? 0.0 : (wd + ws <= 0.0 ? 1.0 : clamp(coat.weight / (wd + ws + coat.weight), 0.05, 0.9));
        if (sampleEnvironment) {
            float pe;
            vec3 Le = rotateY(lpPtSampleEnvironment(vec2(rand(), rand()), pe), uEnvironmentRotation);
            float nl = dot(N, Le);
            float coatNl = coat.weight > 0.0 ? dot(coat.normal, Le) : 0.0;
            if (pe > 0.0 && (nl > 0.0 || coatNl > 0.0) && dot(Ng, Le) > 0.0 && visible(Po, Le, 3.0e38)) {
                float pb = coatedMixturePdf(N, V, Le, pSpecular, alpha, coat, pCoat) * branch;
                vec3 f = nl > 0.0 ? brdfDiffuse(uBrdf, N, V, Le, kd, ks) + brdfSpecular(uBrdf, N, V, Le, ks, shininess) : vec3(0.0);
                vec3 coatCos = vec3(clearcoatSpecular(coat, V, Le) * max(coatNl, 0.0));
                // f cos L / pe, weighted pe^2 / (pe^2 + pb^2).
                radiance += (throughput * f * max(nl, 0.0) + throughput * coatCos) * environmentRadiance(Le) *
                            (pe / (pe * pe + pb * pb));
            }
        }
        vec3 tx, ty;
        basis(N, tx, ty);
        vec3 L;
        float u1 = rand(), u2 = rand();
        if (pCoat > 0.0 && rand() < pCoat) {
            vec3 cx, cy;
            basis(coat.normal, cx, cy);
            float a2 = coat.alpha * coat.alpha;
            float cosTheta = sqrt((1.0 - u1) / (1.0 + (a2 - 1.0) * u1));
            float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
            float phi = 2.0 * LP_PI * u2;
            vec3 H = normalize(cx * (sinTheta * cos(phi)) + cy * (sinTheta * sin(phi)) + coat.normal * cosTheta);
            L = reflect(-V, H);
        } else if (rand() < pSpecular) {
            float a2 = alpha * alpha;
            float cosTheta = sqrt((1.0 - u1) / (1.0 + (a2 - 1.0) * u1));
            float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
            float phi = 2.0 * LP_PI * u2;
            vec3 H = normalize(tx * (sinTheta * cos(phi)) + ty * (sinTheta * sin(phi)) + N * cosTheta);
            L = reflect(-V, H);
        } else {
            float r = sqrt(u1), phi = 2.0 * LP_PI * u2;
            L = normalize(tx * (r * cos(phi)) + ty * (r * sin(phi)) + N * sqrt(max(1.0 - u1, 0.0)));
        }
        if (dot(Ng, L) <= 0.0) break;
        vec3 fcos = coatedBrdfCosine(N, V, L, kd, ks, shininess, coat);
        if (maxComponent(fcos) <= 0.0) break;
        float pdf = coatedMixturePdf(N, V, L, pSpecular, alpha, coat, pCoat) * branch;
        if (!(pdf > 0.0)) break;
        lastPdf = pdf;
        throughput *= fcos / pdf;
        if (bounce + 1 >= uRouletteFrom) {
            float survive = min(maxComponent(throughput), 0.95);
            if (!(rand() < survive)) break;
            throughput /= survive;
        }
        origin = Po;
        dir = L;
    }
    radiance = max(radiance, vec3(0.0));
    if (any(isnan(radiance)) || any(isinf(radiance))) radiance = vec3(0.0);  // never poisons the mean
    vec4 sum = (uSample == 0 ? vec4(0.0) : imageLoad(uAccumulation, p)) + vec4(radiance, luminance(radiance) * luminance(radiance));
    imageStore(uAccumulation, p, sum);
    imageStore(uHdr, p, vec4(sanitizeHdr(sum.rgb / float(uSample + 1)), 1.0));
}

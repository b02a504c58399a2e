// The path tracer's scene (engine/render/path_trace_scene.hpp, engine/render/bvh.hpp): storage
// blocks, the BVH traversal and the triangle test. World space.
#ifndef LP_PATH_TRACE_GLSL
#define LP_PATH_TRACE_GLSL

// Storage-block bindings; passes/path_trace_pass.hpp's PathTraceBinding has the same numbers.
#define LP_PT_BIND_NODES 0
#define LP_PT_BIND_TRIANGLES 1
#define LP_PT_BIND_MATERIALS 2
#define LP_PT_BIND_LIGHTS 3
#define LP_PT_BIND_ENVIRONMENT 4  // common/path_trace_environment.glsl
#define LP_PT_STACK 64  // traversal stack; the pass refuses a BVH deeper than this

struct LpBvhNode {
    vec4 lo;  // w: first (int bits): the left child, or a leaf's first triangle
    vec4 hi;  // w: count (int bits): 0 for an interior node
};
struct LpPathTraceTriangle {
    vec4 position[3];  // position[0].w: material index
    vec4 normal[3];
    vec4 uv[3];       // xy: TEXCOORD_0, zw: TEXCOORD_1
    vec4 tangent[3];  // world, w: handedness
};
struct LpPathTraceMaterial {
    vec4 baseOpacity;
    vec4 specularMetallic;
    vec4 emissionShininess;
    vec4 flags;      // x: flat-lit, y: double-sided, z: alpha mode (0 opaque, 1 MASK, 2 BLEND), w: cutoff
    vec4 maps;       // layers of base colour, metallic-roughness, normal, emissive (-1: none)
    vec4 mapParams;  // x: normal scale, y: roughness factor, z: sampling bits (pathTraceMapBits),
                     // w: KHR_materials_specular's dielectric f90 (-1: none given)
    vec4 clearcoat;  // x: KHR_materials_clearcoat's factor (0: no coat), y: its roughness
    vec4 transmission;  // x: KHR_materials_transmission's factor (0: none), y: ior, z: volume thickness
                        // factor (0: thin-walled), w: attenuationDistance (0: infinite)
    vec4 attenuation;   // rgb: attenuationColor
};

layout(std430, binding = LP_PT_BIND_NODES) readonly buffer PtNodes { LpBvhNode uPtNodes[]; };
layout(std430, binding = LP_PT_BIND_TRIANGLES) readonly buffer PtTriangles { LpPathTraceTriangle uPtTriangles[]; };
layout(std430, binding = LP_PT_BIND_MATERIALS) readonly buffer PtMaterials { LpPathTraceMaterial uPtMaterials[]; };

uniform int uPtNodeCount;  // 0: no geometry

// The materials' maps, one layer each (passes/path_trace_pass: base colour and emissive sRGB,
// metallic-roughness and normal linear); level 0 only: the jittered rays of a pixel filter them.
layout(binding = 1) uniform sampler2DArray uPtSrgbMaps;
layout(binding = 2) uniform sampler2DArray uPtLinearMaps;
uniform bool uHasMaskedMaterials;  // some material is MASK or BLEND: hits test its alpha
uint gLpPtAlphaSeed = 0u;          // BLEND's stochastic test: the caller's number for this ray

// A coordinate wrapped as its sampler says: 0 repeat, 1 clamp to edge, 2 mirrored repeat.
float lpPtWrap(float x, int mode) {
    if (mode == 1) return clamp(x, 0.0, 1.0);
    if (mode == 2) {
        float m = mod(x, 2.0);
        return m > 1.0 ? 2.0 - m : m;
    }
    return fract(x);
}

// Map `map` (lp::PathTraceMap) of material m at barycentrics `bary` of triangle T, in its uv set and
// wraps (lp::pathTraceMapBits).
vec4 lpPtSampleMap(LpPathTraceMaterial m, LpPathTraceTriangle T, vec2 bary, int map, bool srgb) {
    int bits = int(m.mapParams.z);
    vec4 uvs = (1.0 - bary.x - bary.y) * T.uv[0] + bary.x * T.uv[1] + bary.y * T.uv[2];
    vec2 st = ((bits >> (4 * map)) & 1) != 0 ? uvs.zw : uvs.xy;
    vec2 uv = vec2(lpPtWrap(st.x, (bits >> (4 * map + 1)) & 3), lpPtWrap(st.y, (bits >> (16 + 2 * map)) & 3));
    vec3 at = vec3(uv, m.maps[map]);
    return srgb ? textureLod(uPtSrgbMaps, at, 0.0) : textureLod(uPtLinearMaps, at, 0.0);
}

uint lpPtHash(uint v) {
    v ^= v >> 16;
    v *= 0x7feb352du;
    v ^= v >> 15;
    v *= 0x846ca68bu;
    return v ^ (v >> 16);
}

// Whether a hit on triangle `tri` at `bary` is cut away: MASK below its cutoff, or BLEND passed
// through with the probability 1 - alpha (its opacity: what the transparent pass blends by).
bool lpPtAlphaCuts(int tri, vec2 bary) {
    LpPathTraceTriangle T = uPtTriangles[tri];
    LpPathTraceMaterial m = uPtMaterials[int(T.position[0].w)];
    if (m.flags.z == 0.0) return false;
    float alpha = m.baseOpacity.a;
    if (m.maps.x >= 0.0) alpha *= lpPtSampleMap(m, T, bary, 0, true).a;
    if (m.flags.z == 1.0) return alpha < m.flags.w;
    uint h = lpPtHash(gLpPtAlphaSeed ^ lpPtHash(uint(tri) * 9781u + floatBitsToUint(bary.x) * 6271u + floatBitsToUint(bary.y)));
    return float(h >> 8) * (1.0 / 16777216.0) >= alpha;
}

// Moller-Trumbore, both faces (bvh.cpp's intersectTriangle).
bool lpPtIntersectTriangle(vec3 o, vec3 d, vec3 a, vec3 b, vec3 c, float tMin, float tMax, out float t, out vec2 uv) {
    vec3 e1 = b - a, e2 = c - a;
    vec3 p = cross(d, e2);
    float det = dot(e1, p);
    t = 0.0;
    uv = vec2(0.0);
    if (det == 0.0) return false;
    float inv = 1.0 / det;
    vec3 s = o - a;
    float u = dot(s, p) * inv;
    if (u < 0.0 || u > 1.0) return false;
    vec3 q = cross(s, e1);
    float v = dot(d, q) * inv;
    if (v < 0.0 || u + v > 1.0) return false;
    t = dot(e2, q) * inv;
    uv = vec2(u, v);
    return t > tMin && t < tMax;
}

// Whether a hit on triangle `tri` counts for a ray along d: a single-sided material is seen from the
// side its normals face only (the raster passes cull its back faces).
bool lpPtFaceCounts(int tri, vec3 d) {
    LpPathTraceTriangle T = uPtTriangles[tri];
    LpPathTraceMaterial m = uPtMaterials[int(T.position[0].w)];
    if (m.flags.y != 0.0) return true;
    if (m.transmission.x > 0.0 && m.transmission.z > 0.0) return true;  // a volume's inside is met from within
    vec3 n = T.normal[0].xyz + T.normal[1].xyz + T.normal[2].xyz;
    return dot(n, d) < 0.0;
}

// Fresnel reflectance of a smooth dielectric boundary for the cosine cosI on the incident side and
// eta = n_incident / n_transmitted (1: total internal reflection).
float lpPtDielectricFresnel(float cosI, float eta) {
    float sin2T = eta * eta * max(1.0 - cosI * cosI, 0.0);
    if (sin2T >= 1.0) return 1.0;
    float cosT = sqrt(1.0 - sin2T);
    float rs = (eta * cosI - cosT) / (eta * cosI + cosT);
    float rp = (cosI - eta * cosT) / (cosI + eta * cosT);
    return 0.5 * (rs * rs + rp * rp);
}

// Nearest hit in (tMin, tMax): triangle index (or -1), t, barycentrics. `anyHit`: stop at the first.
int lpPtTrace(vec3 o, vec3 d, float tMin, float tMax, bool anyHit, out float tHit, out vec2 uvHit) {
    tHit = tMax;
    uvHit = vec2(0.0);
    if (uPtNodeCount == 0) return -1;
    int hit = -1;
    vec3 invD = 1.0 / d;
    int stack[LP_PT_STACK];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        LpBvhNode n = uPtNodes[stack[--top]];
        vec3 t0 = (n.lo.xyz - o) * invD, t1 = (n.hi.xyz - o) * invD;
        vec3 tn = min(t0, t1), tf = max(t0, t1);
        float enter = max(max(tn.x, tn.y), max(tn.z, tMin));
        float leave = min(min(tf.x, tf.y), min(tf.z, tHit));
        if (enter > leave) continue;
        int first = floatBitsToInt(n.lo.w), count = floatBitsToInt(n.hi.w);
        if (count == 0) {
            if (top + 2 > LP_PT_STACK) continue;  // deeper than the pass allows; never with its check
            stack[top++] = first;
            stack[top++] = first + 1;
            continue;
        }
        for (int i = first; i < first + count; ++i) {
            LpPathTraceTriangle T = uPtTriangles[i];
            float t;
            vec2 uv;
            if (lpPtIntersectTriangle(o, d, T.position[0].xyz, T.position[1].xyz, T.position[2].xyz, tMin, tHit, t, uv) &&
                lpPtFaceCounts(i, d) && !(uHasMaskedMaterials && lpPtAlphaCuts(i, uv))) {
                tHit = t;
                uvHit = uv;
                hit = i;
                if (anyHit) return hit;
            }
        }
    }
    return hit;
}

#endif

#version 450
// gbuffer_resolve: turns the visibility buffer back into the G-buffer targets gbuffer.frag writes.
// Per pixel: the id gives the triangle (common/visibility.glsl) and its draw (binary search over the
// draws' first triangles); its three vertices come from the scene's concatenated vertex and index
// buffers; the pixel's ray through the current (jittered) projection meets the triangle at
// perspective-correct barycentrics, and the rays of the pixel's neighbours in its 2x2 quad give the
// uv derivatives dFdxFine / dFdyFine would, so textures are sampled with the raster's footprint. The material is
// evaluated by common/material.glsl, the function gbuffer.frag calls.
// Dispatched once with uMaterialFilter = -1 (every pixel of an untextured material, and the
// background), then once per textured material with its maps on units 0..4 (no bindless textures in
// GL 4.5 core): each pixel is written by exactly one dispatch.
// Defines: gbufferImageDefines (passes/gbuffer_pass.hpp), LP_VERTEX_FLOATS (floats per vertex), and
// LP_ANISOTROPY_FROM_GRADIENTS where the driver's anisotropic filter ignores textureGrad's gradients in
// compute (engine/gl/gradient_probe): the maps are then filtered by common/material.glsl's
// textureGradAnisotropic, at the level the driver's raster would take (per 2x2 quad where it does).
#include "common/gbuffer_layout.glsl"
#include "common/velocity.glsl"
#include "common/material.glsl"
#include "common/visibility.glsl"
#include "common/gbuffer_images.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 5) uniform usampler2D uVisibility;  // R32UI ids, meaningful only where uDepth holds a surface
// gbuffer.depth: the cleared value uBackgroundDepth where nothing was drawn (the depth test is strict,
// so a drawn fragment never equals it). The ids are not cleared (the clear alone cost 0.59 ms at 4K
// on an H100): the depth says where they hold a triangle.
layout(binding = 6) uniform sampler2D uDepth;
uniform float uBackgroundDepth;

uniform int uMaterialFilter;   // -1: untextured materials and the background; else this material only
uniform uint uDrawCount;
uniform mat4 uInverseProjection;  // inverse of the jittered projection the ids were rasterised with
uniform mat4 uProjection;         // that projection
// 2^GL_SUBPIXEL_BITS where the rasteriser interpolates from vertices snapped to that grid
// (engine/gl/raster_probe), else 0: the pixel's ray through the exact triangle.
uniform float uSubpixelSnap;
uniform bool uDepthZeroToOne;     // clip control 0..1 (reversed-Z): the near clip plane is z = 0, else z = -w

// lp::VisibilityDrawRecord
struct DrawRecord {
    uint firstTriangle;
    uint firstIndex;
    uint vertexBase;
    uint mesh;
    int material;
    uint indexCount;
    uint pad0;
    uint pad1;
};
// Per mesh, per frame: eye-space transforms and the unjittered clip transforms of the velocity.
struct MeshRecord {
    mat4 modelView;
    mat4 normalMatrix;  // inverse transpose of modelView's 3x3, in the upper 3x3
    mat4 clipFromModel;
    mat4 previousClipFromModel;
};
// lp::GpuMaterial
struct MaterialRecord {
    vec4 diffuseOpacity;
    vec4 specularMetallic;
    vec4 shininessRoughnessBumpNormal;  // shininess, roughness, bump scale, normal scale
    vec4 occlusionCutoff;               // occlusion strength, alpha cutoff, KHR_materials_specular's f90
    vec4 clearcoat;                     // KHR_materials_clearcoat's factor, roughness, normal map scale
    uvec4 flags;                        // x: LP_MAP_* of its maps and LP_MATERIAL_* bits, y: LP_MAP_* of the maps on the second uv set
};
const uint LP_MATERIAL_ALPHA_MASK = 2048u, LP_MATERIAL_FLAT = 4096u, LP_MATERIAL_SPECULAR_F90 = 8192u;
const uint LP_MATERIAL_ANY_MAP = LP_MAP_DIFFUSE | LP_MAP_BUMP | LP_MAP_NORMAL | LP_MAP_METAL_ROUGH | LP_MAP_OCCLUSION |
                                 LP_MAP_SPECULAR | LP_MAP_SPECULAR_COLOR | LP_MAP_CLEARCOAT | LP_MAP_CLEARCOAT_ROUGHNESS |
                                 LP_MAP_CLEARCOAT_NORMAL;

layout(std430, binding = 0) readonly buffer Vertices { float vertices[]; };
layout(std430, binding = 1) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 2) readonly buffer Draws { DrawRecord draws[]; };
layout(std430, binding = 3) readonly buffer Meshes { MeshRecord meshes[]; };
layout(std430, binding = 4) readonly buffer Materials { MaterialRecord materials[]; };
#ifdef LP_SECOND_UV  // a material samples TEXCOORD_1: every vertex's second uv set, numbered as `vertices`
layout(std430, binding = 5) readonly buffer SecondUvs { vec2 secondUvs[]; };
#endif
// The previous frame's position of every vertex of an animated mesh (w = 1), 0 elsewhere: read
// only when the scene animates (uAnimated); a still vertex's previous position is its position.
layout(std430, binding = LP_PREVIOUS_POSITIONS_BINDING) readonly buffer PreviousPositions { vec4 previousPositions[]; };
uniform bool uAnimated;
vec3 previousPosition(uint v, vec3 current) {
    if (!uAnimated) return current;
    vec4 p = previousPositions[v];
    return p.w == 1.0 ? p.xyz : current;
}

// The last draw whose first triangle is <= triangle.
uint findDraw(uint triangle) {
    uint lo = 0u, hi = uDrawCount - 1u;
    while (lo < hi) {
        uint mid = (lo + hi + 1u) >> 1;
        if (draws[mid].firstTriangle <= triangle) lo = mid;
        else hi = mid - 1u;
    }
    return lo;
}

#if LP_VERTEX_FLOATS == 16
// The same buffer as four vec4 a vertex (position, normal, uv, tangent, colour: lp::Vertex): one
// 16-byte load instead of four scalar ones.
layout(std430, binding = 0) readonly buffer VertexQuads { vec4 vertexQuads[]; };
vec3 vertexPosition(uint v) { return vertexQuads[4u * v].xyz; }
vec3 vertexNormal(uint v) { return vec3(vertexQuads[4u * v].w, vertexQuads[4u * v + 1u].xy); }
vec2 vertexUv(uint v) { return vertexQuads[4u * v + 1u].zw; }
vec4 vertexTangent(uint v) { return vertexQuads[4u * v + 2u]; }
vec4 vertexColor(uint v) { return vertexQuads[4u * v + 3u]; }
#else
vec3 vertexPosition(uint v) { uint b = v * uint(LP_VERTEX_FLOATS); return vec3(vertices[b], vertices[b + 1u], vertices[b + 2u]); }
vec3 vertexNormal(uint v) { uint b = v * uint(LP_VERTEX_FLOATS) + 3u; return vec3(vertices[b], vertices[b + 1u], vertices[b + 2u]); }
vec2 vertexUv(uint v) { uint b = v * uint(LP_VERTEX_FLOATS) + 6u; return vec2(vertices[b], vertices[b + 1u]); }
vec4 vertexTangent(uint v) {
    uint b = v * uint(LP_VERTEX_FLOATS) + 8u;
    return vec4(vertices[b], vertices[b + 1u], vertices[b + 2u], vertices[b + 3u]);
}
vec4 vertexColor(uint v) {
    uint b = v * uint(LP_VERTEX_FLOATS) + 12u;
    return vec4(vertices[b], vertices[b + 1u], vertices[b + 2u], vertices[b + 3u]);
}
#endif

// The eye-space direction of the ray through window position `window` (pixels).
vec3 eyeRay(vec2 window, vec2 size) {
    vec4 far = uInverseProjection * vec4(window / size * 2.0 - 1.0, 1.0, 1.0);
    return far.xyz / far.w;
}

vec2 snappedWindow(vec4 c, vec2 size) { return round((c.xy / c.w * 0.5 + 0.5) * size * uSubpixelSnap) / uSubpixelSnap; }

// The rasteriser's own arithmetic where it interpolates from snapped vertices: the triangle clipped
// to the depth planes (-w or 0 <= z <= w, as GL clips without depth clamp; a fan from the first
// vertex, as clippers emit it), each vertex's window position snapped to the sub-pixel grid, and the
// perspective-correct weights of the piece that holds the pixel, turned back into the whole
// triangle's. The quad partners use the same piece's plane, as helper invocations do. False when no
// piece holds the pixel (rounding at a piece's edge): the caller then takes the exact ray.
bool insideDepthPlanes(vec4 c) { return (uDepthZeroToOne ? c.z : c.z + c.w) >= 0.0 && c.w - c.z >= 0.0; }

bool snappedBarycentrics(vec4 c0, vec4 c1, vec4 c2, vec2 window, vec2 partnerX, vec2 partnerY, vec2 size,
                         out vec3 b, out vec3 bx, out vec3 by) {
    if (insideDepthPlanes(c0) && insideDepthPlanes(c1) && insideDepthPlanes(c2)) {
        // Nothing to clip (nearly every triangle): the general path below with one piece whose
        // weights are the identity, without its arrays (indexed at run time, they live in slow
        // per-thread memory).
        vec2 s0 = snappedWindow(c0, size), s1 = snappedWindow(c1, size), s2 = snappedWindow(c2, size);
        vec3 w = vec3(c0.w, c1.w, c2.w);
        b = windowBarycentrics(window, s0, s1, s2, w);
        if (any(lessThan(b, vec3(0.0)))) return false;
        bx = windowBarycentrics(partnerX, s0, s1, s2, w);
        by = windowBarycentrics(partnerY, s0, s1, s2, w);
        return true;
    }
    vec4 clip[5];
    vec3 weight[5];
    int n = 3;
    clip[0] = c0; clip[1] = c1; clip[2] = c2;
    weight[0] = vec3(1.0, 0.0, 0.0); weight[1] = vec3(0.0, 1.0, 0.0); weight[2] = vec3(0.0, 0.0, 1.0);
    for (int plane = 0; plane < 2; ++plane) {
        vec4 inClip[5];
        vec3 inWeight[5];
        int m = n;
        for (int i = 0; i < 5; ++i) {
            inClip[i] = clip[i];
            inWeight[i] = weight[i];
        }
        n = 0;
        for (int i = 0; i < m; ++i) {
            vec4 a = inClip[i], c = inClip[(i + 1) % m];
            float da = plane == 0 ? (uDepthZeroToOne ? a.z : a.z + a.w) : a.w - a.z;
            float dc = plane == 0 ? (uDepthZeroToOne ? c.z : c.z + c.w) : c.w - c.z;
            if (da >= 0.0 && n < 5) {
                clip[n] = a;
                weight[n] = inWeight[i];
                ++n;
            }
            if ((da >= 0.0) != (dc >= 0.0) && n < 5) {
                float t = da / (da - dc);
                clip[n] = mix(a, c, t);
                weight[n] = mix(inWeight[i], inWeight[(i + 1) % m], t);
                ++n;
            }
        }
    }
    if (n < 3) return false;
    vec2 s0 = snappedWindow(clip[0], size);
    for (int k = 1; k + 1 < n; ++k) {
        vec2 s1 = snappedWindow(clip[k], size), s2 = snappedWindow(clip[k + 1], size);
        vec3 w = vec3(clip[0].w, clip[k].w, clip[k + 1].w);
        vec3 l = windowBarycentrics(window, s0, s1, s2, w);
        if (any(lessThan(l, vec3(0.0)))) continue;
        mat3 toTriangle = mat3(weight[0], weight[k], weight[k + 1]);
        b = toTriangle * l;
        bx = toTriangle * windowBarycentrics(partnerX, s0, s1, s2, w);
        by = toTriangle * windowBarycentrics(partnerY, s0, s1, s2, w);
        return true;
    }
    return false;
}

// A uv set at the pixel (barycentrics b) and its dFdxFine / dFdyFine, from its quad partners' (bx, by).
TexCoord resolveTexCoord(vec2 t0, vec2 t1, vec2 t2, vec3 b, vec3 bx, vec3 by, bvec2 odd) {
    TexCoord t;
    t.uv = interpolateAttribute(b, t0, t1, t2);
    vec2 uvX = interpolateAttribute(bx, t0, t1, t2), uvY = interpolateAttribute(by, t0, t1, t2);
    t.dx = odd.x ? t.uv - uvX : uvX - t.uv;
    t.dy = odd.y ? t.uv - uvY : uvY - t.uv;
    return t;
}

MaterialInputs materialInputs(MaterialRecord r) {
    uint f = r.flags.x;
    return MaterialInputs(r.diffuseOpacity.rgb, r.diffuseOpacity.a, r.specularMetallic.rgb, r.specularMetallic.a,
                          r.shininessRoughnessBumpNormal.x, r.shininessRoughnessBumpNormal.y,
                          r.shininessRoughnessBumpNormal.z, r.shininessRoughnessBumpNormal.w, r.occlusionCutoff.x,
                          r.occlusionCutoff.y, (f & LP_MAP_DIFFUSE) != 0u, (f & LP_MAP_BUMP) != 0u,
                          (f & LP_MAP_NORMAL) != 0u, (f & LP_MAP_METAL_ROUGH) != 0u, (f & LP_MAP_OCCLUSION) != 0u, (f & LP_MATERIAL_ALPHA_MASK) != 0u,
                          (f & LP_MATERIAL_FLAT) != 0u, r.flags.y, r.occlusionCutoff.z, (f & LP_MATERIAL_SPECULAR_F90) != 0u,
                          (f & LP_MAP_SPECULAR) != 0u, (f & LP_MAP_SPECULAR_COLOR) != 0u, r.clearcoat.x, r.clearcoat.y,
                          r.clearcoat.z, (f & LP_MAP_CLEARCOAT) != 0u, (f & LP_MAP_CLEARCOAT_ROUGHNESS) != 0u,
                          (f & LP_MAP_CLEARCOAT_NORMAL) != 0u);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 isize = textureSize(uVisibility, 0);
    if (any(greaterThanEqual(p, isize))) return;
    vec2 size = vec2(isize);
    if (texelFetch(uDepth, p, 0).r == uBackgroundDepth) {
        if (uMaterialFilter < 0) storeBackground(p, size);
        return;
    }
    uint triangle = visibilityTriangle(texelFetch(uVisibility, p, 0).r);
    DrawRecord d = draws[findDraw(triangle)];
    MaterialRecord mr = materials[d.material];
    bool textured = (mr.flags.x & LP_MATERIAL_ANY_MAP) != 0u;
    if (uMaterialFilter < 0 ? textured : d.material != uMaterialFilter) return;

    uint first = d.firstIndex + 3u * (triangle - d.firstTriangle);
    uint i0 = indices[first] + d.vertexBase, i1 = indices[first + 1u] + d.vertexBase, i2 = indices[first + 2u] + d.vertexBase;
    MeshRecord mesh = meshes[d.mesh];
    vec3 o0 = vertexPosition(i0), o1 = vertexPosition(i1), o2 = vertexPosition(i2);
    vec3 e0 = (mesh.modelView * vec4(o0, 1.0)).xyz;
    vec3 e1 = (mesh.modelView * vec4(o1, 1.0)).xyz;
    vec3 e2 = (mesh.modelView * vec4(o2, 1.0)).xyz;

    // The pixel's ray, and the rays of its partners in its 2x2 quad along x and y: the differences
    // are dFdxFine / dFdyFine of the uv (gbuffer.frag's derivatives), extended over the triangle's
    // plane as the raster's helper invocations are.
    vec2 window = vec2(p) + 0.5;
    bvec2 odd = bvec2((p.x & 1) != 0, (p.y & 1) != 0);
    vec2 partnerX = window + vec2(odd.x ? -1.0 : 1.0, 0.0), partnerY = window + vec2(0.0, odd.y ? -1.0 : 1.0);
    vec4 c0 = uProjection * vec4(e0, 1.0), c1 = uProjection * vec4(e1, 1.0), c2 = uProjection * vec4(e2, 1.0);
    vec3 b, bx, by;
    if (uSubpixelSnap <= 0.0 || !snappedBarycentrics(c0, c1, c2, window, partnerX, partnerY, size, b, bx, by)) {
        b = rayTriangleBarycentrics(vec3(0.0), eyeRay(window, size), e0, e1, e2);
        bx = rayTriangleBarycentrics(vec3(0.0), eyeRay(partnerX, size), e0, e1, e2);
        by = rayTriangleBarycentrics(vec3(0.0), eyeRay(partnerY, size), e0, e1, e2);
    }

    // Every attribute in the raster's plane-equation form (interpolateAttribute): what the three
    // vertices share, such as a floor's eye z, comes out exact, as gbuffer.frag's inputs do.
    UvSets uvs;
    uvs.set0 = resolveTexCoord(vertexUv(i0), vertexUv(i1), vertexUv(i2), b, bx, by, odd);
    uvs.set1 = uvs.set0;
#ifdef LP_SECOND_UV
    if (mr.flags.y != 0u) uvs.set1 = resolveTexCoord(secondUvs[i0], secondUvs[i1], secondUvs[i2], b, bx, by, odd);
#endif
#ifdef LP_ANISOTROPY_FROM_GRADIENTS
    // The footprint the own anisotropic filter takes its level from: the pixel's, or where the
    // driver's raster takes one level per 2x2 quad, its first pixel's on this pixel's triangle (as
    // the raster's helper invocations extend it).
    uvs.set0.quadDx = uvs.set0.dx;
    uvs.set0.quadDy = uvs.set0.dy;
    uvs.set1.quadDx = uvs.set1.dx;
    uvs.set1.quadDy = uvs.set1.dy;
    if (uAnisotropyPerQuad && any(odd)) {
        vec2 q = vec2(p & ~1) + 0.5, qx = q + vec2(1.0, 0.0), qy = q + vec2(0.0, 1.0);
        vec3 bq, bqx, bqy;
        if (uSubpixelSnap <= 0.0 || !snappedBarycentrics(c0, c1, c2, q, qx, qy, size, bq, bqx, bqy)) {
            bq = rayTriangleBarycentrics(vec3(0.0), eyeRay(q, size), e0, e1, e2);
            bqx = rayTriangleBarycentrics(vec3(0.0), eyeRay(qx, size), e0, e1, e2);
            bqy = rayTriangleBarycentrics(vec3(0.0), eyeRay(qy, size), e0, e1, e2);
        }
        TexCoord quad = resolveTexCoord(vertexUv(i0), vertexUv(i1), vertexUv(i2), bq, bqx, bqy, bvec2(false));
        uvs.set0.quadDx = quad.dx;
        uvs.set0.quadDy = quad.dy;
        uvs.set1.quadDx = quad.dx;
        uvs.set1.quadDy = quad.dy;
#ifdef LP_SECOND_UV
        if (mr.flags.y != 0u) {
            quad = resolveTexCoord(secondUvs[i0], secondUvs[i1], secondUvs[i2], bq, bqx, bqy, bvec2(false));
            uvs.set1.quadDx = quad.dx;
            uvs.set1.quadDy = quad.dy;
        }
#endif
    }
#endif
    vec2 uv = uvs.set0.uv;
    vec3 normal = mat3(mesh.normalMatrix) * interpolateAttribute(b, vertexNormal(i0), vertexNormal(i1), vertexNormal(i2));
    vec4 tangentObject = interpolateAttribute(b, vertexTangent(i0), vertexTangent(i1), vertexTangent(i2));
    vec4 tangent = vec4(mat3(mesh.modelView) * tangentObject.xyz, tangentObject.w);

    MaterialInputs m = materialInputs(mr);
#ifdef LP_VERTEX_COLOR
    vec4 vertexColors = interpolateAttribute(b, vertexColor(i0), vertexColor(i1), vertexColor(i2));
#else
    vec4 vertexColors = vec4(1.0);  // the scene has none (common/vertex_color.glsl)
#endif
    vec4 base = materialBaseColor(m, uvs, vertexColors);
    vec3 position = interpolateAttribute(b, e0, e1, e2);
    MaterialSample g =
        materialEvaluate(m, base, SurfaceInputs(normal, tangent, uvs, eyeTriangleFrontFacing(e0, e1, e2), position));
    g.shininess = gbufferEncodeShininess(g.shininess);  // the half-float channel's encoding (to the 0.02 floor)
    if ((uTargets & LP_TARGET_NORMAL) != 0u) storeNormal(p, g.normal, g.shininess);
    if ((uTargets & LP_TARGET_DIFFUSE) != 0u) storeDiffuse(p, g.kd, m.flatLit ? 0.0 : gbufferEncodeOcclusion(g.occlusion));
#ifndef LP_GBUFFER_POSITION_FROM_DEPTH
    if ((uTargets & LP_TARGET_POSITION) != 0u) imageStore(uPositionOut, p, vec4(position, 1.0));
#endif
    if ((uTargets & LP_TARGET_SPECULAR) != 0u) storeSpecular(p, g.f0, g.shininess);
#ifdef LP_GBUFFER_CLEARCOAT
    if ((uTargets & LP_TARGET_CLEARCOAT) != 0u) imageStore(uClearcoatOut, p, materialClearcoatValue(g));
#else
    if ((uTargets & LP_TARGET_TEXCOORD) != 0u) imageStore(uTexcoordOut, p, vec4(uv, 0.0, 0.0));
#endif
    if ((uTargets & LP_TARGET_TANGENT) != 0u) imageStore(uTangentOut, p, g.tangentView);
#ifdef LP_GBUFFER_FRESNEL
    if ((uTargets & LP_TARGET_FRESNEL) != 0u) imageStore(uFresnelOut, p, vec4(materialFresnelValue(g), 0.0, 0.0));
#else
    if ((uTargets & LP_TARGET_MATERIAL_INPUT) != 0u) imageStore(uMaterialInputOut, p, materialInputValue(g));
#endif
    if ((uTargets & LP_TARGET_VELOCITY) != 0u) {
        vec4 object = vec4(interpolateAttribute(b, o0, o1, o2), 1.0);
        vec4 previousObject = vec4(interpolateAttribute(b, previousPosition(i0, o0), previousPosition(i1, o1), previousPosition(i2, o2)), 1.0);
        vec2 v = velocityFromClip(mesh.clipFromModel * object, mesh.previousClipFromModel * previousObject);
        imageStore(uVelocityOut, p, vec4(v, 0.0, 0.0));
    }
}

#version 450
// Poses an animated model's vertices (--skinning gpu; engine/render/gpu_skinning.hpp): one
// invocation a vertex of a moving range, poseVertices' arithmetic (engine/scene/animation.cpp) in
// the same order: morphed by the node's weights, then skinned by the weighted sum of its joints'
// matrices (normals by its cofactor, tangents by the matrix) or placed by the node's world and
// normal matrix; normals and tangents renormalised. Writes the mesh's vertex buffer, which every
// pass draws from, and the previous positions the velocity reads.
// Defines: LP_SKINNING_*_BINDING, LP_VERTEX_FLOATS (floats a GpuVertex), the mode and flag bits.
layout(local_size_x = 64) in;

struct RestVertex {
    vec4 position, normal, tangent;
};
struct VertexJoints {
    uvec4 joint0, joint1;
    vec4 weight0, weight1;
};
struct MorphDelta {
    vec4 position, normal, tangent;
};
struct Range {
    uint firstVertex, vertexCount, firstWork, firstDelta, morphTargets, firstWeight, firstMatrix, flags;
};

layout(std430, binding = LP_SKINNING_REST_BINDING) readonly buffer RestBlock { RestVertex rest[]; };
layout(std430, binding = LP_SKINNING_JOINTS_BINDING) readonly buffer JointsBlock { VertexJoints joints[]; };
layout(std430, binding = LP_SKINNING_DELTAS_BINDING) readonly buffer DeltasBlock { MorphDelta deltas[]; };
layout(std430, binding = LP_SKINNING_RANGES_BINDING) readonly buffer RangesBlock { Range ranges[]; };
layout(std430, binding = LP_SKINNING_WORK_RANGE_BINDING) readonly buffer WorkRangeBlock { uint workRange[]; };
// The pose: matrices (four columns each), then the morph weights, four a vec4.
layout(std430, binding = LP_SKINNING_POSE_BINDING) readonly buffer PoseBlock { vec4 pose[]; };
layout(std430, binding = LP_SKINNING_VERTICES_BINDING) buffer VerticesBlock { float vertices[]; };
layout(std430, binding = LP_SKINNING_PREVIOUS_BINDING) buffer PreviousBlock { vec4 previous[]; };

uniform uint uWorkCount;
uniform uint uPoseBase;    // vec4s into pose[] where this dispatch's pose begins
uniform uint uWeightBase;  // floats from there to its weights
uniform uint uMode;        // LP_SKINNING_POSE_VERTICES | LP_SKINNING_POSE_PREVIOUS | LP_SKINNING_KEEP_PREVIOUS

mat4 poseMatrix(uint m) {
    const uint b = uPoseBase + 4u * m;
    return mat4(pose[b], pose[b + 1u], pose[b + 2u], pose[b + 3u]);
}
float poseWeight(uint w) {
    const uint i = 4u * uPoseBase + uWeightBase + w;
    return pose[i >> 2u][i & 3u];
}
mat3 cofactor(mat3 m) { return mat3(cross(m[1], m[2]), cross(m[2], m[0]), cross(m[0], m[1])); }
bool finitePositive(float x) { return x > 0.0 && !isinf(x) && !isnan(x); }

void main() {
    const uint w = gl_GlobalInvocationID.x;
    if (w >= uWorkCount) return;
    const Range r = ranges[workRange[w]];
    const uint i = w - r.firstWork;
    const uint base = (r.firstVertex + i) * uint(LP_VERTEX_FLOATS);
    vec3 p = rest[w].position.xyz, n = rest[w].normal.xyz;
    vec4 t = rest[w].tangent;
    for (uint k = 0u; k < r.morphTargets; ++k) {
        const float weight = poseWeight(r.firstWeight + k);
        if (weight == 0.0) continue;
        const MorphDelta d = deltas[r.firstDelta + k * r.vertexCount + i];
        p += weight * d.position.xyz;
        n += weight * d.normal.xyz;
        t.xyz += weight * d.tangent.xyz;
    }
    vec3 position, normal, tangent;
    if ((r.flags & LP_SKINNING_RANGE_SKINNED) != 0u) {
        const VertexJoints vj = joints[w];
        mat4 m = mat4(0.0);
        float sum = 0.0;
        for (int k = 0; k < 4; ++k) {
            if (vj.weight0[k] != 0.0) {
                m += vj.weight0[k] * poseMatrix(r.firstMatrix + vj.joint0[k]);
                sum += vj.weight0[k];
            }
        }
        for (int k = 0; k < 4; ++k) {
            if (vj.weight1[k] != 0.0) {
                m += vj.weight1[k] * poseMatrix(r.firstMatrix + vj.joint1[k]);
                sum += vj.weight1[k];
            }
        }
        if (sum == 0.0) m = mat4(1.0);
        const mat3 ml = mat3(m);
        position = (m * vec4(p, 1.0)).xyz;
        normal = (determinant(ml) < 0.0 ? -1.0 : 1.0) * (cofactor(ml) * n);
        if (!(length(normal) > 0.0)) normal = ml * n;  // a joint matrix scaling a plane to a line
        tangent = ml * t.xyz;
    } else {
        const mat4 world = poseMatrix(r.firstMatrix);
        position = (world * vec4(p, 1.0)).xyz;
        normal = mat3(poseMatrix(r.firstMatrix + 1u)) * n;
        tangent = mat3(world) * t.xyz;
    }
    if ((uMode & LP_SKINNING_POSE_PREVIOUS) != 0u) {
        previous[r.firstVertex + i] = vec4(position, 1.0);
        return;
    }
    if ((uMode & LP_SKINNING_KEEP_PREVIOUS) != 0u)
        previous[r.firstVertex + i] = vec4(vertices[base], vertices[base + 1u], vertices[base + 2u], 1.0);
    if ((uMode & LP_SKINNING_POSE_VERTICES) == 0u) return;
    vertices[base] = position.x;
    vertices[base + 1u] = position.y;
    vertices[base + 2u] = position.z;
    const float nl = length(normal);
    if (finitePositive(nl)) {
        const vec3 u = normal / nl;
        vertices[base + 3u] = u.x;
        vertices[base + 4u] = u.y;
        vertices[base + 5u] = u.z;
    }
    const float tl = length(tangent);
    if (finitePositive(tl)) {
        const vec3 u = tangent / tl;
        vertices[base + 8u] = u.x;
        vertices[base + 9u] = u.y;
        vertices[base + 10u] = u.z;
        vertices[base + 11u] = t.w * ((r.flags & LP_SKINNING_RANGE_MIRRORED) != 0u ? -1.0 : 1.0);
    }
}

#include "passes/skinning_pass.hpp"

#include <algorithm>

#include "engine/gl/shader.hpp"
#include "engine/gl/uniforms.hpp"
#include "engine/render/scene_gpu.hpp"

namespace lp {

namespace {
constexpr GLuint kGroupSize = 64;  // shaders/skinning.comp's local_size_x

// A model whose vertices a playing clip moves (SceneGpu's GpuMesh::animated, from the scene alone).
bool animatesVertices(const ModelInstance& m) {
    return m.animation && !m.playingClips.empty() && !m.animation->ranges.empty() && !m.mesh.vertices.empty();
}
}  // namespace

std::string skinningSkipReason(const FrameData& frame) {
    const Scene& scene = *frame.scene;
    if (!std::any_of(scene.models.begin(), scene.models.end(), animatesVertices))
        return "nothing is animated (no model plays a clip that moves its vertices)";
    if (frame.settings->skinning == SkinningMode::Cpu) return "--skinning cpu: animated models are posed on the CPU and uploaded";
    if (frame.gpu && frame.gpu->skinningWork().empty()) return "the vertex buffers already hold this frame's pose";
    return "";
}

void addSkinningPass(fg::FrameGraph& graph, SkinningPass& state, const FrameData& frame) {
    const fg::ResourceId posed = graph.importBuffer(kPosedVerticesName, [gpu = frame.gpu] {
        // One resource stands for every animated mesh's buffers; it names the first one's.
        if (gpu)
            for (const GpuMesh& m : gpu->meshes)
                if (m.animated) return m.vertices.id();
        return GLuint(0);
    });
    if (frame.gpu) {
        size_t vertices = 0;
        for (const SkinningDispatch& d : frame.gpu->skinningWork())
            if (d.mode != kSkinningPosePrevious) vertices += frame.gpu->meshes[d.mesh].skinning->layout.workCount();
        graph.notePass("skinning", std::to_string(frame.gpu->skinningWork().size()) + " dispatches, " + std::to_string(vertices) +
                                       " vertices posed");
    }
    graph.addPass(
        "skinning", fg::PassKind::Compute, [&](fg::PassBuilder& b) { b.write(posed, fg::Usage::StorageBuffer); },
        [&state, frame](const fg::PassResources&) {
            const SceneGpu& gpu = *frame.gpu;
            if (!state.program) {
                auto define = [](const char* name, unsigned value) { return std::string(name) + " " + std::to_string(value) + "u"; };
                state.program = frame.shaders->compute(
                    "skinning.comp",
                    {define("LP_SKINNING_REST_BINDING", kSkinningRestBinding), define("LP_SKINNING_JOINTS_BINDING", kSkinningJointsBinding),
                     define("LP_SKINNING_DELTAS_BINDING", kSkinningDeltasBinding),
                     define("LP_SKINNING_RANGES_BINDING", kSkinningRangesBinding),
                     define("LP_SKINNING_WORK_RANGE_BINDING", kSkinningWorkRangeBinding),
                     define("LP_SKINNING_POSE_BINDING", kSkinningPoseBinding),
                     define("LP_SKINNING_VERTICES_BINDING", kSkinningVerticesBinding),
                     define("LP_SKINNING_PREVIOUS_BINDING", kSkinningPreviousBinding),
                     define("LP_SKINNING_POSE_VERTICES", kSkinningPoseVertices), define("LP_SKINNING_POSE_PREVIOUS", kSkinningPosePrevious),
                     define("LP_SKINNING_KEEP_PREVIOUS", kSkinningKeepPrevious),
                     define("LP_SKINNING_RANGE_SKINNED", kSkinningRangeSkinned),
                     define("LP_SKINNING_RANGE_MIRRORED", kSkinningRangeMirrored),
                     "LP_VERTEX_FLOATS " + std::to_string(sizeof(GpuVertex) / sizeof(float))});
            }
            const GLuint prog = state.program.id();
            const GLint workCount = gl::Uniforms(frame.shaders, prog).location("uWorkCount"), poseBase = gl::Uniforms(frame.shaders, prog).location("uPoseBase"),
                        weightBase = gl::Uniforms(frame.shaders, prog).location("uWeightBase"), mode = gl::Uniforms(frame.shaders, prog).location("uMode");
            const GLuint bindings[] = {kSkinningRestBinding,  kSkinningJointsBinding,   kSkinningDeltasBinding,   kSkinningRangesBinding,
                                       kSkinningWorkRangeBinding, kSkinningPoseBinding, kSkinningVerticesBinding, kSkinningPreviousBinding};
            glUseProgram(prog);
            for (const SkinningDispatch& d : gpu.skinningWork()) {
                const GpuMesh& m = gpu.meshes[d.mesh];
                const GpuSkinning& s = *m.skinning;
                const GLuint buffers[] = {s.rest.id(),       s.joints.id(),  s.deltas.id(),     s.ranges.id(),
                                          s.workRange.id(), s.pose.current(), m.vertices.id(), m.previousPositions.id()};
                for (size_t k = 0; k < std::size(bindings); ++k) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, bindings[k], buffers[k]);
                glProgramUniform1ui(prog, workCount, s.layout.workCount());
                glProgramUniform1ui(prog, poseBase, d.poseBase);
                glProgramUniform1ui(prog, weightBase, skinningWeightBase(s.layout));
                glProgramUniform1ui(prog, mode, d.mode);
                glDispatchCompute((s.layout.workCount() + kGroupSize - 1) / kGroupSize, 1, 1);
            }
            for (GLuint binding : bindings) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
            glUseProgram(0);
            gpu.skinningWorkDone();
        });
}

void readPosedVertices(fg::PassBuilder& b, const FrameData& frame, fg::Usage how) {
    if (frame.posedVerticesOnGpu) b.read(kPosedVerticesName, how);
}

}  // namespace lp

#pragma once
// One G-buffer channel as an image (depth, normals, diffuse, position, shininess, specular,
// texcoords), decoded from whatever layout the G-buffer has; or a shadow map; or the ambient occlusion; or an environment
// texture (environment, irradiance, prefiltered, dfg). It reads only those, so the graph culls
// lighting and tone mapping by itself.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/ibl_pass.hpp"
#include "passes/shadow_map_pass.hpp"

namespace lp {

struct DebugViewPass {
    gl::Program program, environmentProgram;
    GBufferProgramKey layout, environmentLayout;  // the G-buffer layouts the programs were compiled for
};

// The velocity view is at full brightness for motion of this many output pixels per frame (linear
// below; shaders/common/velocity.glsl velocityViewColour).
inline constexpr float kVelocityViewFullScalePixels = 16.0f;

// The eye depths the scene's bounds span from frame's camera, within near..far (the depth-fitted
// view maps them to 0..1); near..far when the bounds give no range.
glm::vec2 sceneDepthRange(const FrameData& frame);
// Which G-buffer channels `view` needs (texcoords are only written for their view).
GBufferChannels channelsForView(DebugView view);
// `shadowMaps`: this frame's maps (the shadowmap view); `environment`: imported with a bake for the
// irradiance and prefiltered views (importEnvironment), unused by the G-buffer views; `ao`: the
// ambient-occlusion target (the ao view, passes/ambient_occlusion_pass).
fg::ResourceId addDebugViewPass(fg::FrameGraph& graph, DebugViewPass& state, const FrameData& frame,
                                const GBuffer& gbuffer, const ShadowMaps& shadowMaps,
                                const EnvironmentTextures& environment, DebugView view, fg::ResourceId ao = {});

}  // namespace lp

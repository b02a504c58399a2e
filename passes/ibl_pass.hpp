#pragma once
// Image-based lighting: adds the environment's diffuse (SH or irradiance cube) and specular
// (prefiltered GGX chain x split-sum DFG) light into the HDR buffer, when
// EnvironmentSettings::ibl is on and the scene has an environment map. The environment views
// (environment, irradiance, prefiltered, dfg) are drawn here too.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "engine/render/ibl_environment.hpp"
#include "passes/gbuffer_pass.hpp"

namespace lp {

struct IblPass {
    EnvironmentCache environments;  // cubes and bakes, made once per environment and kept
    gl::Program program;
    gl::Program debugProgram;
    GBufferSettings layout, debugLayout;  // the G-buffer layouts the programs were compiled for
};

bool isEnvironmentView(DebugView view);

// Returns `hdr` unchanged (and adds no pass) when IBL is off or the scene has no map.
fg::ResourceId addIblPass(fg::FrameGraph& graph, IblPass& state, const FrameData& frame, const GBuffer& gbuffer,
                          fg::ResourceId hdr, bool lightingOnly);

// "ibl_bake": makes the environment cube and, if `bake`, its irradiance / prefiltered cubes and the
// DFG LUT. The frame builder adds it only in a frame where the cache lacks them (the environment or
// the bake settings changed); a side effect, so it runs first and the ibl and sky passes find them made.
void addIblBakePass(fg::FrameGraph& graph, IblPass& state, const FrameData& frame, bool bake);

// An environment debug view into a new RGBA8 image (pass name "debug_view").
fg::ResourceId addIblDebugViewPass(fg::FrameGraph& graph, IblPass& state, const FrameData& frame,
                                   const GBuffer& gbuffer, DebugView view);

}  // namespace lp

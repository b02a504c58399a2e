#pragma once
// Builds one frame's graph from the scene and the settings. Every pass a frame could use is added;
// the outputs chosen by the settings (final image, a debug view, the HDR buffer) decide what
// survives compile(), so e.g. the normals view culls lighting and tone mapping by itself.
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/debug_view_pass.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/post_pass.hpp"
#include "passes/global_light_pass.hpp"
#include "passes/local_light_pass.hpp"
#include "passes/sky_pass.hpp"
#include "passes/tonemap_pass.hpp"

namespace lp {

// GL state of every pass (programs, framebuffers), made lazily on first execute.
struct PassStates {
    GBufferPass gbuffer;
    GlobalLightPass globalLights;
    SkyPass sky;
    ToneMapPass tonemap;
    DebugViewPass debugView;
    ShadowMapPass shadowMaps;  // the depth-only program and framebuffer
    IblPass ibl;  // environment cache (cubes, bakes, DFG LUT) and the IBL programs
    LocalLightPass localLights;
    PostPasses post;
};

struct FrameOutputs {
    fg::ResourceId display;  // RGBA8, what is shown or saved as PNG
    fg::ResourceId hdr;      // RGBA16F linear radiance (valid when the view has one)
};

FrameOutputs buildFrameGraph(fg::FrameGraph& graph, PassStates& passes, const FrameData& frame);

// Camera matrices, planes and sizes for a frame of `scene` under `settings`.
FrameData makeFrameData(const Scene& scene, const RenderSettings& settings, float time);

}  // namespace lp

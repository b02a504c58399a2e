#pragma once
// Ranged point lights added into the HDR buffer, by one of four methods that give the
// same image (settings.localLights.method): fullscreen, scissor, volumes, tiled. Plus the overlays:
// light globes, the light-ranges view and the lights-per-tile heat map.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/gbuffer_pass.hpp"

namespace lp {

// What the last executed local-light pass did, for tests and the UI.
struct LocalLightStats {
    LocalLightMethod method = LocalLightMethod::Tiled;
    int requested = 0;   // lights in the SSBO this frame
    int drawn = 0;       // lights the method shaded: draw calls, instances, or lights the tiles binned from
    int offscreen = 0;   // scissor method: lights skipped because their rectangle was empty
    int fullScreen = 0;  // scissor method: lights drawn full screen (camera inside / near plane crossed)
};

struct LocalLightPass {
    gl::Program fragmentProgram;  // local_light.vert/.frag: fullscreen, scissor, volumes
    gl::Program tiledProgram;     // local_light_tiled.comp
    gl::Program heatmapProgram;   // local_light_tiled.comp with LP_TILE_HEATMAP
    gl::Program sanitizeProgram;  // local_light_sanitize.comp
    gl::Program overlayProgram;   // local_light_overlay.vert/.frag: globes, volumes, rectangles
    gl::Program globeVelocityProgram;  // the same with LP_GLOBE_VELOCITY: globes and their motion vectors
    GBufferSettings layout;       // the G-buffer layout the fragment, tiled and heatmap programs were compiled for
    gl::Framebuffer fbo;
    gl::Buffer lights;            // SSBO of GpuLocalLight
    gl::Buffer globeMotion;       // SSBO of each light's world centre now and at the previous frame's time
    size_t globeMotionCapacity = 0;
    size_t lightCapacity = 0;
    gl::Buffer volumeMesh, globeMesh;
    gl::VertexArray volumeVao, globeVao;
    int volumeVertices = 0, globeVertices = 0;
    LocalLightStats stats;
};

// Adds the "local_lights" pass (read-modify-write of hdr). Whether the frame needs it (lights on,
// some in view) is the frame builder's decision.
fg::ResourceId addLocalLightPass(fg::FrameGraph& graph, LocalLightPass& state, const FrameData& frame,
                                 const GBuffer& gbuffer, fg::ResourceId hdr, bool lightingOnly);

// After the sky: "light_globes" (settings.localLights.globes, else the scene's lightGlobes) and the overlay views
// ("light_ranges", "lights_per_tile") over the finished HDR image. When the frame has gbuffer.velocity,
// the globes also write their motion into it (their lights orbit): gbuffer.velocity becomes that new
// version, for the passes that read motion after them.
fg::ResourceId addLocalLightOverlayPasses(fg::FrameGraph& graph, LocalLightPass& state, const FrameData& frame,
                                          GBuffer& gbuffer, fg::ResourceId hdr);

}  // namespace lp

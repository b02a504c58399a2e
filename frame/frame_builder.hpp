#pragma once
// Builds one frame's graph from the scene and the settings. A pass is added only when the scene
// calls for it (a shadow-casting sun, a local light in view, an environment, an enabled effect);
// every candidate left out is recorded with FrameGraph::skipPass and its reason. The outputs chosen
// by the settings (final image, a debug view, the HDR buffer) then decide what survives compile(),
// so e.g. the normals view culls lighting and tone mapping by itself. RenderSettings::allPasses
// adds every candidate regardless (to measure what the scene-driven graph saves).
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/ambient_occlusion_pass.hpp"
#include "passes/auto_exposure_pass.hpp"
#include "passes/debug_view_pass.hpp"
#include "passes/emission_pass.hpp"
#include "passes/downsample_pass.hpp"
#include "passes/forward_pass.hpp"
#include "passes/fxaa_pass.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/post_pass.hpp"
#include "passes/global_light_pass.hpp"
#include "passes/hdr_view_pass.hpp"
#include "passes/ibl_pass.hpp"
#include "passes/local_light_pass.hpp"
#include "passes/motion_blur_pass.hpp"
#include "passes/path_trace_pass.hpp"
#include "passes/skinning_pass.hpp"
#include "passes/sky_pass.hpp"
#include "passes/point_shadow_pass.hpp"
#include "passes/spot_shadow_pass.hpp"
#include "passes/taa_pass.hpp"
#include "passes/tonemap_pass.hpp"
#include "passes/transparent_pass.hpp"
#include "passes/upscale_pass.hpp"
#include "passes/visibility_pass.hpp"
#include "passes/visibility_resolve_pass.hpp"

namespace lp {

// GL state of every pass (programs, framebuffers), made lazily on first execute; and the textures
// that outlive a frame, which each frame's graph imports.
struct PassStates {
    SkinningPass skinning;  // --skinning gpu: animated models posed once a frame for every pass
    GBufferPass gbuffer;
    VisibilityPass visibility;          // --gbuffer-mode visibility: gbuffer_visibility
    VisibilityResolvePass visibilityResolve;  // and gbuffer_resolve
    GlobalLightPass globalLights;
    SkyPass sky;
    ToneMapPass tonemap;
    DebugViewPass debugView;
    ShadowMapPass shadowMaps;  // the depth-only program and framebuffer
    SpotShadowPass spotShadows;
    PointShadowPass pointShadows;  // kept cube atlas (--shadow-cache)
    IblPass ibl;
    LocalLightPass localLights;
    ForwardPass forward;          // forward+'s forward_opaque
    TransparentPass transparent;  // alpha-blended surfaces, both render paths
    MotionBlurPass motionBlur;
    EmissionPass emission;
    PostPasses post;
    UpscalePass upscale;
    DownsamplePass downsample;
    FxaaPass fxaa;
    TaaPass taa;  // holds the TAA history across frames (imported into each frame's graph)
    HdrViewPass hdrView;
    AutoExposurePass autoExposure;
    AmbientOcclusionPass ambientOcclusion;
    PathTracePass pathTrace;  // --render-path pathtraced: the BVH, scene buffers and accumulated samples
    // Environment cubes, IBL bakes and the DFG LUT, kept across frames; imported into the graph
    // (written there by ibl_bake in the frame where they change).
    EnvironmentCache environments;
};

struct FrameOutputs {
    fg::ResourceId display;  // RGBA8, what is shown or saved as PNG (dithered unless --no-dither)
    fg::ResourceId hdr;      // RGBA16F linear radiance (valid when the view has one)
};

// The one entry point: frame.scene and frame.settings decide the passes. After graph.compile(),
// graph.explain() lists every candidate pass as "runs" or "skipped: <reason>".
// frame.environments is set to &passes.environments here.
FrameOutputs buildFrameGraph(fg::FrameGraph& graph, PassStates& passes, const FrameData& frame);

// For --explain: notes on the ibl pass (when it runs) saying which sources light extraction takes out of
// the scene's map (direction, irradiance, solid angle) or why none. Reads the map on the CPU; no GL.
void noteEnvironmentLights(fg::FrameGraph& graph, const Scene& scene, const RenderSettings& settings);

// Throws lp::Error for a --disable-pass name that is no candidate pass of `graph` (built, compiled),
// listing the candidates: "--disable-pass foo: no such pass (gbuffer, shadow_map_0, ...)".
void checkDisabledPasses(const fg::FrameGraph& graph, const std::set<std::string>& disabled);

// Whether a world-space sphere reaches into the frustum of `viewProjection` (its six planes, after
// Gribb and Hartmann; conservative near the frustum's edges, never wrongly false).
bool sphereIntersectsFrustum(const glm::mat4& viewProjection, glm::vec3 center, float radius);
// How many of the frame's local lights (orbits applied at frame.time) reach into the view.
int localLightsInView(const FrameData& frame);

// The size the G-buffer and lighting run at: round(output x renderScale), at least 1 x 1
// (renderScale up to kMaxSsaaScale).
glm::ivec2 scaledRenderSize(int outputWidth, int outputHeight, float renderScale);
// Whether the frame is supersampled: --aa ssaa (the default) at --render-scale 1. A render scale
// below 1 asks for fewer pixels than the output, so it is kept and SSAA is not used; nor is it for
// --render-path pathtraced, whose samples are spread over each pixel.
bool supersampled(const RenderSettings& settings);
// The scale the G-buffer, lighting and post effects run at: --ssaa-scale when supersampled (the
// image is filtered down to the output), else --render-scale.
float internalRenderScale(const RenderSettings& settings);

// Whether the frame runs the taa pass (and so is jittered): --aa taa in a view of the lit image
// (final, lighting, the overlays and HDR views; not a G-buffer channel).
bool temporalAntiAliasing(const RenderSettings& settings);
// Every knob's value and the view, as text: TAA's history is reset when it changes.
std::string settingsSignature(const RenderSettings& settings);

// Camera matrices, planes and sizes for a frame of `scene` under `settings`.
FrameData makeFrameData(const Scene& scene, const RenderSettings& settings, float time);

}  // namespace lp

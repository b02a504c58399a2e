#include "frame/frame_builder.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/render/exposure.hpp"
#include "engine/core/error.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/ibl_lights.hpp"
#include "engine/render/local_lights.hpp"
#include "frame/knobs.hpp"

namespace lp {

bool sphereIntersectsFrustum(const glm::mat4& viewProjection, glm::vec3 center, float radius) {
    const glm::mat4 m = glm::transpose(viewProjection);  // rows of the matrix
    const glm::vec4 planes[6] = {m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[3] + m[2], m[3] - m[2]};
    for (const glm::vec4& p : planes) {
        const float len = glm::length(glm::vec3(p));
        if (len <= 0.0f) continue;
        if ((glm::dot(glm::vec3(p), center) + p.w) / len < -radius) return false;
    }
    return true;
}

int localLightsInView(const FrameData& frame) {
    const glm::mat4 viewProjection = frame.projection * frame.view;
    int visible = 0;
    for (const PointLight& l : *frameLocalLights(frame)) {
        const BoundingSphere b = localLightBounds(l);
        visible += (b.radius <= 0.0f || sphereIntersectsFrustum(viewProjection, b.center, b.radius)) ? 1 : 0;
    }
    return visible;
}

namespace {
// A view of one G-buffer channel (or the environment), not of the lit image.
bool isChannelView(DebugView view) {
    return view != DebugView::Final && view != DebugView::Lighting &&
           !isShadingTermView(view) &&  // the lit frame's terms (term-*, emissive)
           !isLocalLightView(view) &&  // overlays on the final image
           !isHdrView(view);           // the final HDR buffer inspected
}

// Why the frame needs no local-light pass (nor tiling, globes, overlays); empty when it does.
std::string localLightSkipReason(const FrameData& frame) {
    const LocalLightSettings& s = frame.settings->localLights;
    if (!s.enabled) return "local lights are off (--no-local-lights)";
    const int count = localLightCount(*frame.scene, s);
    if (count <= 0) return "scene has no local lights";
    if (localLightsInView(frame) == 0) return "all " + std::to_string(count) + " local lights are out of view";
    return "";
}

// Why the frame needs no ambient-occlusion pass; empty when it does. AO darkens indirect light only
// (IBL, the constant ambient), so without any there is nothing for it to do. The ao view shows it
// regardless; --all-passes adds it without indirect light, but not against --no-ao.
std::string ambientOcclusionSkipReason(const FrameData& frame, bool iblAdded) {
    const RenderSettings& s = *frame.settings;
    if (s.view == DebugView::Ao) return "";
    if (!s.ao.enabled) return "ambient occlusion is off (--no-ao)";
    if (s.allPasses) return "";
    const bool ambient = glm::any(glm::greaterThan(frameAmbient(frame), glm::vec3(0.0f)));
    if (!iblAdded && !ambient) return "no indirect light to occlude (IBL off, ambient 0)";
    return "";
}
// From the HDR frame to the displayed one: auto exposure, the tone map, FXAA, the HDR views. The
// same for every render path, so a path-traced frame compares with a raster one.
fg::ResourceId addDisplayPasses(fg::FrameGraph& graph, PassStates& passes, const FrameData& frame, fg::ResourceId hdr,
                                fg::ResourceId& exposure) {
    const RenderSettings& s = *frame.settings;
    const Scene& scene = *frame.scene;
    if (autoExposureOn(s, scene)) exposure = addAutoExposurePass(graph, passes.autoExposure, frame, hdr);
    else graph.skipPass("auto_exposure", s.autoExposure ? "manual exposure (--no-auto-exposure)"
                                                        : "the scene fixes its exposure (its \"exposure\" field)");
    // With FXAA after it, the tone map keeps its result in RGBA16F and FXAA does the one 8-bit
    // quantisation (and its dither).
    const bool fxaa = s.aa.method == AntiAliasing::Fxaa;
    fg::ResourceId display = addToneMapPass(graph, passes.tonemap, frame, hdr, exposure,
                                            fxaa ? ToneMapTarget::Float16 : ToneMapTarget::Display8);
    if (fxaa) display = addFxaaPass(graph, passes.fxaa, frame, display);
    else graph.skipPass("fxaa", "anti-aliasing is " + std::string(antiAliasingName(s.aa.method)) + ", not fxaa");
    if (isHdrView(s.view)) display = addHdrViewPass(graph, passes.hdrView, frame, hdr, exposure, s.view);  // culls tonemap
    return display;
}

// --render-path pathtraced: the path tracer makes the HDR frame; the raster passes are left out with
// the reason, and the display passes are the raster frame's.
FrameOutputs buildPathTracedFrame(fg::FrameGraph& graph, PassStates& passes, const FrameData& frame) {
    const RenderSettings& s = *frame.settings;
    if (isChannelView(s.view))
        throw Error("--render-path pathtraced: the '" + std::string(viewName(s.view)) +
                    "' view shows a G-buffer channel, which the path tracer does not make; use the final image or an "
                    "HDR view");
    if (s.view == DebugView::Lighting || isLocalLightView(s.view))
        throw Error("--render-path pathtraced: the '" + std::string(viewName(s.view)) + "' view shows the raster passes' light; use the final image or an HDR view");
    const std::string why = "pathtraced: the path tracer makes the HDR frame";
    for (const char* pass : {"ibl_bake", "gbuffer", "gbuffer_visibility", "gbuffer_resolve", "depth_prepass", "spot_shadows", "point_shadows",
                             "forward_opaque", "global_lights", "ibl", "local_lights", "emission", "sky", "transparent",
                             "motion_blur", "bloom", "bloom_composite", "toon", "taa", "ssaa_downsample"})
        graph.skipPass(pass, why);
    for (const char* name : ambientOcclusionPassNames()) graph.skipPass(name, why);
    fg::ResourceId hdr = addPathTracePass(graph, passes.pathTrace, frame);
    if (frame.width != frame.outputWidth || frame.height != frame.outputHeight)
        hdr = addUpscalePass(graph, passes.upscale, frame, hdr, UpscaleInput::Hdr);
    else graph.skipPass("upscale", "render scale 1: the frame is rendered at the output size");
    fg::ResourceId exposure;
    const fg::ResourceId display = addDisplayPasses(graph, passes, frame, hdr, exposure);
    for (const auto& name : s.disabledPasses) graph.disablePass(name);
    graph.markOutput(display);
    FrameOutputs out{display, {}};
    if (s.keepHdr) {
        graph.markOutput(hdr);
        out.hdr = hdr;
    }
    return out;
}
}  // namespace

FrameOutputs buildFrameGraph(fg::FrameGraph& graph, PassStates& passes, const FrameData& frameIn) {
    FrameData frame = frameIn;
    frame.environments = &passes.environments;
    if (frame.settings->renderPath == RenderPath::PathTraced) return buildPathTracedFrame(graph, passes, frame);
    // Animated models' vertices posed on the GPU, before every pass that draws them.
    const std::string skinningSkip = skinningSkipReason(frame);
    if (skinningSkip.empty()) {
        addSkinningPass(graph, passes.skinning, frame);
        frame.posedVerticesOnGpu = true;
    } else {
        graph.skipPass("skinning", skinningSkip);
    }
    const RenderSettings& s = *frame.settings;
    const Scene& scene = *frame.scene;
    const bool channelView = isChannelView(s.view);
    const bool lightingView = s.view == DebugView::Lighting;
    // The lighting view and the term views (term-diffuse, term-specular, emissive) show the opaque
    // surfaces' light alone: no sky, no transparent surfaces, no overlays.
    const bool termView = isShadingTermView(s.view);
    const bool lightAlone = lightingView || termView;
    const std::string lightAloneWhy = lightingView ? "the lighting view shows light alone"
                                                   : "the " + std::string(viewName(s.view)) + " view shows its term alone";
    const bool hasMap = !scene.environment.map.empty();
    const bool iblWanted = iblLightsFrame(scene, s);
    const bool iblAdded = iblWanted || s.allPasses;
    // A black background with no map: the global-light pass already leaves the background at zero.
    const bool skyWanted = hasMap || glm::any(glm::greaterThan(scene.environment.color * scene.environment.intensity, glm::vec3(0.0f)));
    const bool skyAdded = !lightAlone && (skyWanted || s.allPasses);
    const std::string localSkip = s.allPasses ? "" : localLightSkipReason(frame);
    const bool scaled = frame.width != frame.outputWidth || frame.height != frame.outputHeight;
    const bool supersampling = supersampled(s);

    // The environment's cubes are made (and, for IBL, baked) in the frame where they changed.
    const bool environmentView = isEnvironmentView(s.view);  // shows the cubes or the LUT themselves
    const bool bake = iblAdded || environmentView;
    // Imported whenever a pass that samples it is added (in a G-buffer view those passes are
    // culled, so nothing asks for the textures); baked only when a live pass will sample it.
    const bool environmentSampled = environmentView || iblAdded || (skyAdded && hasMap);
    EnvironmentTextures environment;
    if (environmentSampled) environment = importEnvironment(graph, frame, bake);
    if (environmentView || (!channelView && environmentSampled)) {
        if (!passes.environments.ready(scene, s.environment, s.specularMasking, bake)) environment = addIblBakePass(graph, frame, environment, bake);
        else graph.skipPass("ibl_bake", "environment unchanged since its bake (cached)");
    } else {
        graph.skipPass("ibl_bake", hasMap ? "nothing in this view samples the environment" : "scene has no environment map");
    }
    // Motion vectors only for a pass that reads them (the velocity view, motion blur, TAA).
    const std::string motionBlurSkip = motionBlurSkipReason(frame);
    const bool taa = temporalAntiAliasing(s);
    GBufferChannels channels = channelsForView(s.view);
    channels.velocity = channels.velocity || motionBlurSkip.empty() || taa;
    channels.fresnel = gbufferCarriesFresnel(frame);
    channels.clearcoat = gbufferCarriesClearcoat(frame);
    // The G-buffer: rasterised target by target, a visibility buffer resolved into the same targets,
    // or (forward+) a depth pre-pass that writes only what later passes read.
    const bool forwardPlus = s.renderPath == RenderPath::ForwardPlus;
    GBuffer gbuffer;
    if (forwardPlus) {
        gbuffer = addDepthPrepass(graph, passes.gbuffer, frame, channels);
        graph.skipPass("gbuffer", "forward+: the depth pre-pass writes depth (and what later passes read)");
        graph.skipPass("gbuffer_visibility", "forward+: the depth pre-pass replaces the G-buffer");
        graph.skipPass("gbuffer_resolve", "forward+: the depth pre-pass replaces the G-buffer");
    } else {
        const GBufferModeChoice mode = chooseGBufferMode(
            s.gbuffer.mode, frame.softwareRaster, visibilityBufferUnsupported(*frame.scene, frame.maxStorageBlockBytes));
        graph.skipPass("depth_prepass", "render path deferred (--render-path forward+ uses a depth pre-pass)");
        if (mode.mode == GBufferMode::Visibility) {
            graph.skipPass("gbuffer", mode.why + ": gbuffer_visibility and gbuffer_resolve make the G-buffer");
            const VisibilityBuffer visibility = addVisibilityPass(graph, passes.visibility, frame);
            gbuffer = addVisibilityResolvePass(graph, passes.visibilityResolve, frame, visibility, channels);
        } else {
            gbuffer = addGBufferPass(graph, passes.gbuffer, frame, channels);
            graph.skipPass("gbuffer_visibility", mode.why);
            graph.skipPass("gbuffer_resolve", mode.why);
        }
        // --explain: whether the G-buffer carries KHR_materials_clearcoat's layer, and why not.
        const std::string coat = gbufferClearcoatNote(frame);
        for (const char* pass : {"gbuffer", "gbuffer_resolve"}) graph.notePass(pass, coat);
    }
    // one depth pass per shadow-casting directional light; global_lights and the shadowmap view read them.
    if (const std::string why = sunShadowSkipReason(frame); !why.empty()) graph.skipPass("shadow_map", why);
    const ShadowMaps shadowMaps = addShadowMapPasses(graph, passes.shadowMaps, frame);
    for (const LightShadowMap& map : shadowMaps)
        if (!map.droppedCascades.empty())
            graph.skipPass("shadow_map_" + std::to_string(map.light) + " cascades", map.droppedCascades);
    // Occlusion of the indirect light (ambient, IBL); the light passes read it, the ao view shows it.
    const std::string aoSkip = ambientOcclusionSkipReason(frame, iblAdded);
    fg::ResourceId ao;
    if (aoSkip.empty()) {
        ao = addAmbientOcclusionPasses(graph, passes.ambientOcclusion, frame, gbuffer);
    } else {
        for (const char* name : ambientOcclusionPassNames()) graph.skipPass(name, aoSkip);
    }
    // What lights forward-shaded surfaces: forward+'s opaque pass and the transparent pass.
    ForwardLighting forwardLighting;
    forwardLighting.shadowMaps = shadowMaps;
    if (iblAdded) forwardLighting.environment = environment;
    forwardLighting.lightingOnly = lightingView;
    // One perspective depth map per shadow-casting spot and a cube of six per shadow-casting point
    // light, read by local_lights and the forward passes.
    LocalShadowMaps localShadows;
    LocalLightRecords lightRecords;  // uploaded once a frame by the first pass that shades the lights
    if (localSkip.empty()) {
        if (const std::string why = spotShadowSkipReason(frame); !why.empty()) graph.skipPass("spot_shadows", why);
        if (const std::string why = pointShadowSkipReason(frame); !why.empty()) graph.skipPass("point_shadows", why);
        localShadows.spot = addSpotShadowPass(graph, passes.spotShadows, frame);
        localShadows.point = addPointShadowPass(graph, passes.pointShadows, frame);  // lets a kept atlas go if asked
        lightRecords = importLocalLightRecords(graph, passes.localLights, frame, localShadows);
        forwardLighting.localLights = true;
        forwardLighting.localShadows = localShadows;
        forwardLighting.lightRecords = lightRecords;
    } else {
        graph.skipPass("spot_shadows", localSkip);
        graph.skipPass("point_shadows", localSkip);
    }
    fg::ResourceId hdr;
    if (forwardPlus) {
        ForwardLighting opaque = forwardLighting;
        opaque.ao = ao;
        opaque.fillsLightRecords = true;
        hdr = addForwardOpaquePass(graph, passes.forward, passes.localLights, frame, gbuffer, opaque);
        const std::string why = "forward+: forward_opaque shades the opaque surfaces";
        for (const char* pass : {"global_lights", "ibl", "local_lights", "emission"}) graph.skipPass(pass, why);
    } else {
        graph.skipPass("forward_opaque", "render path deferred (--render-path forward+)");
        hdr = addGlobalLightPass(graph, passes.globalLights, frame, gbuffer, shadowMaps, lightingView, ao);
        if (iblAdded) hdr = addIblPass(graph, passes.ibl, frame, gbuffer, environment, hdr, lightingView, ao);
        else graph.skipPass("ibl", hasMap ? "IBL is off (environment.ibl false, no --ibl)" : "scene has no environment map");
        if (localSkip.empty())
            hdr = addLocalLightPass(graph, passes.localLights, frame, gbuffer, hdr, lightingView, localShadows, lightRecords);
        else graph.skipPass("local_lights", localSkip);
        const bool emissionHidden = lightingView || (hiddenShadingTerms(s.view) & kHideEmission) != 0;
        if (!emissionHidden && sceneHasEmission(frame)) hdr = addEmissionPass(graph, passes.emission, frame, gbuffer, hdr);
        else graph.skipPass("emission", emissionHidden ? lightAloneWhy : "no material of the scene emits");
    }
    if (skyAdded) hdr = addSkyPass(graph, passes.sky, frame, gbuffer.depth, hasMap ? environment.cube : fg::ResourceId{}, hdr);
    else graph.skipPass("sky", lightAlone ? lightAloneWhy : "scene has no environment (black, no map)");
    // Alpha-blended and transmissive surfaces over the opaque frame and the sky, back to front; the
    // transmissive ones refract a copy of that frame.
    const char* noTransmission = "no material of the scene is transmissive (KHR_materials_transmission, MTL illum 4/6/7)";
    if (lightAlone) {
        graph.skipPass("transmission_background", lightAloneWhy + " (the opaque surfaces')");
        graph.skipPass("transparent", lightAloneWhy + " (the opaque surfaces')");
    } else if (!sceneHasTransparency(scene)) {
        graph.skipPass("transmission_background", noTransmission);
        graph.skipPass("transparent", "no material of the scene is alpha-blended or transmissive");
    } else {
        fg::ResourceId background;
        if (sceneHasTransmission(scene)) background = addTransmissionBackgroundPass(graph, frame, hdr);
        else graph.skipPass("transmission_background", noTransmission);
        hdr = addTransparentPass(graph, passes.transparent, passes.localLights, frame, gbuffer.depth, hdr, forwardLighting,
                                 background);
    }
    // globes and the light-ranges / lights-per-tile / lights-per-cluster overlays, over the sky too.
    if (!lightAlone && localSkip.empty() && localLightCount(scene, s.localLights) > 0)
        hdr = addLocalLightOverlayPasses(graph, passes.localLights, frame, gbuffer, hdr, lightRecords);
    // Motion blur on the HDR buffer, before bloom and the tone map.
    if (motionBlurSkip.empty()) hdr = addMotionBlurPasses(graph, passes.motionBlur, frame, gbuffer, hdr);
    else graph.skipPass("motion_blur", motionBlurSkip);
    const PostResult post = addPostPasses(graph, passes.post, frame, gbuffer, hdr);  // bloom, toon (not in the lighting view)
    for (const auto& [pass, why] : post.skipped) graph.skipPass(pass, why);
    hdr = post.hdr;
    if (scaled && !supersampling) hdr = addUpscalePass(graph, passes.upscale, frame, hdr, UpscaleInput::Hdr);
    else graph.skipPass("upscale", supersampling ? "--aa ssaa: the frame is rendered above the output size"
                                                : "render scale 1: the frame is rendered at the output size");
    if (supersampling) hdr = addDownsamplePass(graph, passes.downsample, frame, hdr, s.aa.ssaaScale);
    else graph.skipPass("ssaa_downsample", s.aa.method == AntiAliasing::Ssaa
                                               ? "--render-scale below 1: the frame is rendered below the output size"
                                               : "anti-aliasing is " + std::string(antiAliasingName(s.aa.method)) + ", not ssaa");
    if (taa) hdr = addTaaPass(graph, passes.taa, frame, hdr, gbuffer.velocity, settingsSignature(s));
    else graph.skipPass("taa", s.aa.method == AntiAliasing::Taa ? "a G-buffer view is not anti-aliased"
                                                                : "anti-aliasing is " + std::string(antiAliasingName(s.aa.method)) + ", not taa");
    fg::ResourceId exposure;
    fg::ResourceId display = addDisplayPasses(graph, passes, frame, hdr, exposure);
    if (channelView) {
        display = addDebugViewPass(graph, passes.debugView, frame, gbuffer, shadowMaps, environment, s.view, ao);
        if (scaled) display = addUpscalePass(graph, passes.upscale, frame, display, UpscaleInput::DebugView);
    }

    for (const auto& name : s.disabledPasses) graph.disablePass(name);
    graph.markOutput(display);
    FrameOutputs out{display, {}};
    if (s.keepHdr && !channelView) {
        graph.markOutput(hdr);
        out.hdr = hdr;
    }
    return out;
}

void checkDisabledPasses(const fg::FrameGraph& graph, const std::set<std::string>& disabled) {
    // Pass names have no spaces; a decision named with one is a note on a pass (the cascades a shadow
    // map dropped: "shadow_map_0 cascades"), not a pass that can be disabled.
    std::vector<fg::PassDecision> candidates = graph.explain();
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                    [](const fg::PassDecision& d) { return d.name.find(' ') != std::string::npos; }),
                     candidates.end());
    for (const std::string& name : disabled) {
        auto named = [&](const fg::PassDecision& d) { return d.name == name; };
        if (std::any_of(candidates.begin(), candidates.end(), named)) continue;
        std::string list;
        for (const fg::PassDecision& d : candidates) list += (list.empty() ? "" : ", ") + d.name;
        throw Error("--disable-pass " + name + ": no such pass in this frame (" + list + ")");
    }
}

glm::ivec2 scaledRenderSize(int outputWidth, int outputHeight, float renderScale) {
    const float scale = std::isfinite(renderScale) ? std::clamp(renderScale, 0.0f, float(kMaxSsaaScale)) : 1.0f;
    return {std::max(1, int(std::lround(double(outputWidth) * scale))),
            std::max(1, int(std::lround(double(outputHeight) * scale)))};
}

bool temporalAntiAliasing(const RenderSettings& settings) {
    return settings.aa.method == AntiAliasing::Taa && !isChannelView(settings.view) &&
           settings.renderPath != RenderPath::PathTraced;
}

std::string settingsSignature(const RenderSettings& settings) {
    std::string text = std::string(viewName(settings.view)) + " " + std::to_string(settings.width) + "x" +
                       std::to_string(settings.height);
    for (const KnobEntry& k : knobTable()) text += " " + k.name + "=" + formatKnobValue(k, k.field.get(settings));
    for (const std::string& pass : settings.disabledPasses) text += " -" + pass;
    return text;
}

bool supersampled(const RenderSettings& settings) {
    return settings.aa.method == AntiAliasing::Ssaa && settings.renderScale >= 1.0f &&
           settings.renderPath != RenderPath::PathTraced;  // its samples are spread over each pixel
}

float internalRenderScale(const RenderSettings& settings) {
    return supersampled(settings) ? float(settings.aa.ssaaScale) : settings.renderScale;
}

FrameData makeFrameData(const Scene& scene, const RenderSettings& settings, float time) {
    FrameData f;
    const glm::ivec2 size = scaledRenderSize(settings.width, settings.height, internalRenderScale(settings));
    f.width = size.x;
    f.height = size.y;
    f.outputWidth = settings.width;
    f.outputHeight = settings.height;
    const Camera camera = scene.cameraAt(time);  // the camera path's, when the scene has one
    f.view = camera.view();
    f.unjitteredProjection = camera.projection(float(settings.width) / float(std::max(settings.height, 1)));
    f.projection = f.unjitteredProjection;
    f.previousViewProjection = f.unjitteredProjection * f.view;
    f.nearPlane = camera.nearPlane;
    f.farPlane = camera.farPlane;
    f.time = time;
    f.previousTime = time;
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    f.sceneExtent = std::max(glm::length(0.5f * (lo + hi) - camera.position) + 0.5f * glm::length(hi - lo), 1e-3f);
    f.scene = &scene;
    f.settings = &settings;
    f.localLights = std::make_shared<const std::vector<PointLight>>(localLightsForFrame(scene, settings.localLights, time));
    return f;
}

void noteEnvironmentLights(fg::FrameGraph& graph, const Scene& scene, const RenderSettings& settings) {
    const Environment& e = scene.environment;
    if (!iblLightsFrame(scene, settings)) return;
    ImageF map = loadHdrImage(e.map);
    const LightExtraction extraction = extractEnvironmentLights(map, e.rotationDegrees, settings.environment.extractLights,
                                                                settings.environment.extractThreshold);
    for (const std::string& line : describeExtraction(extraction, settings.environment.extractLights))
        graph.notePass("ibl", "extracted from the map: " + line);
}

}  // namespace lp

#pragma once
// Transparent surfaces (glTF alphaMode BLEND, MTL d < 1): "transparent" draws them after the opaque
// frame and the sky, in either render path, forward-shaded by shaders/forward.frag
// (LP_FORWARD_TRANSPARENT) with the opaque pass's lighting (suns and shadows, ambient and IBL, the
// clustered local lights, emission; no screen-space AO, which belongs to the surface behind), and
// blended "over" with premultiplied alpha: hdr = c a + hdr (1 - a). Depth is tested against the
// opaque depth and not written; the draws are sorted back to front by the view depth of each draw's
// bounding-box centre (sortTransparentDraws), so overlapping objects composite in order.
//
// Transmissive materials (KHR_materials_transmission / _volume, MTL illum 4/6/7) are drawn here too:
// "transmission_background" first copies the opaque frame (after the sky) into a mip-mapped texture,
// which forward.frag (LP_FORWARD_TRANSMISSION) reads along each fragment's refracted ray, at a level
// from its roughness. It is added only when some material transmits.
#include <vector>

#include "passes/forward_pass.hpp"

namespace lp {

struct TransparentPass {
    ForwardPass forward;  // forward.frag compiled with LP_FORWARD_TRANSPARENT
    int drawn = 0;        // draws the last execute blended, for tests
};

// Whether any material of the scene is alpha-blended or transmissive (the transparent pass is added
// only then).
bool sceneHasTransparency(const Scene& scene);
// Whether any material of the scene is transmissive (Material::transmissive): the background copy is
// added only then.
bool sceneHasTransmission(const Scene& scene);

// Texture unit of the background copy in forward.frag (LP_TRANSMISSION_BACKGROUND_UNIT), then the
// transmission and thickness maps: above every unit the forward programs bind otherwise.
constexpr unsigned kTransmissionBackgroundUnit = 23, kTransmissionMapUnit = 24, kThicknessMapUnit = 25;

// The levels of a full mip chain of a width x height texture (1 for 1 x 1).
int fullMipLevels(int width, int height);

// Adds "transmission_background": copies `hdr` (the opaque frame with the sky) into
// "transmission.background", level 0, and fills its mip chain. Returns the copy.
fg::ResourceId addTransmissionBackgroundPass(fg::FrameGraph& graph, const FrameData& frame, fg::ResourceId hdr);

struct TransparentDraw {
    int mesh = 0, draw = 0;  // into SceneGpu::meshes[mesh].draws[draw]
    float viewDepth = 0.0f;  // distance along the view axis of the draw's centre
};
// The blended draws of `gpu`, farthest first (ties keep scene order).
std::vector<TransparentDraw> sortTransparentDraws(const SceneGpu& gpu, const glm::mat4& view);

// Adds "transparent": blends into `hdr` (a new version), depth-testing against `depth`; with a valid
// `transmissionBackground` (addTransmissionBackgroundPass) its transmissive materials refract it.
fg::ResourceId addTransparentPass(fg::FrameGraph& graph, TransparentPass& state, LocalLightPass& localLights,
                                  const FrameData& frame, fg::ResourceId depth, fg::ResourceId hdr,
                                  const ForwardLighting& lighting, fg::ResourceId transmissionBackground = {});

}  // namespace lp

#pragma once
// Transparent surfaces (glTF alphaMode BLEND, MTL d < 1): "transparent" draws them after the opaque
// frame and the sky, in either render path, forward-shaded by shaders/forward.frag
// (LP_FORWARD_TRANSPARENT) with the opaque pass's lighting (suns and shadows, ambient and IBL, the
// clustered local lights, emission; no screen-space AO, which belongs to the surface behind), and
// blended "over" with premultiplied alpha: hdr = c a + hdr (1 - a). Depth is tested against the
// opaque depth and not written; the draws are sorted back to front by the view depth of each draw's
// bounding-box centre (sortTransparentDraws), so overlapping objects composite in order.
#include <vector>

#include "passes/forward_pass.hpp"

namespace lp {

struct TransparentPass {
    ForwardPass forward;  // forward.frag compiled with LP_FORWARD_TRANSPARENT
    int drawn = 0;        // draws the last execute blended, for tests
};

// Whether any material of the scene is alpha-blended (the transparent pass is added only then).
bool sceneHasTransparency(const Scene& scene);

struct TransparentDraw {
    int mesh = 0, draw = 0;  // into SceneGpu::meshes[mesh].draws[draw]
    float viewDepth = 0.0f;  // distance along the view axis of the draw's centre
};
// The blended draws of `gpu`, farthest first (ties keep scene order).
std::vector<TransparentDraw> sortTransparentDraws(const SceneGpu& gpu, const glm::mat4& view);

// Adds "transparent": blends into `hdr` (a new version), depth-testing against `depth`.
fg::ResourceId addTransparentPass(fg::FrameGraph& graph, TransparentPass& state, LocalLightPass& localLights,
                                  const FrameData& frame, fg::ResourceId depth, fg::ResourceId hdr,
                                  const ForwardLighting& lighting);

}  // namespace lp

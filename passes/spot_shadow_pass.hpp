#pragma once
// "spot_shadows": one depth-only raster pass drawing a perspective shadow map for every local spot
// light with castsShadow (up to kMaxSpotShadows, the first ones), as square tiles of one D32F atlas
// "spot_shadows.depth". The local-light pass reads it and filters it like the suns' maps (PCF,
// settings.shadows.filter). No shadow-casting spot in the frame, or shadows off: no pass. Opaque
// casters are drawn plainly; MASK and BLEND ones test their alpha (alphaProgram, as the suns').
#include <vector>

#include <glm/glm.hpp>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

constexpr int kMaxSpotShadows = 16;

struct SpotShadowPass {
    gl::Program program;       // opaque casters: no texture fetch, no discard
    gl::Program alphaProgram;  // MASK and BLEND casters (LP_SHADOW_ALPHA_TEST), made when the scene has some
    gl::Framebuffer fbo;
};

struct SpotShadowMaps {
    fg::ResourceId depth;                  // the atlas; invalid when no spot casts a shadow this frame
    std::vector<int> light;                // per tile: the index into localLightsForFrame's lights
    std::vector<glm::mat4> worldToClip;    // per tile: the spot's perspective projection x view
    std::vector<float> nearPlane, farPlane;  // per tile: its depth range (metres along the axis)
    std::vector<float> texelSlope;         // per tile: a texel's world size per metre of distance
    int columns = 1;
    int tileSize = 0;
    bool any() const { return !light.empty(); }
};

// Why the frame has no spot_shadows pass ("": it has one); the frame builder records it.
std::string spotShadowSkipReason(const FrameData& frame);
SpotShadowMaps addSpotShadowPass(fg::FrameGraph& graph, SpotShadowPass& state, const FrameData& frame);

}  // namespace lp

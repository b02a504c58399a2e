#pragma once
// The post effects of a frame, between the light passes and the tone map: bloom, then toon
// (DESIGN.md's order), each only when the scene's effects or the user's flags enable it.
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/bloom_pass.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/post_backend.hpp"
#include "passes/toon_pass.hpp"

namespace lp {

struct PostPasses {
    PostBackend backend;
    BloomPass bloom;
    ToonPass toon;
};

struct PostResult {
    // The HDR buffer for the tone map: hdr after bloom and toon, or the bloom buffer alone when
    // settings.post.bloomOnly (the bloom view).
    fg::ResourceId hdr;
    // The post passes not added and why (bloom, toon, bloom_composite): the frame builder records them.
    std::vector<std::pair<std::string, std::string>> skipped;
};

// Called for every frame (it counts frames for the CUDA registrations); adds nothing in the lighting view.
PostResult addPostPasses(fg::FrameGraph& graph, PostPasses& state, const FrameData& frame, const GBuffer& gbuffer,
                         fg::ResourceId hdr);

// Per effect, whether it runs in CUDA this frame: decided before the passes are added, so the graph
// knows each pass's kind and what it touches. `auto` measures both backends at this size and kernel
// the first time (or reads the cache; see PostBackend::autoChoice).
PostBackendChoice postBackendChoice(PostPasses& state, const FrameData& frame, const post::PostConfig& config);
// The cache key of a measurement on this GL context (GPU, driver, size, kernel, method, interop).
post::TimingKey postTimingKey(const FrameData& frame, const post::PostConfig& config, const std::string& interop);

}  // namespace lp

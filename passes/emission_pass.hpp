#pragma once
// Emission (MTL Ke, glTF emissiveFactor x emissiveTexture x KHR_materials_emissive_strength): the
// emissive materials' triangles drawn again over the G-buffer's depth (GL_EQUAL, no depth writes),
// adding their radiance to the HDR buffer, so bloom and exposure see it like any light. Only
// emissive materials are drawn; alpha MASK texels the G-buffer discarded are discarded here too.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/gbuffer_pass.hpp"

namespace lp {

struct EmissionPass {
    gl::Program program;
    GBufferProgramKey layout;  // the depth convention `program` and the depth test were set up for
    gl::Framebuffer fbo;
};

// Whether any material of the frame's scene emits (the frame builder adds the pass only then).
bool sceneHasEmission(const FrameData& frame);

// Adds the "emission" pass: hdr += emission where the emissive surfaces are the visible ones.
fg::ResourceId addEmissionPass(fg::FrameGraph& graph, EmissionPass& state, const FrameData& frame, const GBuffer& gbuffer,
                               fg::ResourceId hdr);

}  // namespace lp

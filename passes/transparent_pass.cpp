#include "passes/transparent_pass.hpp"

#include <algorithm>


#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "passes/skinning_pass.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId depth;
    ForwardLightingReads reads;
    fg::ResourceId hdr;
    fg::ResourceId background;  // the transmission background copy (invalid: no transmission)
};
struct CopyData {
    fg::ResourceId hdr, background;
};

// forward.frag's LP_FORWARD_TRANSMISSION uniforms, looked up once per execute.
struct TransmissionUniforms {
    explicit TransmissionUniforms(const gl::Uniforms& u)
        : transmission(u.location("uTransmission")), hasTransmissionMap(u.location("uHasTransmissionMap")),
          thickness(u.location("uThickness")), hasThicknessMap(u.location("uHasThicknessMap")), ior(u.location("uIor")),
          attenuationColor(u.location("uAttenuationColor")), attenuationDistance(u.location("uAttenuationDistance")) {}
    void set(GLuint prog, const GpuMaterial& m) const {
        const bool on = m.transmissive();
        glProgramUniform1f(prog, transmission, on ? m.transmission : 0.0f);
        glProgramUniform1i(prog, hasTransmissionMap, on && m.transmissionMap != 0);
        glProgramUniform1f(prog, thickness, on ? std::max(m.thickness, 0.0f) : 0.0f);
        glProgramUniform1i(prog, hasThicknessMap, on && m.thicknessMap != 0);
        glProgramUniform1f(prog, ior, m.ior);
        glProgramUniform3f(prog, attenuationColor, m.attenuationColor.x, m.attenuationColor.y, m.attenuationColor.z);
        glProgramUniform1f(prog, attenuationDistance, m.attenuationDistance);
        glBindTextureUnit(kTransmissionMapUnit, on ? m.transmissionMap : 0);
        glBindTextureUnit(kThicknessMapUnit, on ? m.thicknessMap : 0);
    }
    GLint transmission, hasTransmissionMap, thickness, hasThicknessMap, ior, attenuationColor, attenuationDistance;
};
}  // namespace

bool sceneHasTransparency(const Scene& scene) {
    for (const ModelInstance& model : scene.models)
        for (const Material& m : model.mesh.materials)
            if (m.alphaMode == AlphaMode::Blend || m.transmissive()) return true;
    return false;
}

bool sceneHasTransmission(const Scene& scene) {
    for (const ModelInstance& model : scene.models)
        for (const Material& m : model.mesh.materials)
            if (m.transmissive()) return true;
    return false;
}

int fullMipLevels(int width, int height) {
    int levels = 1;
    for (int size = std::max(width, height); size > 1; size /= 2) ++levels;
    return levels;
}

fg::ResourceId addTransmissionBackgroundPass(fg::FrameGraph& graph, const FrameData& frame, fg::ResourceId hdr) {
    const CopyData& d = graph.addPass<CopyData>(
        "transmission_background", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, CopyData& data) {
            data.hdr = b.read(hdr, fg::Usage::Transfer);
            data.background = b.create("transmission.background",
                                       {frame.width, frame.height, GL_RGBA16F, fullMipLevels(frame.width, frame.height)},
                                       fg::Usage::Transfer);
        },
        [frame](const CopyData& data, const fg::PassResources& res) {
            const GLuint background = res.texture(data.background);
            glCopyImageSubData(res.texture(data.hdr), GL_TEXTURE_2D, 0, 0, 0, 0, background, GL_TEXTURE_2D, 0, 0, 0, 0,
                               frame.width, frame.height, 1);
            glGenerateTextureMipmap(background);
        });
    return d.background;
}

std::vector<TransparentDraw> sortTransparentDraws(const SceneGpu& gpu, const glm::mat4& view) {
    std::vector<TransparentDraw> draws;
    for (size_t i = 0; i < gpu.meshes.size(); ++i) {
        const GpuMesh& mesh = gpu.meshes[i];
        for (size_t j = 0; j < mesh.draws.size(); ++j) {
            if (!gpu.materials[size_t(mesh.draws[j].material)].alphaBlend) continue;
            const glm::vec4 eye = view * mesh.model * glm::vec4(mesh.draws[j].centre, 1.0f);
            draws.push_back({int(i), int(j), -eye.z});
        }
    }
    std::stable_sort(draws.begin(), draws.end(),
                     [](const TransparentDraw& a, const TransparentDraw& b) { return a.viewDepth > b.viewDepth; });
    return draws;
}

fg::ResourceId addTransparentPass(fg::FrameGraph& graph, TransparentPass& state, LocalLightPass& localLights,
                                  const FrameData& frame, fg::ResourceId depth, fg::ResourceId hdr,
                                  const ForwardLighting& lighting, fg::ResourceId transmissionBackground) {
    ForwardLighting withoutAo = lighting;
    withoutAo.ao = {};
    const Data& d = graph.addPass<Data>(
        "transparent", fg::PassKind::Raster,
        [&](fg::PassBuilder& b, Data& data) {
            data.depth = b.read(depth, fg::Usage::DepthTest);
            data.reads = declareForwardLighting(b, localLights, withoutAo);
            data.hdr = b.write(hdr, fg::Usage::Blend);
            if (transmissionBackground.valid()) data.background = b.read(transmissionBackground, fg::Usage::Sampled);
            readPosedVertices(b, frame);
        },
        [&state, &localLights, frame, withoutAo](const Data& data, const fg::PassResources& res) {
            ForwardPass& forward = state.forward;
            if (!forward.fbo) forward.fbo = gl::makeFramebuffer("transparent");
            const GLuint fbo = forward.fbo.id();
            glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, res.texture(data.hdr), 0);
            glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, res.texture(data.depth), 0);
            glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);
            const bool transmission = data.background.valid();
            std::vector<std::string> defines = {"LP_FORWARD_TRANSPARENT"};
            if (transmission) defines.push_back("LP_FORWARD_TRANSMISSION");
            if (forward.transmissionVariant != transmission) forward.program = {};  // compiled again with the define
            forward.transmissionVariant = transmission;
            bindForwardLighting(forward, localLights, frame, withoutAo, data.reads, res, defines);
            const GLuint prog = forward.program.id();
            const std::vector<TransparentDraw> order = sortTransparentDraws(*frame.gpu, frame.view);
            {
                gl::ScopedFramebuffer bind(fbo, frame.width, frame.height);
                gl::ScopedEnable depthTest(GL_DEPTH_TEST, true);
                gl::ScopedEnable cull(GL_CULL_FACE, false);  // two-sided unless the material says not
                gl::ScopedEnable blend(GL_BLEND, true);
                gl::ScopedEnable seamless(GL_TEXTURE_CUBE_MAP_SEAMLESS, true);
                gl::ScopedRasterState saved;
                setGBufferDepthTest(frame.settings->gbuffer);  // LESS, or GREATER for reversed-Z
                glDepthMask(GL_FALSE);
                // Premultiplied "over" on colour; the HDR alpha (1 on surfaces) is kept.
                glBlendEquation(GL_FUNC_ADD);
                glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
                glUseProgram(prog);
                const gl::Uniforms uniforms(frame.shaders, prog);
                const ForwardMaterialUniforms material(uniforms);
                const TransmissionUniforms transmissive(uniforms);
                if (transmission) glBindTextureUnit(kTransmissionBackgroundUnit, res.texture(data.background));
                for (const TransparentDraw& t : order) {
                    const GpuMesh& mesh = frame.gpu->meshes[size_t(t.mesh)];
                    const GpuDraw& dr = mesh.draws[size_t(t.draw)];
                    material.setModel(prog, frame.view, mesh.model);
                    material.set(prog, frame.gpu->materials[size_t(dr.material)]);
                    if (transmission) transmissive.set(prog, frame.gpu->materials[size_t(dr.material)]);
                    glBindVertexArray(mesh.vao.id());
                    glDrawElements(GL_TRIANGLES, GLsizei(dr.indexCount), GL_UNSIGNED_INT,
                                   reinterpret_cast<const void*>(size_t(dr.firstIndex) * sizeof(uint32_t)));
                }
                state.drawn = int(order.size());
                if (transmission)
                    for (GLuint unit : {kTransmissionBackgroundUnit, kTransmissionMapUnit, kThicknessMapUnit}) glBindTextureUnit(unit, 0);
                glBindVertexArray(0);
                glUseProgram(0);
            }
            finishForwardDraws(fbo);
        });
    return d.hdr;
}

}  // namespace lp

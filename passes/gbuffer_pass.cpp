#include "passes/gbuffer_pass.hpp"

#include <algorithm>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"
#include "engine/render/scene_gpu.hpp"
#include "passes/skinning_pass.hpp"

namespace lp {

GLenum gbufferNormalFormat(GBufferNormalFormat format) {
    switch (format) {
        case GBufferNormalFormat::Unpacked: return GL_RGBA32F;
        case GBufferNormalFormat::SeedPacked:
        case GBufferNormalFormat::SeedPackedSigned: return GL_RGBA16F;
        case GBufferNormalFormat::TwoAngle: return GL_RG32F;
        case GBufferNormalFormat::Oct16: return GL_R16UI;
        case GBufferNormalFormat::Oct24:
        case GBufferNormalFormat::Oct32: return GL_R32UI;
    }
    return GL_RGBA32F;
}

GLenum gbufferSpecularFormat(GBufferNormalFormat format) {
    return shininessInNormalTarget(format) ? GL_SRGB8_ALPHA8 : GL_RGBA16F;
}

MaterialUniforms::MaterialUniforms(const gl::Uniforms& u) {
    auto loc = [&u](const char* name) { return u.location(name); };
    kd = loc("uDiffuse"); opacity = loc("uOpacity"); ks = loc("uSpecular"); metallic = loc("uMetallic");
    shininess = loc("uShininess"); roughness = loc("uRoughness"); hasDiffuse = loc("uHasDiffuseMap");
    hasBump = loc("uHasBumpMap"); bumpScale = loc("uBumpScale"); hasNormal = loc("uHasNormalMap");
    normalScale = loc("uNormalScale"); hasMetalRough = loc("uHasMetalRoughMap"); hasOcclusion = loc("uHasOcclusionMap");
    occlusionStrength = loc("uOcclusionStrength"); mask = loc("uAlphaMask"); cutoff = loc("uAlphaCutoff");
    twoSided = loc("uDoubleSided"); flat = loc("uFlat"); secondUvMaps = loc("uSecondUvMaps");
    specularF90 = loc("uSpecularF90"); specularF90Given = loc("uSpecularF90Given");
    hasSpecularMap = loc("uHasSpecularMap"); hasSpecularColorMap = loc("uHasSpecularColorMap");
    clearcoat = loc("uClearcoat"); clearcoatRoughness = loc("uClearcoatRoughness");
    clearcoatNormalScale = loc("uClearcoatNormalScale"); hasClearcoatMap = loc("uHasClearcoatMap");
    hasClearcoatRoughnessMap = loc("uHasClearcoatRoughnessMap"); hasClearcoatNormalMap = loc("uHasClearcoatNormalMap");
}

void MaterialUniforms::set(GLuint prog, const GpuMaterial& m) const {
    glProgramUniform3fv(prog, kd, 1, glm::value_ptr(m.diffuse));
    glProgramUniform1f(prog, opacity, m.opacity);
    glProgramUniform3fv(prog, ks, 1, glm::value_ptr(m.specular));
    glProgramUniform1f(prog, metallic, m.metallic);
    glProgramUniform1f(prog, shininess, m.shininess);
    glProgramUniform1f(prog, roughness, m.roughness);
    glProgramUniform1i(prog, hasDiffuse, m.diffuseMap != 0);
    glProgramUniform1i(prog, hasBump, m.bumpMap != 0);
    glProgramUniform1f(prog, bumpScale, m.bumpScale);
    glProgramUniform1i(prog, hasNormal, m.normalMap != 0);
    glProgramUniform1f(prog, normalScale, m.normalScale);
    glProgramUniform1i(prog, hasMetalRough, m.metallicRoughnessMap != 0);
    glProgramUniform1i(prog, hasOcclusion, m.occlusionMap != 0);
    glProgramUniform1f(prog, occlusionStrength, m.occlusionStrength);
    glProgramUniform1i(prog, mask, m.alphaMask);
    glProgramUniform1f(prog, cutoff, m.alphaCutoff);
    glProgramUniform1i(prog, twoSided, m.doubleSided);
    glProgramUniform1i(prog, flat, m.flat);
    glProgramUniform1ui(prog, secondUvMaps, m.secondUvMaps);
    glProgramUniform1f(prog, specularF90, m.dielectricF90.value_or(1.0f));
    glProgramUniform1i(prog, specularF90Given, m.dielectricF90.has_value());
    glProgramUniform1i(prog, hasSpecularMap, m.specularMap != 0);
    glProgramUniform1i(prog, hasSpecularColorMap, m.specularColorMap != 0);
    glBindTextureUnit(0, m.diffuseMap);
    glBindTextureUnit(1, m.bumpMap);
    glBindTextureUnit(2, m.normalMap);
    glBindTextureUnit(3, m.metallicRoughnessMap);
    glBindTextureUnit(4, m.occlusionMap);
    glBindTextureUnit(kMaterialSpecularUnit, m.specularMap);
    glBindTextureUnit(kMaterialSpecularColorUnit, m.specularColorMap);
    glProgramUniform1f(prog, clearcoat, m.clearcoat);
    glProgramUniform1f(prog, clearcoatRoughness, m.clearcoatRoughness);
    glProgramUniform1f(prog, clearcoatNormalScale, m.clearcoatNormalScale);
    glProgramUniform1i(prog, hasClearcoatMap, m.clearcoatMap != 0);
    glProgramUniform1i(prog, hasClearcoatRoughnessMap, m.clearcoatRoughnessMap != 0);
    glProgramUniform1i(prog, hasClearcoatNormalMap, m.clearcoatNormalMap != 0);
    glBindTextureUnit(kMaterialClearcoatUnit, m.clearcoatMap);
    glBindTextureUnit(kMaterialClearcoatRoughnessUnit, m.clearcoatRoughnessMap);
    glBindTextureUnit(kMaterialClearcoatNormalUnit, m.clearcoatNormalMap);
}

void unbindMaterialTextures() {
    for (GLuint u = 0; u < 5; ++u) glBindTextureUnit(u, 0);
    glBindTextureUnit(kMaterialSpecularUnit, 0);
    glBindTextureUnit(kMaterialSpecularColorUnit, 0);
    for (GLuint u : {kMaterialClearcoatUnit, kMaterialClearcoatRoughnessUnit, kMaterialClearcoatNormalUnit})
        glBindTextureUnit(u, 0);
}

glm::mat4 gbufferDepthProjection(const FrameData& frame) {
    glm::mat4 p = frame.projection;
    if (frame.settings->gbuffer.position != GBufferPositionMode::ReversedZ) return p;
    // z_clip = n/(f-n) z_eye + n f/(f-n), w = -z_eye: window depth 1 at the near plane, 0 at the far.
    const double n = frame.nearPlane, f = frame.farPlane;
    p[2][2] = float(n / (f - n));
    p[3][2] = float(n * f / (f - n));
    return p;
}

void setGBufferDepthTest(const GBufferSettings& layout) {
    const bool reversed = layout.position == GBufferPositionMode::ReversedZ;
    glClipControl(GL_LOWER_LEFT, reversed ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
    glDepthFunc(reversed ? GL_GREATER : GL_LESS);
}

bool gbufferCarriesFresnel(const FrameData& frame) {
    if (frame.scene == nullptr || materialInputShown(frame.settings->view) != 0) return false;
    for (const ModelInstance& model : frame.scene->models)
        for (const Material& m : model.mesh.materials)
            // Blended surfaces are shaded forward (the transparent pass): the G-buffer never holds them.
            if (m.dielectricF90 && m.alphaMode != AlphaMode::Blend) return true;
    return false;
}

bool gbufferCarriesClearcoat(const FrameData& frame) {
    if (frame.scene == nullptr || frame.settings->view == DebugView::Texcoords) return false;
    for (const ModelInstance& model : frame.scene->models)
        for (const Material& m : model.mesh.materials)
            if (m.hasClearcoat() && m.alphaMode != AlphaMode::Blend) return true;
    return false;
}

std::string gbufferClearcoatNote(const FrameData& frame) {
    size_t coated = 0, blended = 0;
    if (frame.scene != nullptr)
        for (const ModelInstance& model : frame.scene->models)
            for (const Material& m : model.mesh.materials)
                if (m.hasClearcoat()) (m.alphaMode == AlphaMode::Blend ? blended : coated) += 1;
    const std::string what = "KHR_materials_clearcoat: ";
    if (coated == 0)
        return what + "no gbuffer.clearcoat (no opaque material has a coat" +
               (blended > 0 ? "; " + std::to_string(blended) + " blended ones are coated in the transparent pass)" : ")");
    if (!gbufferCarriesClearcoat(frame))
        return what + "no gbuffer.clearcoat in the texcoords view (its target takes the location; nothing is lit)";
    return what + "gbuffer.clearcoat carries the coat of " + std::to_string(coated) + " opaque material(s)";
}

void readGBuffer(fg::PassBuilder& b, const GBuffer& g, bool diffuse, bool shading) {
    constexpr fg::Usage sampled = fg::Usage::Sampled;  // bindGBuffer binds them to texture units
    b.read(g.depth, sampled);
    b.read(g.normal, sampled);
    if (diffuse) b.read(g.diffuse, sampled);
    if (g.position.valid()) b.read(g.position, sampled);
    b.read(g.specular, sampled);
    if (shading && g.fresnel.valid()) b.read(g.fresnel, sampled);
    if (shading && g.clearcoat.valid()) b.read(g.clearcoat, sampled);
}

GBuffer createGBufferColourTargets(fg::PassBuilder& b, int w, int h, const GBufferSettings& layout,
                                   GBufferChannels channels, fg::Usage how) {
    GBuffer out;
    out.normal = b.createIfRead("gbuffer.normal", {w, h, gbufferNormalFormat(layout.normal)}, how);
    out.diffuse = b.createIfRead("gbuffer.diffuse", {w, h, kGBufferDiffuseFormat}, how);
    if (channels.position && !positionFromDepth(layout.position))
        out.position = b.createIfRead("gbuffer.position", {w, h, GL_RGBA32F}, how);
    out.specular = b.createIfRead("gbuffer.specular", {w, h, gbufferSpecularFormat(layout.normal)}, how);
    if (channels.texcoord) out.texcoord = b.createIfRead("gbuffer.texcoord", {w, h, GL_RG32F}, how);
    else if (channels.clearcoat) out.clearcoat = b.createIfRead("gbuffer.clearcoat", {w, h, GL_RGBA16}, how);
    if (channels.tangent) out.tangent = b.createIfRead("gbuffer.tangent", {w, h, GL_RGBA16F}, how);
    if (channels.velocity) out.velocity = b.createIfRead("gbuffer.velocity", {w, h, GL_RG16F}, how);
    if (channels.materialInput)
        out.materialInput = b.createIfRead("gbuffer.material_input", {w, h, GL_RGBA16F}, how);
    else if (channels.fresnel)
        out.fresnel = b.createIfRead("gbuffer.fresnel", {w, h, GL_RG16F}, how);
    return out;
}

void addGBufferImageDefines(std::vector<std::string>& d, const GBufferSettings& layout) {
    switch (gbufferNormalFormat(layout.normal)) {
        case GL_RGBA16F: d.push_back("LP_NORMAL_IMAGE_FORMAT rgba16f"); d.push_back("LP_NORMAL_IMAGE image2D"); break;
        case GL_RG32F: d.push_back("LP_NORMAL_IMAGE_FORMAT rg32f"); d.push_back("LP_NORMAL_IMAGE image2D"); break;
        case GL_R16UI: d.push_back("LP_NORMAL_IMAGE_FORMAT r16ui"); d.push_back("LP_NORMAL_IMAGE uimage2D"); break;
        case GL_R32UI: d.push_back("LP_NORMAL_IMAGE_FORMAT r32ui"); d.push_back("LP_NORMAL_IMAGE uimage2D"); break;
        default: d.push_back("LP_NORMAL_IMAGE_FORMAT rgba32f"); d.push_back("LP_NORMAL_IMAGE image2D"); break;
    }
    // An sRGB target is stored through its RGBA8 view (gl::imageFormatOf); the shader encodes.
    d.push_back(gl::imageFormatOf(gbufferSpecularFormat(layout.normal)) == GL_RGBA8 ? "LP_SPECULAR_IMAGE_FORMAT rgba8"
                                                                                    : "LP_SPECULAR_IMAGE_FORMAT rgba16f");
}

GLuint bindGBufferImages(const fg::PassResources& res, const GBuffer& g) {
    // Unit 7: the material input, or (never both: GBufferChannels::fresnel) the Fresnel ends; unit 4 the
    // texcoords or (never both: GBufferChannels::clearcoat) the clearcoat layer.
    const fg::ResourceId targets[8] = {g.normal,   g.diffuse, g.position, g.specular,
                                       g.clearcoat.valid() ? g.clearcoat : g.texcoord, g.tangent, g.velocity,
                                       g.fresnel.valid() ? g.fresnel : g.materialInput};
    GLuint bound = 0;
    for (GLuint i = 0; i < 8; ++i) {
        if (!targets[i].valid()) continue;
        const fg::PassResources::ImageBinding image = res.image(targets[i]);  // sRGB targets: an RGBA8 view
        if (!image.texture) continue;
        glBindImageTexture(i, image.texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, image.format);
        bound |= 1u << i;
    }
    return bound;
}

void unbindGBufferImages() {
    for (GLuint i = 0; i < 8; ++i) glBindImageTexture(i, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
}

void setBackgroundMotionUniforms(GLuint program, const FrameData& frame) {
    const gl::Uniforms u(frame.shaders, program);
    const glm::mat4 viewProjection = frame.unjitteredProjection * frame.view;  // velocity is unjittered
    const glm::mat4 rotation = frame.unjitteredProjection * glm::mat4(glm::mat3(frame.view));
    const glm::vec2 jitterNdc =
        2.0f * frame.jitterPixels / glm::vec2(std::max(frame.outputWidth, 1), std::max(frame.outputHeight, 1));
    u.set("uJitterNdc", jitterNdc);
    u.set("uInverseRotationProjection", glm::inverse(rotation));
    u.set("uViewProjection", viewProjection);
    u.set("uPreviousViewProjection", frame.previousViewProjection);
}

void setBrdfUniforms(GLuint prog, const FrameData& frame) {
    const RenderSettings& settings = *frame.settings;
    const gl::Uniforms u(frame.shaders, prog);
    u.set("uBrdf", int(settings.brdf));  // = LP_BRDF_*
    u.set("uSpecularMasking", int(settings.specularMasking));
    u.set("uHiddenTerms", int(hiddenShadingTerms(settings.view)));
}

void setMaterialInputUniform(GLuint prog, const FrameData& frame) {
    gl::Uniforms(frame.shaders, prog).set("uMaterialInput", int(materialInputShown(frame.settings->view)));
}

void bindGBuffer(GLuint program, const fg::PassResources& res, const GBuffer& g, const FrameData& frame, bool diffuse,
                 bool shading) {
    glBindTextureUnit(0, res.texture(g.depth));
    glBindTextureUnit(1, res.texture(g.normal));
    // The sRGB targets through their RGBA8 views: gbuffer_layout.glsl decodes them exactly.
    glBindTextureUnit(2, diffuse ? res.image(g.diffuse).texture : 0);
    glBindTextureUnit(3, g.position.valid() ? res.texture(g.position) : 0);
    glBindTextureUnit(4, res.image(g.specular).texture);
    if (shading && g.fresnel.valid()) glBindTextureUnit(kGBufferFresnelUnit, res.texture(g.fresnel));
    if (shading && g.clearcoat.valid()) glBindTextureUnit(kGBufferClearcoatUnit, res.texture(g.clearcoat));
    const glm::mat4& p = frame.projection;
    glProgramUniform4f(program, gl::Uniforms(frame.shaders, program).location("uGbufferCamera"), frame.nearPlane, frame.farPlane,
                       1.0f / p[1][1], p[1][1] / p[0][0]);
}

void unbindGBuffer() {
    for (GLuint u = 0; u < 5; ++u) glBindTextureUnit(u, 0);
    glBindTextureUnit(kGBufferFresnelUnit, 0);
    glBindTextureUnit(kGBufferClearcoatUnit, 0);
}

namespace {
// The G-buffer pass, or (named depth_prepass) forward+'s pre-pass: the same raster of the opaque
// draws into whichever targets later passes read.
GBuffer addGeometryPass(fg::FrameGraph& graph, GBufferPass& state, const FrameData& frame, GBufferChannels channels,
                        const char* name) {
    const int w = frame.width, h = frame.height;
    const GBufferSettings layout = frame.settings->gbuffer;
    return graph.addPass<GBuffer>(
        name, fg::PassKind::Raster,
        [&](fg::PassBuilder& b, GBuffer& out) {
            const fg::ResourceId depth =
                b.create("gbuffer.depth", {w, h, GL_DEPTH_COMPONENT32F}, fg::Usage::DepthAttachment);
            // Attachments for the meshes; image stores for the background (gbuffer_background.comp).
            out = createGBufferColourTargets(b, w, h, layout, channels,
                                             fg::Usage::ColorAttachment | fg::Usage::ImageStore);
            out.depth = depth;
            readPosedVertices(b, frame);
        },
        [&state, frame, layout](const GBuffer& out, const fg::PassResources& res) {
            const bool velocity = out.velocity.valid() && res.texture(out.velocity) != 0;
            // No material channel is read (forward+ without AO or a channel view): depth and motion only.
            bool depthOnly = true;
            for (fg::ResourceId c :
                 {out.normal, out.diffuse, out.position, out.specular, out.texcoord, out.tangent, out.materialInput, out.fresnel,
                  out.clearcoat})
                depthOnly = depthOnly && (!c.valid() || res.texture(c) == 0);
            auto variant = [&](gl::Program& program, GBufferProgramKey& builtFor, bool withVelocity,
                               bool withDepthOnly) -> const gl::Program& {
                return programForLayout(program, builtFor, frame, [&](std::vector<std::string> defines) {
                    if (withVelocity) defines.push_back("LP_GBUFFER_VELOCITY");
                    if (withVelocity) defines.push_back("LP_PREVIOUS_POSITION_ATTRIBUTE " + std::to_string(kPreviousPositionAttribute));
                    if (withDepthOnly) defines.push_back("LP_GBUFFER_DEPTH_ONLY");
                    return frame.shaders->graphics("gbuffer.vert", "gbuffer.frag", defines);
                });
            };
            const gl::Program& program =
                depthOnly ? (velocity ? variant(state.depthOnlyVelocityProgram, state.depthOnlyVelocityLayout, true, true)
                                      : variant(state.depthOnlyProgram, state.depthOnlyLayout, false, true))
                          : (velocity ? variant(state.velocityProgram, state.velocityLayout, true, false)
                                      : variant(state.program, state.layout, false, false));
            if (!state.fbo) state.fbo = gl::makeFramebuffer("gbuffer");
            const GLuint fbo = state.fbo.id();
            glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, res.texture(out.depth), 0);
            constexpr int kTargets = 8;  // = gbuffer.frag's outputs (location i) and gbuffer_images.glsl's bindings
            const fg::ResourceId colour[kTargets] = {out.normal,   out.diffuse,  out.position,
                                                     out.specular, out.clearcoat.valid() ? out.clearcoat : out.texcoord, out.tangent,
                                                     out.velocity, out.fresnel.valid() ? out.fresnel : out.materialInput};
            GLenum buffers[kTargets];
            for (int i = 0; i < kTargets; ++i) {
                // sRGB targets through their RGBA8 view: the shader writes the encoding (gbuffer.frag).
                GLuint tex = colour[i].valid() ? res.image(colour[i]).texture : 0;
                glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + i, tex, 0);
                buffers[i] = tex ? GL_COLOR_ATTACHMENT0 + i : GL_NONE;
            }
            glNamedFramebufferDrawBuffers(fbo, kTargets, buffers);
            gl::ScopedFramebuffer bind(fbo, frame.width, frame.height);
            gl::ScopedEnable depthTest(GL_DEPTH_TEST, true);
            gl::ScopedEnable cull(GL_CULL_FACE, false);  // thin walls and open meshes are two-sided
            gl::ScopedEnable blend(GL_BLEND, false);
            gl::ScopedRasterState saved;
            setGBufferDepthTest(layout);  // reversed-Z: clip control 0..1, GL_GREATER
            glDepthMask(GL_TRUE);
            // Only the depth is cleared: the colour targets' background is written after the meshes,
            // by compute at the pixels the depth shows empty (gbuffer_background.comp). Clearing every
            // target cost the H100 its fragment rate over the whole screen: 6.5 of 12.5 ms at 4K.
            const float farDepth = layout.position == GBufferPositionMode::ReversedZ ? 0.0f : 1.0f;
            glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &farDepth);

            const glm::mat4 viewProjection = frame.unjitteredProjection * frame.view;  // velocity is unjittered
            const GLuint prog = program.id();
            glUseProgram(prog);
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uProjection", gbufferDepthProjection(frame));
            setBrdfUniforms(prog, frame);
            setMaterialInputUniform(prog, frame);
            const GLint locClip = u.location("uClipFromModel");
            const GLint locPreviousClip = u.location("uPreviousClipFromModel");
            const GLint locMV = u.location("uModelView");
            const GLint locN = u.location("uNormalMatrix");
            const MaterialUniforms material(u);
            for (const auto& mesh : frame.gpu->meshes) {
                glm::mat4 mv = frame.view * mesh.model;
                glm::mat3 nm = glm::inverseTranspose(glm::mat3(mv));
                glProgramUniformMatrix4fv(prog, locMV, 1, GL_FALSE, glm::value_ptr(mv));
                glProgramUniformMatrix3fv(prog, locN, 1, GL_FALSE, glm::value_ptr(nm));
                if (velocity) {  // the model matrix does not move; an animated mesh's vertices bring their previous positions
                    const glm::mat4 clip = viewProjection * mesh.model, previous = frame.previousViewProjection * mesh.model;
                    glProgramUniformMatrix4fv(prog, locClip, 1, GL_FALSE, glm::value_ptr(clip));
                    glProgramUniformMatrix4fv(prog, locPreviousClip, 1, GL_FALSE, glm::value_ptr(previous));
                }
                glBindVertexArray(mesh.vao.id());
                for (const auto& d : mesh.draws) {
                    const GpuMaterial& m = frame.gpu->materials[size_t(d.material)];
                    if (m.alphaBlend) continue;  // blended: the transparent pass draws it after the opaque frame
                    material.set(prog, m);
                    glDrawElements(GL_TRIANGLES, GLsizei(d.indexCount), GL_UNSIGNED_INT,
                                   reinterpret_cast<const void*>(size_t(d.firstIndex) * sizeof(uint32_t)));
                }
            }
            glBindVertexArray(0);
            unbindMaterialTextures();

            // The background of every target written (gbuffer_background.comp); none with depth alone.
            const GLuint bound = bindGBufferImages(res, out);
            if (bound) {
                const GLuint bg = programForLayout(state.background, state.backgroundLayout, frame,
                                                   [&](std::vector<std::string> defines) {
                                                       addGBufferImageDefines(defines, layout);
                                                       return frame.shaders->compute("gbuffer_background.comp", defines);
                                                   })
                                      .id();
                glProgramUniform1ui(bg, gl::Uniforms(frame.shaders, bg).location("uTargets"), bound);
                glProgramUniform1f(bg, gl::Uniforms(frame.shaders, bg).location("uBackgroundDepth"), farDepth);
                setBackgroundMotionUniforms(bg, frame);
                glBindTextureUnit(6, res.texture(out.depth));
                glUseProgram(bg);
                glDispatchCompute(GLuint((frame.width + 7) / 8), GLuint((frame.height + 7) / 8), 1);
                glBindTextureUnit(6, 0);
            }
            unbindGBufferImages();
            glUseProgram(0);
        });
}

}  // namespace

GBuffer addGBufferPass(fg::FrameGraph& graph, GBufferPass& state, const FrameData& frame, GBufferChannels channels) {
    return addGeometryPass(graph, state, frame, channels, "gbuffer");
}

GBuffer addDepthPrepass(fg::FrameGraph& graph, GBufferPass& state, const FrameData& frame, GBufferChannels channels) {
    return addGeometryPass(graph, state, frame, channels, "depth_prepass");
}

}  // namespace lp

#include "passes/shadow_map_pass.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include <glm/gtc/type_ptr.hpp>

#include "engine/core/log.hpp"
#include "engine/gl/raster_probe.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/render/shadow_casters.hpp"

namespace lp {

std::string shadowRasterCacheKey() {
    auto str = [](GLenum name) {
        const GLubyte* v = glGetString(name);
        return v ? std::string(reinterpret_cast<const char*>(v)) : std::string("?");
    };
    return str(GL_VENDOR) + " / " + str(GL_RENDERER) + " / " + str(GL_VERSION);
}

std::filesystem::path shadowRasterCachePath() {
    if (const char* dir = std::getenv("LIGHTPASS_CACHE_DIR"); dir && *dir) return std::filesystem::path(dir) / "shadow_raster.txt";
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return std::filesystem::path(xdg) / "lightpass" / "shadow_raster.txt";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".cache" / "lightpass" / "shadow_raster.txt";
    return std::filesystem::path("lightpass_shadow_raster.txt");
}

ConservativeRasterSupport queryConservativeRasterSupport() {
    ConservativeRasterSupport support;
    if (!GLAD_GL_NV_conservative_raster) support.reason = "no GL_NV_conservative_raster";
    else if (!GLAD_GL_NV_fragment_shader_barycentric)
        support.reason = "GL_NV_conservative_raster without GL_NV_fragment_shader_barycentric (the fragment shader needs the triangle's vertices)";
    support.hardware = support.reason.empty();
    return support;
}

bool usesHardwareConservative(ShadowSettings::ConservativeRaster setting, const ConservativeRasterSupport& support) {
    return setting != ShadowSettings::ConservativeRaster::GeometryShader && support.hardware;
}

const char* conservativeRasterLabel(bool hardware) { return hardware ? "hardware" : "geometry shader"; }

bool ShadowTileKey::operator==(const ShadowTileKey& o) const {
    // Bit for bit: a matrix that differs in any bit may move a caster's depth by an ulp.
    return std::memcmp(&worldToClip, &o.worldToClip, sizeof worldToClip) == 0 && tileSize == o.tileSize &&
           column == o.column && row == o.row && raster == o.raster && hardwareConservative == o.hardwareConservative &&
           std::memcmp(&slopeBias, &o.slopeBias, sizeof slopeBias) == 0 && cullCasters == o.cullCasters;
}

size_t ShadowMapPass::cacheBytes() const {
    size_t bytes = 0;
    for (const auto& [light, atlas] : atlases)
        if (atlas.depth) bytes += size_t(atlas.width) * size_t(atlas.height) * sizeof(float);
    return bytes;
}

namespace {
// FNV-1a over raw bytes.
struct Fnv1a {
    uint64_t h = 1469598103934665603ull;
    void add(const void* data, size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    }
    template <typename T>
    void add(const T& v) {
        add(&v, sizeof v);
    }
};
}  // namespace

uint64_t casterSignature(const FrameData& frame) {
    Fnv1a f;
    if (!frame.gpu) {  // 'lightpass graph': nothing is drawn; the scene's transforms stand in
        for (const ModelInstance& m : frame.scene->models) f.add(m.transform);
        return f.h;
    }
    const SceneGpu& gpu = *frame.gpu;
    f.add(&gpu);
    f.add(gpu.meshes.size());
    for (const GpuMesh& mesh : gpu.meshes) {
        f.add(mesh.model);
        f.add(mesh.vao.id());
        f.add(mesh.vertices.id());
        f.add(mesh.indices.id());
    }
    for (const GpuMaterial& m : gpu.materials) f.add(m.alphaBlend);
    f.add(gpu.casterClusters.size());
    for (const CasterCluster& c : gpu.casterClusters) {
        f.add(c.model);
        f.add(c.firstIndex);
        f.add(c.indexCount);
    }
    return f.h;
}

bool growsCastersInHardware(ShadowSettings::Raster resolvedRaster, bool hardwareConservative) {
    return hardwareConservative &&
           (resolvedRaster == ShadowSettings::Raster::Conservative || resolvedRaster == ShadowSettings::Raster::Split);
}

std::vector<ShadowTileKey> shadowTileKeys(const ShadowFrustum& fr, const ShadowSettings& settings,
                                          ShadowSettings::Raster resolvedRaster, bool hardwareConservative) {
    std::vector<ShadowTileKey> keys(fr.cascades.size());
    for (size_t c = 0; c < keys.size(); ++c) {
        keys[c].worldToClip = fr.cascades[c].worldToClip;
        keys[c].tileSize = fr.tileSize;
        keys[c].column = int(c % size_t(fr.columns));
        keys[c].row = int(c / size_t(fr.columns));
        keys[c].raster = resolvedRaster;
        keys[c].hardwareConservative = growsCastersInHardware(resolvedRaster, hardwareConservative);
        keys[c].slopeBias = settings.slopeBias;
        keys[c].cullCasters = settings.cullCasters;
    }
    return keys;
}

std::vector<std::string> shadowTilesToDraw(const ShadowAtlasCache* cache, int width, int height, uint64_t casters,
                                           const std::vector<ShadowTileKey>& keys) {
    std::string all;
    if (!cache || !cache->depth || cache->width == 0) all = "nothing kept yet";
    else if (cache->width != width || cache->height != height) all = "atlas size changed";
    else if (cache->casters != casters) all = "casters changed";
    std::vector<std::string> why(keys.size(), all);
    if (!all.empty()) return why;
    for (size_t c = 0; c < keys.size(); ++c) {
        const ShadowTileKey& k = keys[c];
        if (c >= cache->tiles.size() || !cache->tiles[c]) {
            why[c] = "tile not drawn yet";
            continue;
        }
        const ShadowTileKey& old = *cache->tiles[c];
        if (old == k) continue;
        if (old.raster != k.raster) why[c] = "caster raster changed";
        else if (old.hardwareConservative != k.hardwareConservative)
            why[c] = std::string("conservative raster changed to ") + conservativeRasterLabel(k.hardwareConservative);
        else if (old.slopeBias != k.slopeBias) why[c] = "slope bias changed";
        else if (old.cullCasters != k.cullCasters) why[c] = "caster culling changed";
        else if (old.tileSize != k.tileSize) why[c] = "tile size changed";
        else if (glm::mat3(old.worldToClip) == glm::mat3(k.worldToClip) && old.worldToClip[3].z == k.worldToClip[3].z)
            why[c] = "square moved";  // same light, size and depth range: only the texel-snapped origin
        else why[c] = "light matrix changed";
    }
    return why;
}

namespace {
struct Data {
    fg::ResourceId depth;
};

struct DrawArraysCommand {
    GLuint count, instanceCount, first, baseInstance;
};

// --shadow-raster compute, inside the pass's framebuffer (the atlas bound as its depth, cleared to
// 1, depth clamp and the polygon offset factor set): every cascade's culled casters through
// shadow_raster.comp into the R32UI image, that image into the atlas, then each cascade's large
// triangles drawn plainly over it with the depth test.
void drawCascadesByCompute(ShadowMapPass& state, const FrameData& frame, const ShadowFrustum& fr,
                           const std::vector<CasterList>& casters, int width, int height, bool depthZeroToOne,
                           const std::vector<bool>& redraw) {
    if (!state.rasterProgram) state.rasterProgram = frame.shaders->compute("shadow_raster.comp");
    if (!state.resolveProgram) state.resolveProgram = frame.shaders->graphics("fullscreen.vert", "shadow_raster_resolve.frag");
    if (!state.largeProgram) state.largeProgram = frame.shaders->graphics("shadow_raster_large.vert", "shadow_depth.frag");
    if (!state.emptyVao) state.emptyVao = gl::makeVertexArray("shadow_map.compute_raster");
    if (!state.depthBits || state.depthBits.width != width || state.depthBits.height != height)
        state.depthBits = gl::makeTexture2D(GL_R32UI, width, height, 1, "shadow_map.depth_bits");
    // Every caster of a cascade may be large: one region of that many vertices per cascade.
    std::vector<DrawArraysCommand> commands(fr.cascades.size());
    size_t needed = 0;
    for (size_t c = 0; c < fr.cascades.size(); ++c) {
        commands[c] = {0, 1, GLuint(needed), 0};
        if (redraw[c]) needed += 3 * casters[c].triangles;
    }
    needed = std::max<size_t>(needed, 3);
    if (needed > state.largeCapacity) {
        state.largeVertices = gl::makeBuffer(GLsizeiptr(needed * sizeof(glm::vec4)), nullptr, 0, "shadow_map.large_vertices");
        state.largeCapacity = needed;
    }
    // A buffer no earlier frame's indirect draws still read (gl::StreamBuffer).
    const GLuint largeDraws = state.largeDraws.fill(commands.data(), commands.size() * sizeof(DrawArraysCommand));
    const GLuint cleared = 0x3f800000u;  // the bits of 1.0f: no caster
    glClearTexImage(state.depthBits.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &cleared);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);

    const GLuint prog = state.rasterProgram.id();
    glUseProgram(prog);
    glBindImageTexture(0, state.depthBits.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, largeDraws);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, state.largeVertices.id());
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uTileSize"), fr.tileSize);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uDepthZeroToOne"), depthZeroToOne ? 1 : 0);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uSlopeBias"), frame.settings->shadows.slopeBias);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uLargeTexels"), kComputeRasterMaxTexels);
    if (!state.rasterModel) state.rasterModel = gl::probeRasterInterpolation(*frame.shaders);
    // Edge functions of 32-bit integers: at most 8 sub-texel bits keep uLargeTexels' triangles exact.
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uSubTexel"), 1 << std::min(state.rasterModel->subpixelBits, 8));
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uSnappedDepthPlane"), state.rasterModel->fromSnappedVertices);
    const GLint locMvp = glGetUniformLocation(prog, "uModelToClip");
    const GLint locFirst = glGetUniformLocation(prog, "uFirstIndex");
    const GLint locCount = glGetUniformLocation(prog, "uTriangleCount");
    for (size_t c = 0; c < fr.cascades.size(); ++c) {
        if (!redraw[c]) continue;  // kept from an earlier frame (--shadow-cache)
        glProgramUniform2i(prog, glGetUniformLocation(prog, "uTileOrigin"), GLint(c % size_t(fr.columns)) * fr.tileSize,
                           GLint(c / size_t(fr.columns)) * fr.tileSize);
        glProgramUniform1i(prog, glGetUniformLocation(prog, "uCascade"), GLint(c));
        for (const CasterDraw& draw : casters[c].draws) {
            if (draw.model < 0 || size_t(draw.model) >= frame.gpu->meshes.size()) continue;
            const GpuMesh& mesh = frame.gpu->meshes[size_t(draw.model)];
            const glm::mat4 mvp = fr.cascades[c].worldToClip * mesh.model;
            glProgramUniformMatrix4fv(prog, locMvp, 1, GL_FALSE, glm::value_ptr(mvp));
            glProgramUniform1ui(prog, locFirst, draw.firstIndex);
            const GLuint triangles = draw.indexCount / 3;
            glProgramUniform1ui(prog, locCount, triangles);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, mesh.vertices.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, mesh.indices.id());
            glDispatchCompute((triangles + 63) / 64, 1, 1);
        }
    }
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    for (GLuint b = 0; b < 4; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);

    // The bits into the atlas: every texel of the redrawn tiles written, the depth test off.
    glBindVertexArray(state.emptyVao.id());
    glDepthFunc(GL_ALWAYS);
    glUseProgram(state.resolveProgram.id());
    glBindTextureUnit(0, state.depthBits.id());
    const bool all = std::all_of(redraw.begin(), redraw.end(), [](bool r) { return r; });
    if (all) {
        glViewport(0, 0, width, height);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glEnable(GL_SCISSOR_TEST);  // tiles kept from an earlier frame (--shadow-cache) stay untouched
    for (size_t c = 0; c < fr.cascades.size() && !all; ++c) {
        if (!redraw[c]) continue;
        glViewport(GLint(c % size_t(fr.columns)) * fr.tileSize, GLint(c / size_t(fr.columns)) * fr.tileSize, fr.tileSize,
                   fr.tileSize);
        glScissor(GLint(c % size_t(fr.columns)) * fr.tileSize, GLint(c / size_t(fr.columns)) * fr.tileSize, fr.tileSize,
                  fr.tileSize);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glDisable(GL_SCISSOR_TEST);
    glBindTextureUnit(0, 0);
    glDepthFunc(GL_LESS);

    // The large triangles: the plain path (polygon offset, depth clamp), one indirect draw per cascade.
    glUseProgram(state.largeProgram.id());
    glEnable(GL_POLYGON_OFFSET_FILL);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, largeDraws);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, state.largeVertices.id());
    glEnable(GL_SCISSOR_TEST);
    for (size_t c = 0; c < fr.cascades.size(); ++c) {
        if (!redraw[c]) continue;
        glViewport(GLint(c % size_t(fr.columns)) * fr.tileSize, GLint(c / size_t(fr.columns)) * fr.tileSize, fr.tileSize,
                   fr.tileSize);
        glScissor(GLint(c % size_t(fr.columns)) * fr.tileSize, GLint(c / size_t(fr.columns)) * fr.tileSize, fr.tileSize,
                  fr.tileSize);
        glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(c * sizeof(DrawArraysCommand)));
    }
    glDisable(GL_SCISSOR_TEST);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, 0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glBindVertexArray(0);
    glUseProgram(0);
}

// Draws the cascades' casters into the atlas `depthTexture` (width x height) with `raster` (not Auto),
// only the tiles of the cascades `redraw` marks (each cleared first; all of them: the whole atlas
// cleared); the other tiles are left as they are. Conservative and split grow casters by
// GL_NV_conservative_raster where state.hardwareConservative, else by the geometry shader.
void drawAtlas(ShadowMapPass& state, const FrameData& frame, const ShadowFrustum& fr, const std::vector<CasterList>& casters,
               ShadowSettings::Raster raster, GLuint depthTexture, int width, int height, const std::vector<bool>& redraw) {
    using Raster = ShadowSettings::Raster;
        if (!state.fbo) state.fbo = gl::makeFramebuffer("shadow_map");
        const bool hardware = growsCastersInHardware(raster, state.hardwareConservative);
        if (hardware && raster == Raster::Conservative && !state.hardwareTowardProgram)
            state.hardwareTowardProgram = frame.shaders->graphics("shadow_depth.vert", "shadow_depth.frag",
                                                                  std::vector<std::string>{"LP_SHADOW_HARDWARE_CONSERVATIVE"});
        if (hardware && !state.hardwareAwayProgram)
            state.hardwareAwayProgram = frame.shaders->graphics("shadow_depth.vert", "shadow_depth.frag",
                                                                std::vector<std::string>{"LP_SHADOW_HARDWARE_CONSERVATIVE",
                                                                                         "LP_SHADOW_FACES_AWAY"});
        if (!hardware && raster == Raster::Conservative && !state.program)
            state.program = frame.shaders->graphics("shadow_depth.vert", "shadow_depth.geom", "shadow_depth.frag",
                                                    {"LP_SHADOW_CONSERVATIVE"});
        if (!hardware && raster == Raster::Split && !state.awayProgram)
            state.awayProgram = frame.shaders->graphics("shadow_depth.vert", "shadow_depth.geom", "shadow_depth.frag",
                                                        {"LP_SHADOW_CONSERVATIVE", "LP_SHADOW_AWAY_ONLY"});
        if ((raster == Raster::Plain || raster == Raster::Split) && !state.plainProgram)
            state.plainProgram = frame.shaders->graphics("shadow_depth.vert", "shadow_depth.frag");
        const GLuint fbo = state.fbo.id();
        glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depthTexture, 0);
        glNamedFramebufferDrawBuffer(fbo, GL_NONE);
        glNamedFramebufferReadBuffer(fbo, GL_NONE);
        gl::ScopedFramebuffer bind(fbo, width, height);
        gl::ScopedEnable depthTest(GL_DEPTH_TEST, true);
        gl::ScopedEnable cull(GL_CULL_FACE, false);  // thin walls and open meshes cast from both sides
        gl::ScopedEnable blend(GL_BLEND, false);
        gl::ScopedEnable clamp(GL_DEPTH_CLAMP, true);  // casters past the light's near plane still cast
        gl::ScopedEnable offset(GL_POLYGON_OFFSET_FILL, false);
        // GL_CONSERVATIVE_RASTERIZATION_NV exists only with the extension: off but around the hardware
        // draws, and put back as found (the GL state check watches it where it exists).
        std::optional<gl::ScopedEnable> conservative;
        if (GLAD_GL_NV_conservative_raster) conservative.emplace(GL_CONSERVATIVE_RASTERIZATION_NV, false);
        gl::ScopedRasterState saved;  // depth function and mask, polygon offset, cull face
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        // Plain draws: the slope bias is the polygon offset's factor (as the spot maps').
        glPolygonOffset(frame.settings->shadows.slopeBias, 0.0f);
        const float one = 1.0f;
        if (std::all_of(redraw.begin(), redraw.end(), [](bool r) { return r; })) {
            glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);
        } else {
            gl::ScopedEnable scissor(GL_SCISSOR_TEST, true);
            for (size_t c = 0; c < fr.cascades.size(); ++c)
                if (redraw[c]) {
                    glScissor(GLint(c % size_t(fr.columns)) * fr.tileSize, GLint(c / size_t(fr.columns)) * fr.tileSize,
                              fr.tileSize, fr.tileSize);
                    glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);
                }
        }

        GLint clipDepth = GL_NEGATIVE_ONE_TO_ONE;
        glGetIntegerv(GL_CLIP_DEPTH_MODE, &clipDepth);
        const GLuint conservativeProg = hardware                       ? 0
                                        : raster == Raster::Conservative ? state.program.id()
                                        : raster == Raster::Split        ? state.awayProgram.id()
                                                                         : 0;
        // Hardware: faces towards the light (conservative only; split draws them plainly), then away.
        const GLuint hardwareProgs[2] = {hardware && raster == Raster::Conservative ? state.hardwareTowardProgram.id() : 0,
                                         hardware ? state.hardwareAwayProgram.id() : 0};
        for (GLuint prog : {conservativeProg, hardwareProgs[0], hardwareProgs[1]}) {
            if (!prog) continue;
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uDepthZeroToOne"), clipDepth == GL_ZERO_TO_ONE ? 1 : 0);
            // Slope-scaled bias against acne, for the faces towards the light only (shadow_depth.frag);
            // the constant part is the receiver's (see shadow.glsl).
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uSlopeBias"), frame.settings->shadows.slopeBias);
        }
        if (raster == Raster::Compute) {
            gl::ScopedEnable scissor(GL_SCISSOR_TEST, false);  // drawCascadesByCompute scissors per tile
            drawCascadesByCompute(state, frame, fr, casters, width, height, clipDepth == GL_ZERO_TO_ONE, redraw);
            glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, 0, 0);
            return;
        }
        const GLuint plainProg = raster == Raster::Conservative ? 0 : state.plainProgram.id();
        // Each cascade's fragments stay in its tile whatever a driver's guard band does: a kept
        // neighbour (--shadow-cache) must not receive this frame's casters.
        gl::ScopedEnable scissor(GL_SCISSOR_TEST, true);
        for (size_t c = 0; c < fr.cascades.size(); ++c) {
            if (!redraw[c]) continue;  // kept from an earlier frame (--shadow-cache)
            const GLint x = GLint(c % size_t(fr.columns)) * fr.tileSize;
            const GLint y = GLint(c / size_t(fr.columns)) * fr.tileSize;
            glViewport(x, y, fr.tileSize, fr.tileSize);
            glScissor(x, y, fr.tileSize, fr.tileSize);
            if (plainProg) {
                // Split: only the faces towards the light (counter-clockwise in the light's window,
                // as shadow_depth.geom's orientation), which need neither growth nor gl_FragDepth.
                glUseProgram(plainProg);
                glEnable(GL_POLYGON_OFFSET_FILL);
                if (raster == Raster::Split) glEnable(GL_CULL_FACE);
                glCullFace(GL_BACK);
                drawCasterList(frame, plainProg, glGetUniformLocation(plainProg, "uModelToClip"),
                               fr.cascades[c].worldToClip, casters[c]);
                glDisable(GL_POLYGON_OFFSET_FILL);
                glDisable(GL_CULL_FACE);
            }
            if (conservativeProg) {
                glUseProgram(conservativeProg);
                glProgramUniform4f(conservativeProg, glGetUniformLocation(conservativeProg, "uViewport"), float(x),
                                   float(y), float(fr.tileSize), float(fr.tileSize));
                drawCasterList(frame, conservativeProg, glGetUniformLocation(conservativeProg, "uModelToClip"),
                               fr.cascades[c].worldToClip, casters[c]);
            }
            if (hardware) {
                // Every texel a triangle touches gets a fragment; no geometry shader, no box to clip to.
                // Each facing in a draw of its own (the other culled, counter-clockwise in the light's
                // window = towards it, as shadow_depth.geom), towards the light first, so each fragment
                // shader knows its facing and can promise depth_greater (shadow_depth.frag).
                glEnable(GL_CONSERVATIVE_RASTERIZATION_NV);
                glEnable(GL_CULL_FACE);
                for (int facing = 0; facing < 2; ++facing) {
                    const GLuint prog = hardwareProgs[facing];
                    if (!prog) continue;
                    glCullFace(facing == 0 ? GL_BACK : GL_FRONT);
                    if (facing == 1) {
                        // Faces away write the nearest depth over the texel, up to (|dz/dx| + |dz/dy|) / 2
                        // <= max(|dz/dx|, |dz/dy|) nearer than the centre: rasterised that much nearer
                        // (and a quarter more, and 4 units, for the rounding between the rasteriser's
                        // depth and the shader's plane), it stays at or in front of what they write.
                        glEnable(GL_POLYGON_OFFSET_FILL);
                        glPolygonOffset(-1.25f, -4.0f);
                    }
                    glUseProgram(prog);
                    glProgramUniform4f(prog, glGetUniformLocation(prog, "uViewport"), float(x), float(y),
                                       float(fr.tileSize), float(fr.tileSize));
                    drawCasterList(frame, prog, glGetUniformLocation(prog, "uModelToClip"), fr.cascades[c].worldToClip,
                                   casters[c]);
                }
                glDisable(GL_POLYGON_OFFSET_FILL);
                glPolygonOffset(frame.settings->shadows.slopeBias, 0.0f);
                glDisable(GL_CULL_FACE);
                glDisable(GL_CONSERVATIVE_RASTERIZATION_NV);
            }
        }
        glBindVertexArray(0);
        glUseProgram(0);
        glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, 0, 0);
}

// --shadow-raster auto: the raster cached for this GPU, else the fastest of the four measured on this
// first frame's cascades (each drawn once to compile, then kAutoRuns times between GL timestamps;
// the median counts) and cached. Bad cache lines are ignored with a warning and rewritten.
constexpr int kAutoRuns = 5;
constexpr ShadowSettings::Raster kMeasuredRasters[] = {ShadowSettings::Raster::Conservative, ShadowSettings::Raster::Plain,
                                                       ShadowSettings::Raster::Split, ShadowSettings::Raster::Compute};

bool rasterFromName(const std::string& name, ShadowSettings::Raster& out) {
    for (ShadowSettings::Raster r : kMeasuredRasters)
        if (name == ShadowSettings::rasterName(r)) {
            out = r;
            return true;
        }
    return false;
}

template <typename DrawFn>
ShadowSettings::Raster resolveAutoRaster(ShadowMapPass& state, DrawFn&& draw) {
    if (state.autoResolved) return state.autoRaster;
    state.autoResolved = true;
    const std::string key = shadowRasterCacheKey();
    const std::filesystem::path path = shadowRasterCachePath();
    std::vector<std::string> kept;  // other GPUs' lines
    {
        std::ifstream in(path);
        std::string line;
        while (std::getline(in, line)) {
            const size_t tab = line.find('\t');
            if (tab == std::string::npos || line.substr(tab + 1) != key) {
                if (!line.empty()) kept.push_back(line);
                continue;
            }
            ShadowSettings::Raster cached;
            if (rasterFromName(line.substr(0, tab), cached)) {
                state.autoRaster = cached;
                state.autoReport = std::string("shadow raster auto: ") + ShadowSettings::rasterName(cached) + " (cached in " +
                                   path.string() + ")";
                logInfo(state.autoReport);
                return cached;
            }
            logWarn(path.string() + ": unknown shadow raster '" + line.substr(0, tab) + "' for this GPU; measuring again");
        }
    }
    std::string times;
    double best = 0.0;
    for (ShadowSettings::Raster r : kMeasuredRasters) {
        draw(r);  // compiles the programs, makes the buffers
        std::vector<double> ms;
        for (int i = 0; i < kAutoRuns; ++i) {
            gl::Query begin = gl::makeQuery(GL_TIMESTAMP), end = gl::makeQuery(GL_TIMESTAMP);
            glQueryCounter(begin.id(), GL_TIMESTAMP);
            draw(r);
            glQueryCounter(end.id(), GL_TIMESTAMP);
            GLuint64 t0 = 0, t1 = 0;
            glGetQueryObjectui64v(begin.id(), GL_QUERY_RESULT, &t0);
            glGetQueryObjectui64v(end.id(), GL_QUERY_RESULT, &t1);
            ms.push_back(double(t1 - t0) * 1e-6);
        }
        std::sort(ms.begin(), ms.end());
        const double median = ms[ms.size() / 2];
        times += std::string(times.empty() ? "" : ", ") + ShadowSettings::rasterName(r) + " " + std::to_string(median) + " ms";
        if (r == kMeasuredRasters[0] || median < best) {
            best = median;
            state.autoRaster = r;
        }
    }
    state.autoReport = std::string("shadow raster auto: ") + ShadowSettings::rasterName(state.autoRaster) + " (measured: " +
                       times + "; conservative and split on the " + conservativeRasterLabel(state.hardwareConservative) +
                       " conservative raster; cached in " + path.string() + ")";
    logInfo(state.autoReport);
    // Written beside and renamed over the cache: a failed write leaves the old file whole.
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    const std::filesystem::path temporary = path.string() + ".tmp";
    {
        std::ofstream out(temporary, std::ios::trunc);
        for (const std::string& line : kept) out << line << '\n';
        out << ShadowSettings::rasterName(state.autoRaster) << '\t' << key << '\n';
        if (!out) ec = std::make_error_code(std::errc::io_error);
    }
    if (!ec) std::filesystem::rename(temporary, path, ec);
    if (ec) {
        std::filesystem::remove(temporary, ec);
        logWarn(path.string() + ": could not write the shadow raster cache; auto measures again next start");
    }
    return state.autoRaster;
}

// Sets state.hardwareConservative for this frame (the GPU asked once: a context is current where the
// scene is on the GPU; 'lightpass graph --explain' sets state.conservativeSupport from a context of
// its own) and returns what the cascades' notes add about it (nothing for rasters that grow none).
std::string chooseConservativeRaster(ShadowMapPass& state, const FrameData& frame) {
    if (frame.gpu && !state.conservativeSupport) state.conservativeSupport = queryConservativeRasterSupport();
    const ShadowSettings::ConservativeRaster setting = frame.settings->shadows.conservativeRaster;
    state.hardwareConservative = state.conservativeSupport && usesHardwareConservative(setting, *state.conservativeSupport);
    if (setting == ShadowSettings::ConservativeRaster::Hardware && state.conservativeSupport &&
        !state.conservativeSupport->hardware && !state.warnedNoHardware) {
        logWarn("--shadow-conservative hardware: this GPU has " + state.conservativeSupport->reason +
                "; conservative casters use the geometry shader");
        state.warnedNoHardware = true;
    }
    const ShadowSettings::Raster raster = frame.settings->shadows.raster;
    if (raster != ShadowSettings::Raster::Conservative && raster != ShadowSettings::Raster::Split &&
        raster != ShadowSettings::Raster::Auto)
        return "";
    if (setting == ShadowSettings::ConservativeRaster::GeometryShader) return ", geometry shader conservative";
    if (!state.conservativeSupport)
        return ", hardware conservative where the GPU has GL_NV_conservative_raster, else geometry shader";
    return state.hardwareConservative ? ", hardware conservative"
                                      : ", geometry shader conservative: " + state.conservativeSupport->reason;
}

}  // namespace

ShadowMaps addShadowMapPasses(fg::FrameGraph& graph, ShadowMapPass& state, const FrameData& frame) {
    ShadowMaps maps;
    // Say why a frame has no (or fewer) shadow passes: 'lightpass graph' and the viewer show it.
    const auto& lights = frame.scene->directionalLights;
    int casting = 0;
    for (const auto& l : lights) casting += (l.castsShadows || frame.settings->allPasses) ? 1 : 0;
    if (casting == 0) graph.skipPass("shadow_map", "no directional light casts shadows");
    else if (!frame.settings->shadows.enabled) graph.skipPass("shadow_map", "shadows are off (--no-shadows)");
    else if (casting > kMaxShadowedLights)
        graph.skipPass("shadow_map", std::to_string(casting - kMaxShadowedLights) + " shadow-casting lights past the first " +
                                         std::to_string(kMaxShadowedLights) + " are unshadowed");
    // Caster clusters: made once at load with the GPU meshes; 'lightpass graph' (no GPU) makes them here.
    std::vector<CasterCluster> localClusters;
    if (!frame.gpu && frame.settings->shadows.enabled && casting > 0) localClusters = buildCasterClusters(*frame.scene);
    const std::vector<CasterCluster>& clusters = frame.gpu ? frame.gpu->casterClusters : localClusters;
    size_t sceneTriangles = 0;
    for (const CasterCluster& c : clusters) sceneTriangles += c.indexCount / 3;
    const bool caching = frame.settings->shadows.cache;
    const std::vector<int> shadowed = shadowCastingLights(frame);
    // Kept atlases of lights no longer shadowed (or every one, with the cache off) are let go.
    for (auto it = state.atlases.begin(); it != state.atlases.end();)
        it = (!caching || std::find(shadowed.begin(), shadowed.end(), it->first) == shadowed.end()) ? state.atlases.erase(it)
                                                                                                     : std::next(it);
    const uint64_t casterKey = caching ? casterSignature(frame) : 0;
    // The raster this frame draws with where it is already known (auto: once measured).
    const ShadowSettings::Raster knownRaster = frame.settings->shadows.raster != ShadowSettings::Raster::Auto
                                                   ? frame.settings->shadows.raster
                                               : state.autoResolved ? state.autoRaster
                                                                    : ShadowSettings::Raster::Auto;
    const std::string rasterNote = std::string(ShadowSettings::rasterName(frame.settings->shadows.raster)) + " raster" +
                                   chooseConservativeRaster(state, frame);
    for (int light : shadowed) {
        LightShadowMap map;
        map.light = light;
        map.frustum = fitShadowFrustum(frame, frame.scene->directionalLights[size_t(light)].direction);
        const ShadowFrustum& fr = map.frustum;
        const std::string name = "shadow_map_" + std::to_string(light);
        // A small scene needs fewer cascades than asked for: say which were dropped and why.
        if (const std::string why = droppedCascadesReason(fr, frame.settings->shadows.cascades); !why.empty())
            graph.skipPass(name + " cascades", why);
        const fg::TextureDesc desc{fr.tileSize * fr.columns, fr.tileSize * fr.rows, GL_DEPTH_COMPONENT32F};
        // --shadow-cache: which tiles the kept atlas already holds (empty reason: kept).
        const std::vector<ShadowTileKey> keys = shadowTileKeys(fr, frame.settings->shadows, knownRaster, state.hardwareConservative);
        const auto kept = state.atlases.find(light);
        std::vector<std::string> why =
            caching ? shadowTilesToDraw(kept == state.atlases.end() ? nullptr : &kept->second, desc.width, desc.height,
                                        casterKey, keys)
                    : std::vector<std::string>(fr.cascades.size(), "cache off");
        if (knownRaster == ShadowSettings::Raster::Auto)
            for (std::string& w : why) w = "first frame of --shadow-raster auto";
        std::vector<bool> redraw(fr.cascades.size());
        for (size_t c = 0; c < redraw.size(); ++c) redraw[c] = !why[c].empty();
        // Each cascade's casters, culled to its tile (one texel of margin for the conservative growth).
        std::vector<CasterList> casters;
        for (size_t c = 0; c < fr.cascades.size(); ++c) {
            casters.push_back(cullCasters(clusters, *frame.scene, fr.cascades[c].worldToClip, 2.0f / float(fr.tileSize),
                                          frame.settings->shadows.cullCasters));
            const CasterList& l = casters.back();
            graph.notePass(name, "cascade " + std::to_string(c) + ": " + std::to_string(l.draws.size()) + " draws, " +
                                     std::to_string(l.clusters) + " of " + std::to_string(clusters.size()) + " clusters, " +
                                     std::to_string(l.triangles) + " of " + std::to_string(sceneTriangles) + " triangles (" +
                                     rasterNote +
                                     (frame.settings->shadows.cullCasters ? "" : ", culling off") + "); " +
                                     (redraw[c] ? "redrawn (" + why[c] + ")" : std::string("kept (unchanged)")));
        }
        ShadowMapPass* s = &state;
        fg::ResourceId keptAtlas;
        if (caching)  // the kept atlas, made (cleared to 1: no caster) when first asked for or resized
            keptAtlas = graph.importTexture(name + ".depth", desc, [s, light, desc]() -> GLuint {
                ShadowAtlasCache& a = s->atlases[light];
                if (!a.depth || a.width != desc.width || a.height != desc.height) {
                    a = ShadowAtlasCache{};
                    a.light = light;
                    a.depth = gl::makeTexture2D(GL_DEPTH_COMPONENT32F, desc.width, desc.height, 1, "shadow_map.kept_atlas");
                    a.width = desc.width;
                    a.height = desc.height;
                    const float one = 1.0f;
                    glClearTexImage(a.depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &one);
                }
                return a.depth.id();
            });
        const Data& data = graph.addPass<Data>(
            name, fg::PassKind::Raster,
            [&](fg::PassBuilder& b, Data& out) {
                out.depth = caching ? b.write(keptAtlas, fg::Usage::DepthAttachment)
                                    : b.create(name + ".depth", desc, fg::Usage::DepthAttachment);
            },
            [s, frame, fr, casters, caching, light, keys, redraw, casterKey](const Data& out, const fg::PassResources& res) {
                const fg::TextureDesc& d = res.desc(out.depth);
                const GLuint texture = res.texture(out.depth);
                ShadowSettings::Raster raster = frame.settings->shadows.raster;
                const std::vector<bool> everyTile(fr.cascades.size(), true);
                if (raster == ShadowSettings::Raster::Auto)
                    raster = resolveAutoRaster(*s, [&](ShadowSettings::Raster r) {
                        drawAtlas(*s, frame, fr, casters, r, texture, d.width, d.height, everyTile);
                    });
                drawAtlas(*s, frame, fr, casters, raster, texture, d.width, d.height, redraw);
                const size_t drawn = size_t(std::count(redraw.begin(), redraw.end(), true));
                s->cacheStats.drawn += drawn;
                s->cacheStats.kept += redraw.size() - drawn;
                for (size_t c = 0; c < redraw.size() && c < size_t(kMaxShadowCascades); ++c)
                    ++(redraw[c] ? s->cacheStats.drawnPerCascade[c] : s->cacheStats.keptPerCascade[c]);
                if (!caching) return;
                // What the tiles now hold. A new caster set or a whole-atlas clear (every tile
                // drawn) leaves tiles past this frame's cascades unknown.
                ShadowAtlasCache& a = s->atlases[light];
                if (a.casters != casterKey || drawn == redraw.size()) a.tiles.assign(a.tiles.size(), std::nullopt);
                a.casters = casterKey;
                if (a.tiles.size() < keys.size()) a.tiles.resize(keys.size());
                for (size_t c = 0; c < keys.size(); ++c)
                    if (redraw[c]) {
                        a.tiles[c] = keys[c];
                        a.tiles[c]->raster = raster;
                        a.tiles[c]->hardwareConservative = growsCastersInHardware(raster, s->hardwareConservative);
                    }
            });
        map.depth = data.depth;
        maps.push_back(std::move(map));
    }
    return maps;
}

void drawCasterList(const FrameData& frame, GLuint prog, GLint locMvp, const glm::mat4& worldToClip, const CasterList& casters) {
    int boundModel = -1;
    for (const CasterDraw& draw : casters.draws) {
        if (draw.model < 0 || size_t(draw.model) >= frame.gpu->meshes.size()) continue;
        const GpuMesh& mesh = frame.gpu->meshes[size_t(draw.model)];
        if (draw.model != boundModel) {
            const glm::mat4 mvp = worldToClip * mesh.model;
            glProgramUniformMatrix4fv(prog, locMvp, 1, GL_FALSE, glm::value_ptr(mvp));
            glBindVertexArray(mesh.vao.id());
            boundModel = draw.model;
        }
        glDrawElements(GL_TRIANGLES, GLsizei(draw.indexCount), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(size_t(draw.firstIndex) * sizeof(uint32_t)));
    }
}

void drawShadowCasters(const FrameData& frame, GLuint prog, GLint locMvp, const glm::mat4& worldToClip) {
    for (const auto& mesh : frame.gpu->meshes) {
        const glm::mat4 mvp = worldToClip * mesh.model;
        glProgramUniformMatrix4fv(prog, locMvp, 1, GL_FALSE, glm::value_ptr(mvp));
        glBindVertexArray(mesh.vao.id());
        for (const auto& draw : mesh.draws) {
            if (frame.gpu->materials[size_t(draw.material)].alphaBlend) continue;  // blended surfaces cast no shadow
            glDrawElements(GL_TRIANGLES, GLsizei(draw.indexCount), GL_UNSIGNED_INT,
                           reinterpret_cast<const void*>(size_t(draw.firstIndex) * sizeof(uint32_t)));
        }
    }
}

}  // namespace lp

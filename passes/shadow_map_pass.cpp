#include "passes/shadow_map_pass.hpp"

#include <algorithm>
#include <bitset>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include <glm/gtc/type_ptr.hpp>

#include "engine/core/fnv1a.hpp"
#include "engine/core/log.hpp"
#include "engine/core/measured_cache.hpp"
#include "engine/gl/raster_probe.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/render/shadow_casters.hpp"
#include "passes/skinning_pass.hpp"

namespace lp {

std::string shadowRasterCacheKey() {
    auto str = [](GLenum name) {
        const GLubyte* v = glGetString(name);
        return v ? std::string(reinterpret_cast<const char*>(v)) : std::string("?");
    };
    return str(GL_VENDOR) + " / " + str(GL_RENDERER) + " / " + str(GL_VERSION);
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
    if (spareAtlas) bytes += size_t(spareAtlas.width) * size_t(spareAtlas.height) * sizeof(float);
    return bytes;
}

namespace {
// Atlas texel of cascade c's tile's first texel (column tile % columns, row tile / columns).
glm::ivec2 tileOrigin(const ShadowFrustum& fr, size_t c) {
    const int tile = fr.cascades[c].tile;
    return glm::ivec2(tile % fr.columns, tile / fr.columns) * fr.tileSize;
}
}  // namespace

uint64_t casterSignature(const FrameData& frame) {
    Fnv1a f;
    if (!frame.gpu) {  // 'lightpass graph': nothing is drawn; the scene's transforms stand in
        for (const ModelInstance& m : frame.scene->models)
            for (size_t k = 0; k < m.instanceCount(); ++k) f.add(m.instanceTransform(k));
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
        f.add(mesh.poseVersion);  // an animated mesh that moved since the atlas was drawn
    }
    for (const GpuMaterial& m : gpu.materials) {  // what the alpha-tested casters read
        f.add(m.alphaMask);
        f.add(m.alphaBlend);
        f.add(m.alphaCutoff);
        f.add(m.opacity);
        f.add(m.diffuseMap);
        f.add(m.secondUvMaps);
    }
    f.add(gpu.casterClusters.size());
    for (const CasterCluster& c : gpu.casterClusters) {
        f.add(c.model);
        f.add(c.firstIndex);
        f.add(c.indexCount);
        f.add(c.alpha);
        f.add(c.material);
    }
    return f.h;
}

bool atlasIsMarked(ShadowSettings::Raster resolvedRaster) { return resolvedRaster == ShadowSettings::Raster::Conservative; }

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
        keys[c].tile = fr.cascades[c].tile;
        keys[c].column = fr.cascades[c].tile % fr.columns;
        keys[c].row = fr.cascades[c].tile / fr.columns;
        keys[c].raster = resolvedRaster;
        keys[c].hardwareConservative = growsCastersInHardware(resolvedRaster, hardwareConservative);
        keys[c].slopeBias = settings.slopeBias;
        keys[c].cullCasters = settings.cullCasters;
    }
    return keys;
}

std::vector<ShadowTileReason> shadowTilesToDraw(const ShadowAtlasCache* cache, int width, int height, uint64_t casters,
                                                const std::vector<ShadowTileKey>& keys) {
    using Change = ShadowTileChange;
    ShadowTileReason all;
    if (!cache || !cache->depth || cache->width == 0) all = {Change::NothingKept, "nothing kept yet"};
    else if (cache->width != width || cache->height != height) all = {Change::AtlasResized, "atlas size changed"};
    else if (cache->casters != casters) all = {Change::CastersChanged, "casters changed"};
    std::vector<ShadowTileReason> why(keys.size(), all);
    if (!all.kept()) return why;
    for (size_t c = 0; c < keys.size(); ++c) {
        const ShadowTileKey& k = keys[c];
        const size_t tile = size_t(k.tile);
        if (tile >= cache->tiles.size() || !cache->tiles[tile]) {
            why[c] = {Change::TileNotDrawn, "tile not drawn yet"};
            continue;
        }
        const ShadowTileKey& old = *cache->tiles[tile];
        if (old == k) continue;
        if (old.raster != k.raster) why[c] = {Change::RasterChanged, "caster raster changed"};
        else if (old.hardwareConservative != k.hardwareConservative)
            why[c] = {Change::ConservativeRasterChanged,
                      std::string("conservative raster changed to ") + conservativeRasterLabel(k.hardwareConservative)};
        else if (old.slopeBias != k.slopeBias) why[c] = {Change::SlopeBiasChanged, "slope bias changed"};
        else if (old.cullCasters != k.cullCasters) why[c] = {Change::CullingChanged, "caster culling changed"};
        else if (old.tileSize != k.tileSize) why[c] = {Change::TileSizeChanged, "tile size changed"};
        else if (glm::mat3(old.worldToClip) == glm::mat3(k.worldToClip) && old.worldToClip[3].z == k.worldToClip[3].z)
            why[c] = {Change::SquareMoved, "square moved"};  // same light, size and depth range: only the texel-snapped origin
        else {
            // The window-depth and w rows bit for bit: the same sun direction and depth range, so
            // only the square (its size and origin) differs. The text stays what --explain said before.
            bool sameDepth = true;
            for (int i = 0; i < 4; ++i)
                for (int r : {2, 3}) sameDepth &= std::memcmp(&old.worldToClip[i][r], &k.worldToClip[i][r], sizeof(float)) == 0;
            why[c] = {sameDepth ? Change::SquareResized : Change::LightChanged, "light matrix changed"};
        }
    }
    return why;
}

TileRect shadowTileQuarter(int q, int tileSize) {
    const int half = tileSize / 2;
    const int x = (q % 2) * half, y = (q / 2) * half;
    return {x, y, q % 2 ? tileSize - half : half, q / 2 ? tileSize - half : half};
}

std::optional<glm::ivec2> shadowTileScroll(const ShadowTileKey& old, const ShadowTileKey& now) {
    // Everything but the translation's x and y bit for bit: the same rotation, scale and depth
    // range give every caster point the same depth, and the same bias, raster and culling.
    if (old.tileSize != now.tileSize || old.column != now.column || old.row != now.row || old.raster != now.raster ||
        old.hardwareConservative != now.hardwareConservative || old.cullCasters != now.cullCasters ||
        std::memcmp(&old.slopeBias, &now.slopeBias, sizeof old.slopeBias) != 0)
        return std::nullopt;
    const glm::mat3 a(old.worldToClip), b(now.worldToClip);
    const float za = old.worldToClip[3].z, zb = now.worldToClip[3].z, wa = old.worldToClip[3].w, wb = now.worldToClip[3].w;
    if (std::memcmp(&a, &b, sizeof a) != 0 || std::memcmp(&za, &zb, sizeof za) != 0 || std::memcmp(&wa, &wb, sizeof wa) != 0)
        return std::nullopt;
    // A point's window x is (clip x + 1) / 2 * tileSize: a translation change of t moves it t * tileSize / 2 texels.
    glm::ivec2 offset;
    for (int i = 0; i < 2; ++i) {
        const double texels = (double(now.worldToClip[3][i]) - double(old.worldToClip[3][i])) * 0.5 * double(now.tileSize);
        const double whole = std::round(texels);
        if (!(std::abs(texels - whole) <= 0.01) || std::abs(whole) >= double(now.tileSize)) return std::nullopt;
        offset[i] = int(whole);
    }
    if (offset == glm::ivec2(0)) return std::nullopt;  // differing bits but no whole texel: redraw
    const TileRect kept = shadowScrollKeptRect(offset, now.tileSize);
    if (kept.width <= 0 || kept.height <= 0) return std::nullopt;
    return offset;
}

TileRect shadowScrollKeptRect(glm::ivec2 offset, int tileSize) {
    // New texel p holds old texel p - offset; the old tile's texels [margin, tileSize - margin) are
    // trusted along an axis the tile moves along. Along one it does not move, the old border texels
    // stay at the border, where a fresh draw rasterises them the same way: all are kept.
    const int mx = offset.x != 0 ? kShadowScrollMargin : 0, my = offset.y != 0 ? kShadowScrollMargin : 0;
    const int x0 = std::max(0, mx + offset.x), x1 = std::min(tileSize, tileSize - mx + offset.x);
    const int y0 = std::max(0, my + offset.y), y1 = std::min(tileSize, tileSize - my + offset.y);
    return {x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

std::vector<TileRect> shadowScrollRegions(glm::ivec2 offset, int tileSize) {
    const TileRect k = shadowScrollKeptRect(offset, tileSize);
    if (k.width <= 0 || k.height <= 0) return {{0, 0, tileSize, tileSize}};
    std::vector<TileRect> strips;
    // Left and right columns over the whole height, then below and above the kept rectangle between them.
    const TileRect candidates[4] = {{0, 0, k.x, tileSize},
                                    {k.x + k.width, 0, tileSize - (k.x + k.width), tileSize},
                                    {k.x, 0, k.width, k.y},
                                    {k.x, k.y + k.height, k.width, tileSize - (k.y + k.height)}};
    for (const TileRect& r : candidates)
        if (r.width > 0 && r.height > 0) strips.push_back(r);
    return strips;
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
// triangles drawn plainly over it with the depth test, and its alpha-tested casters (MASK, BLEND)
// likewise with `alphaProgram` (the plain program's alpha-tested twin): the compute raster takes the
// opaque casters only.
void drawCascadesByCompute(ShadowMapPass& state, const FrameData& frame, const ShadowFrustum& fr,
                           const std::vector<CasterList>& casters, int width, int height, bool depthZeroToOne,
                           const std::vector<bool>& redraw, GLuint alphaProgram) {
    if (!state.rasterProgram)
        state.rasterProgram = frame.shaders->compute(
            "shadow_raster.comp", std::vector<std::string>{"LP_VERTEX_FLOATS " + std::to_string(sizeof(GpuVertex) / sizeof(float))});
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
    glProgramUniform1i(prog, gl::Uniforms(frame.shaders, prog).location("uTileSize"), fr.tileSize);
    glProgramUniform1i(prog, gl::Uniforms(frame.shaders, prog).location("uDepthZeroToOne"), depthZeroToOne ? 1 : 0);
    glProgramUniform1f(prog, gl::Uniforms(frame.shaders, prog).location("uSlopeBias"), frame.settings->shadows.slopeBias);
    glProgramUniform1f(prog, gl::Uniforms(frame.shaders, prog).location("uLargeTexels"), kComputeRasterMaxTexels);
    if (!state.rasterModel) state.rasterModel = gl::probeRasterInterpolation(*frame.shaders);
    // Edge functions of 32-bit integers: at most 8 sub-texel bits keep uLargeTexels' triangles exact.
    glProgramUniform1i(prog, gl::Uniforms(frame.shaders, prog).location("uSubTexel"), 1 << std::min(state.rasterModel->subpixelBits, 8));
    glProgramUniform1i(prog, gl::Uniforms(frame.shaders, prog).location("uSnappedDepthPlane"), state.rasterModel->fromSnappedVertices);
    const GLint locMvp = gl::Uniforms(frame.shaders, prog).location("uModelToClip");
    const GLint locFirst = gl::Uniforms(frame.shaders, prog).location("uFirstIndex");
    const GLint locCount = gl::Uniforms(frame.shaders, prog).location("uTriangleCount");
    for (size_t c = 0; c < fr.cascades.size(); ++c) {
        if (!redraw[c]) continue;  // kept from an earlier frame (--shadow-cache)
        const glm::ivec2 origin = tileOrigin(fr, c);
        glProgramUniform2i(prog, gl::Uniforms(frame.shaders, prog).location("uTileOrigin"), origin.x, origin.y);
        glProgramUniform1i(prog, gl::Uniforms(frame.shaders, prog).location("uCascade"), GLint(c));
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
        const glm::ivec2 origin = tileOrigin(fr, c);
        glViewport(origin.x, origin.y, fr.tileSize, fr.tileSize);
        glScissor(origin.x, origin.y, fr.tileSize, fr.tileSize);
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
        const glm::ivec2 origin = tileOrigin(fr, c);
        glViewport(origin.x, origin.y, fr.tileSize, fr.tileSize);
        glScissor(origin.x, origin.y, fr.tileSize, fr.tileSize);
        glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(c * sizeof(DrawArraysCommand)));
    }
    // The alpha-tested casters: the plain path's hardware draws, the fragments their alpha drops discarded.
    for (size_t c = 0; c < fr.cascades.size() && alphaProgram; ++c) {
        if (!redraw[c] || casters[c].alphaDraws.empty()) continue;
        const glm::ivec2 origin = tileOrigin(fr, c);
        glViewport(origin.x, origin.y, fr.tileSize, fr.tileSize);
        glScissor(origin.x, origin.y, fr.tileSize, fr.tileSize);
        glUseProgram(alphaProgram);
        drawAlphaCasterList(frame, alphaProgram, fr.cascades[c].worldToClip, casters[c]);
    }
    glDisable(GL_SCISSOR_TEST);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, 0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glBindVertexArray(0);
    glUseProgram(0);
}

// Every cascade's whole tile drawn with its culled casters.
std::vector<ShadowTileWork> wholeTiles(const ShadowFrustum& fr, const std::vector<CasterList>& casters) {
    std::vector<ShadowTileWork> work(fr.cascades.size());
    for (size_t c = 0; c < work.size(); ++c) work[c].regions.push_back({{0, 0, fr.tileSize, fr.tileSize}, casters[c]});
    return work;
}

// Moves the kept part of each scrolled tile (--shadow-scroll) by its offset, within the tile (a copy
// within one texture may not overlap its source): as a memmove, in bands as wide as the shift along
// its larger axis, the band whose destination no later band reads from first (one pass over the
// texels), where that takes at most kShadowScrollMaxBands copies; otherwise out to the scratch tile
// and back (two passes).
void scrollTiles(ShadowMapPass& state, const ShadowFrustum& fr, const std::vector<ShadowTileWork>& work, GLuint depthTexture) {
    for (size_t c = 0; c < work.size(); ++c) {
        if (!work[c].scrolled) continue;
        const glm::ivec2 o = work[c].offset;
        const glm::ivec2 origin = tileOrigin(fr, c);
        const GLint x = origin.x, y = origin.y;
        const TileRect k = shadowScrollKeptRect(o, fr.tileSize);
        auto copy = [&](int dx0, int dy0, int w, int h) {  // the kept texels [dx0, +w) x [dy0, +h), from their old place
            glCopyImageSubData(depthTexture, GL_TEXTURE_2D, 0, x + dx0 - o.x, y + dy0 - o.y, 0, depthTexture, GL_TEXTURE_2D, 0,
                               x + dx0, y + dy0, 0, w, h, 1);
        };
        const bool alongX = std::abs(o.x) >= std::abs(o.y);
        const int shift = alongX ? std::abs(o.x) : std::abs(o.y), length = alongX ? k.width : k.height;
        if ((length + shift - 1) / shift <= kShadowScrollMaxBands) {
            // Content moving towards + goes first at the + end (its sources lie behind it), and the reverse.
            const bool positive = (alongX ? o.x : o.y) > 0;
            const int start = alongX ? k.x : k.y;
            for (int done = 0; done < length; done += shift) {
                const int width = std::min(shift, length - done);
                const int from = positive ? start + length - done - width : start + done;
                if (alongX) copy(from, k.y, width, k.height);
                else copy(k.x, from, k.width, width);
            }
            continue;
        }
        if (!state.scrollScratch || state.scrollScratch.width != fr.tileSize || state.scrollScratch.height != fr.tileSize)
            state.scrollScratch = gl::makeTexture2D(GL_DEPTH_COMPONENT32F, fr.tileSize, fr.tileSize, 1, "shadow_map.scroll_scratch");
        glCopyImageSubData(depthTexture, GL_TEXTURE_2D, 0, x + k.x - o.x, y + k.y - o.y, 0, state.scrollScratch.id(),
                           GL_TEXTURE_2D, 0, 0, 0, 0, k.width, k.height, 1);
        glCopyImageSubData(state.scrollScratch.id(), GL_TEXTURE_2D, 0, 0, 0, 0, depthTexture, GL_TEXTURE_2D, 0, x + k.x,
                           y + k.y, 0, k.width, k.height, 1);
    }
}

// Draws the cascades' casters into the atlas `depthTexture` (width x height) with `raster` (not Auto):
// per cascade, the regions of `work` (each cleared first, then drawn scissored with its casters;
// every tile whole: the whole atlas cleared), after moving scrolled tiles' kept parts; tiles without
// regions are left as they are. Conservative and split grow casters by GL_NV_conservative_raster
// where state.hardwareConservative, else by the geometry shader. The compute raster draws whole
// tiles only (the planner never scrolls for it).
void drawAtlas(ShadowMapPass& state, const FrameData& frame, const ShadowFrustum& fr, const std::vector<ShadowTileWork>& work,
               ShadowSettings::Raster raster, GLuint depthTexture, int width, int height) {
    using Raster = ShadowSettings::Raster;
    std::vector<bool> redraw(work.size());
    std::vector<CasterList> casters(work.size());
    for (size_t c = 0; c < work.size(); ++c) {
        redraw[c] = work[c].drawn();
        if (redraw[c]) casters[c] = work[c].regions.front().casters;
    }
    const bool everyTileWhole = std::all_of(work.begin(), work.end(), [&](const ShadowTileWork& w) {
        return w.regions.size() == 1 && !w.scrolled && w.regions[0].rect.width == fr.tileSize && w.regions[0].rect.height == fr.tileSize;
    });
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
        // The alpha-tested twins, with the same defines and LP_SHADOW_ALPHA_TEST.
        const bool alphaTested = hasAlphaTestedCasters(frame.gpu->casterClusters);
        auto twin = [&](gl::Program& program, bool needed, std::vector<std::string> defines, bool geometryShader) {
            if (!alphaTested || !needed || program) return;
            defines.push_back("LP_SHADOW_ALPHA_TEST");
            program = geometryShader ? frame.shaders->graphics("shadow_depth.vert", "shadow_depth.geom", "shadow_depth.frag", defines)
                                     : frame.shaders->graphics("shadow_depth.vert", "shadow_depth.frag", defines);
        };
        twin(state.hardwareTowardAlphaProgram, hardware && raster == Raster::Conservative, {"LP_SHADOW_HARDWARE_CONSERVATIVE"}, false);
        twin(state.hardwareAwayAlphaProgram, hardware, {"LP_SHADOW_HARDWARE_CONSERVATIVE", "LP_SHADOW_FACES_AWAY"}, false);
        twin(state.alphaProgram, !hardware && raster == Raster::Conservative, {"LP_SHADOW_CONSERVATIVE"}, true);
        twin(state.awayAlphaProgram, !hardware && raster == Raster::Split, {"LP_SHADOW_CONSERVATIVE", "LP_SHADOW_AWAY_ONLY"}, true);
        twin(state.plainAlphaProgram, raster == Raster::Plain || raster == Raster::Split || raster == Raster::Compute, {}, false);
        // A program's alpha-tested twin (0: none, or no alpha-tested casters).
        auto alphaTwin = [&](GLuint prog) -> GLuint {
            if (!alphaTested || !prog) return 0;
            const std::pair<const gl::Program*, const gl::Program*> twins[] = {
                {&state.program, &state.alphaProgram},
                {&state.awayProgram, &state.awayAlphaProgram},
                {&state.plainProgram, &state.plainAlphaProgram},
                {&state.hardwareTowardProgram, &state.hardwareTowardAlphaProgram},
                {&state.hardwareAwayProgram, &state.hardwareAwayAlphaProgram}};
            for (const auto& [opaque, alpha] : twins)
                if (opaque->id() == prog) return alpha->id();
            return 0;
        };
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
        if (everyTileWhole) {
            glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);
        } else {
            scrollTiles(state, fr, work, depthTexture);
            gl::ScopedEnable scissor(GL_SCISSOR_TEST, true);
            for (size_t c = 0; c < fr.cascades.size(); ++c)
                for (const ShadowTileRegion& region : work[c].regions) {
                    const glm::ivec2 origin = tileOrigin(fr, c);
                    glScissor(origin.x + region.rect.x, origin.y + region.rect.y, region.rect.width, region.rect.height);
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
        for (GLuint prog : {conservativeProg, hardwareProgs[0], hardwareProgs[1], alphaTwin(conservativeProg),
                            alphaTwin(hardwareProgs[0]), alphaTwin(hardwareProgs[1])}) {
            if (!prog) continue;
            glProgramUniform1i(prog, gl::Uniforms(frame.shaders, prog).location("uDepthZeroToOne"), clipDepth == GL_ZERO_TO_ONE ? 1 : 0);
            // Slope-scaled bias against acne, for the faces towards the light only (shadow_depth.frag);
            // the constant part is the receiver's (see shadow.glsl).
            glProgramUniform1f(prog, gl::Uniforms(frame.shaders, prog).location("uSlopeBias"), frame.settings->shadows.slopeBias);
        }
        if (raster == Raster::Compute) {
            gl::ScopedEnable scissor(GL_SCISSOR_TEST, false);  // drawCascadesByCompute scissors per tile
            drawCascadesByCompute(state, frame, fr, casters, width, height, clipDepth == GL_ZERO_TO_ONE, redraw,
                                  alphaTested ? state.plainAlphaProgram.id() : 0);
            glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, 0, 0);
            return;
        }
        const GLuint plainProg = raster == Raster::Conservative ? 0 : state.plainProgram.id();
        // Each cascade's fragments stay in its tile whatever a driver's guard band does: a kept
        // neighbour (--shadow-cache) must not receive this frame's casters.
        gl::ScopedEnable scissor(GL_SCISSOR_TEST, true);
        for (size_t c = 0; c < fr.cascades.size(); ++c)
          for (const ShadowTileRegion& region : work[c].regions) {  // none: kept from an earlier frame (--shadow-cache)
            const glm::ivec2 origin = tileOrigin(fr, c);
            const GLint x = origin.x, y = origin.y;
            // The whole tile's viewport (a strip rasterises exactly as the whole tile would), the region's scissor.
            glViewport(x, y, fr.tileSize, fr.tileSize);
            glScissor(x + region.rect.x, y + region.rect.y, region.rect.width, region.rect.height);
            const CasterList& regionCasters = region.casters;
            // Conservative: a face towards the light grown past its edge yields to one covering the
            // texel's centre by a texel's world size in depth (shadow_caster_depth.glsl).
            const float texelDepth = fr.cascades[c].texelWorld / fr.cascades[c].depthRange;
            for (GLuint prog : {conservativeProg, hardwareProgs[0], alphaTwin(conservativeProg), alphaTwin(hardwareProgs[0])})
                if (prog) glProgramUniform1f(prog, gl::Uniforms(frame.shaders, prog).location("uTexelDepth"), texelDepth);
            if (plainProg) {
                // Split: only the faces towards the light (counter-clockwise in the light's window,
                // as shadow_depth.geom's orientation), which need neither growth nor gl_FragDepth.
                glEnable(GL_POLYGON_OFFSET_FILL);
                if (raster == Raster::Split) glEnable(GL_CULL_FACE);
                glCullFace(GL_BACK);
                drawCasters(frame, plainProg, alphaTwin(plainProg), fr.cascades[c].worldToClip, regionCasters);
                glDisable(GL_POLYGON_OFFSET_FILL);
                glDisable(GL_CULL_FACE);
            }
            if (conservativeProg) {
                for (GLuint prog : {conservativeProg, alphaTwin(conservativeProg)})
                    if (prog)
                        glProgramUniform4f(prog, gl::Uniforms(frame.shaders, prog).location("uViewport"), float(x), float(y),
                                           float(fr.tileSize), float(fr.tileSize));
                drawCasters(frame, conservativeProg, alphaTwin(conservativeProg), fr.cascades[c].worldToClip, regionCasters);
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
                    for (GLuint p : {prog, alphaTwin(prog)})
                        if (p)
                            glProgramUniform4f(p, gl::Uniforms(frame.shaders, p).location("uViewport"), float(x), float(y),
                                               float(fr.tileSize), float(fr.tileSize));
                    drawCasters(frame, prog, alphaTwin(prog), fr.cascades[c].worldToClip, regionCasters);
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
constexpr const char* kShadowRasterSection = "shadow_raster";  // GPU key -> raster name
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
    const std::filesystem::path path = measuredCachePath();
    MeasuredSection cache;
    if (!path.empty()) {
        cache = readMeasuredSection(path, kShadowRasterSection);
        if (!cache.warning.empty()) logWarn(cache.warning);
    }
    if (cache.entries.contains(key)) {
        ShadowSettings::Raster cached;
        const nlohmann::json& entry = cache.entries[key];
        if (entry.is_string() && rasterFromName(entry.get<std::string>(), cached)) {
            state.autoRaster = cached;
            state.autoReport = std::string("shadow raster auto: ") + ShadowSettings::rasterName(cached) + " (cached in " +
                               path.string() + ")";
            logInfo(state.autoReport);
            return cached;
        }
        logWarn(path.string() + ": " + kShadowRasterSection + " entry for this GPU is not a shadow raster (" +
                entry.dump() + "); measuring again");
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
                       " conservative raster; " + (path.empty() ? std::string("not cached: no cache folder") : "cached in " + path.string()) + ")";
    logInfo(state.autoReport);
    if (!path.empty()) {
        cache.entries[key] = ShadowSettings::rasterName(state.autoRaster);  // other GPUs' entries kept
        const std::string warning = writeMeasuredSection(path, kShadowRasterSection, cache.entries);
        if (!warning.empty()) logWarn(warning + "; auto measures again next start");
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

namespace {
// The casters that can reach `rect` of a tile drawn with `worldToClip`: culled in the rectangle's own
// clip space (it maps to [-1, 1]), one tile texel of margin along its narrower side (more along the
// other: conservative).
CasterList regionCasters(const std::vector<CasterCluster>& clusters, const FrameData& frame, const glm::mat4& worldToClip,
                         const TileRect& r, int tileSize) {
    const float sx = float(r.width) / float(tileSize), sy = float(r.height) / float(tileSize);
    const float cx = (2.0f * float(r.x) + float(r.width)) / float(tileSize) - 1.0f;
    const float cy = (2.0f * float(r.y) + float(r.height)) / float(tileSize) - 1.0f;
    glm::mat4 toRegion(1.0f);
    toRegion[0][0] = 1.0f / sx;
    toRegion[1][1] = 1.0f / sy;
    toRegion[3][0] = -cx / sx;
    toRegion[3][1] = -cy / sy;
    const float margin = 2.0f / float(tileSize) / std::min(sx, sy);
    return cullCasters(clusters, *frame.scene, toRegion * worldToClip, margin, frame.settings->shadows.cullCasters);
}

// A square drawn for an earlier camera, served from this frame's camera: its eye-space matrix redone.
ShadowCascade servedFromThisCamera(ShadowCascade square, const ShadowCascade& slice, const FrameData& frame) {
    square.eyeToClip = glm::mat4(glm::dmat4(square.worldToClip) * glm::inverse(glm::dmat4(frame.view)));
    square.splitNear = slice.splitNear;
    square.splitFar = slice.splitFar;
    square.tile = slice.tile;
    return square;
}

// This frame's pending-square work of one light (--shadow-redraw-budget).
struct PendingWork {
    bool active = false;
    ShadowPendingTile tile;          // as it will be after this frame
    std::vector<ShadowTileRegion> quarters;  // drawn into the spare tile this frame
    bool completes = false;          // copied over the atlas tile this frame
};
}  // namespace

namespace {
// The suns that cast shadows this frame (every sun with --all-passes).
int castingSuns(const FrameData& frame) {
    int casting = 0;
    for (const auto& l : frameDirectionalLights(frame)) casting += (l.castsShadows || frame.settings->allPasses) ? 1 : 0;
    return casting;
}
}  // namespace

std::string sunShadowSkipReason(const FrameData& frame) {
    const int casting = castingSuns(frame);
    if (casting == 0) return "no directional light casts shadows";
    if (!frame.settings->shadows.enabled) return "shadows are off (--no-shadows)";
    if (casting > kMaxShadowedLights)
        return std::to_string(casting - kMaxShadowedLights) + " shadow-casting lights past the first " +
               std::to_string(kMaxShadowedLights) + " are unshadowed";
    return "";
}

ShadowMaps addShadowMapPasses(fg::FrameGraph& graph, ShadowMapPass& state, const FrameData& frame) {
    ShadowMaps maps;
    const int casting = castingSuns(frame);
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
    // --shadow-redraw-budget: quarter tiles of resized squares left to draw this frame, all suns together.
    const int budget = frame.settings->shadows.redrawBudget;
    // Units left this frame (quarters and scrolls); a pending square keeps one for itself, so scrolls
    // cannot starve it.
    int quartersLeft = budget;
    int scrollUnitsLeft = std::max(0, budget - (state.pending ? 1 : 0));
    uint64_t quartersThisFrame = 0, unitsThisFrame = 0;
    if (state.pending && (!caching || std::find(shadowed.begin(), shadowed.end(), state.pending->light) == shadowed.end()))
        state.pending.reset();
    for (int light : shadowed) {
        LightShadowMap map;
        map.light = light;
        const auto held = state.previousFrusta.find(light);
        map.frustum = fitShadowFrustum(frame, frameDirectionalLights(frame)[size_t(light)].direction,
                                       held == state.previousFrusta.end() ? nullptr : &held->second);
        state.previousFrusta[light] = map.frustum;  // the squares wanted, whatever lags behind them
        ShadowFrustum& fr = map.frustum;
        const std::string name = "shadow_map_" + std::to_string(light);
        // A small scene needs fewer cascades than asked for: say which were dropped and why.
        map.droppedCascades = droppedCascadesReason(fr, frame.settings->shadows.cascades);
        const fg::TextureDesc desc{fr.tileSize * fr.columns, fr.tileSize * fr.rows, GL_DEPTH_COMPONENT32F};
        // --shadow-cache: which tiles the kept atlas already holds (None: kept).
        std::vector<ShadowTileKey> keys = shadowTileKeys(fr, frame.settings->shadows, knownRaster, state.hardwareConservative);
        const auto keptIt = state.atlases.find(light);
        const ShadowAtlasCache* kept = keptIt == state.atlases.end() ? nullptr : &keptIt->second;
        std::vector<ShadowTileReason> why =
            caching ? shadowTilesToDraw(kept, desc.width, desc.height, casterKey, keys)
                    : std::vector<ShadowTileReason>(fr.cascades.size(), {ShadowTileChange::CacheOff, "cache off"});
        if (knownRaster == ShadowSettings::Raster::Auto)
            for (ShadowTileReason& w : why) w = {ShadowTileChange::AutoFirstFrame, "first frame of --shadow-raster auto"};
        // Each cascade's casters, culled to its tile (one texel of margin for the conservative growth),
        // and what its tile gets: nothing (kept), its strips after a scroll, or the whole tile.
        std::vector<CasterList> casters;
        std::vector<ShadowTileWork> work(fr.cascades.size());
        std::vector<std::string> what(fr.cascades.size());
        const bool scrolling = caching && frame.settings->shadows.scroll && knownRaster != ShadowSettings::Raster::Auto &&
                               knownRaster != ShadowSettings::Raster::Compute;
        // Resized squares may lag (keep their previous square) where the kept tile is a valid map of
        // that square and the raster draws parts of tiles; never the last cascade, which serves every
        // depth behind it (a pixel its previous square misses would have no cascade left).
        const bool budgeted = caching && budget > 0 && frame.gpu && knownRaster != ShadowSettings::Raster::Auto &&
                              knownRaster != ShadowSettings::Raster::Compute;
        std::vector<bool> lags(fr.cascades.size(), false), scrollWaits(fr.cascades.size(), false);
        for (size_t c = 0; c < fr.cascades.size(); ++c) {
            const size_t tile = size_t(fr.cascades[c].tile);
            std::optional<glm::ivec2> offset;
            if (scrolling && why[c].change == ShadowTileChange::SquareMoved && kept && tile < kept->tiles.size() && kept->tiles[tile])
                offset = shadowTileScroll(*kept->tiles[tile], keys[c]);
            const bool resized = why[c].change == ShadowTileChange::SquareResized ||
                                 (why[c].change == ShadowTileChange::SquareMoved && !offset);
            const bool canLag = budgeted && c + 1 < fr.cascades.size() && kept && tile < kept->squares.size() &&
                                kept->squares[tile] && kept->tiles[tile];
            // A scroll is one unit of the budget too (its strips cost about a quarter tile's casters);
            // past the budget the square waits on its previous place, as a resized one does.
            if (offset && canLag) {
                if (scrollUnitsLeft > 0 && quartersLeft > 0) {
                    --scrollUnitsLeft;
                    --quartersLeft;
                    ++unitsThisFrame;
                } else {
                    scrollWaits[c] = true;
                }
            }
            lags[c] = canLag && (resized || scrollWaits[c]);
            if (lags[c]) continue;
            if (offset) {
                work[c].scrolled = true;
                work[c].offset = *offset;
                size_t stripTriangles = 0;
                for (const TileRect& r : shadowScrollRegions(*offset, fr.tileSize)) {
                    work[c].regions.push_back({r, regionCasters(clusters, frame, fr.cascades[c].worldToClip, r, fr.tileSize)});
                    stripTriangles += work[c].regions.back().casters.triangles;
                }
                what[c] = "scrolled by (" + std::to_string(offset->x) + ", " + std::to_string(offset->y) + "), strip redrawn (" +
                          std::to_string(work[c].regions.size()) + (work[c].regions.size() == 1 ? " strip, " : " strips, ") +
                          std::to_string(stripTriangles) + " caster triangles drawn)";
            } else if (!why[c].kept()) {
                what[c] = "redrawn (" + why[c].text + ")";
            } else {
                what[c] = "kept (unchanged)";
            }
        }
        // The pending square (one for all suns): carried on while its tile still lags (and nothing
        // it depends on changed), else dropped; a new one started for this light's nearest lagging
        // cascade when none is pending. It may be a square of a few frames ago: once copied over, the
        // cascade scrolls or lags again from it.
        PendingWork pending;
        if (state.pending && state.pending->light == light) {
            for (size_t c = 0; c < fr.cascades.size() && budgeted; ++c)
                if (lags[c] && fr.cascades[c].tile == state.pending->tile) {
                    ShadowTileKey wanted = keys[c];
                    wanted.worldToClip = state.pending->key.worldToClip;
                    if (wanted == state.pending->key) pending = {true, *state.pending, {}, false};
                }
            if (!pending.active) state.pending.reset();
        }
        // The nearest lagging tile first, over all suns (the others' as they last lagged): near
        // cascades are the most visible and the cheapest to draw.
        int nearest = -1;
        for (size_t c = 0; c < fr.cascades.size() && nearest < 0; ++c)
            if (lags[c] && !scrollWaits[c]) nearest = fr.cascades[c].tile;
        if (nearest < 0) state.nearestLagging.erase(light);
        else state.nearestLagging[light] = nearest;
        bool nearerElsewhere = false;
        for (const auto& [other, tile] : state.nearestLagging)
            nearerElsewhere |= other != light && std::find(shadowed.begin(), shadowed.end(), other) != shadowed.end() &&
                               (tile < nearest || (tile == nearest && other < light));
        if (budgeted && !state.pending && nearest >= 0 && !nearerElsewhere)
            for (size_t c = 0; c < fr.cascades.size() && !pending.active; ++c)
                if (lags[c] && !scrollWaits[c]) pending = {true, {light, fr.cascades[c].tile, keys[c], fr.cascades[c], 0}, {}, false};
        if (pending.active) {
            for (int q = 0; q < 4 && quartersLeft > 0; ++q)
                if (!(pending.tile.quartersDrawn & (1u << q))) {
                    const TileRect r = shadowTileQuarter(q, fr.tileSize);
                    pending.quarters.push_back({r, regionCasters(clusters, frame, pending.tile.cascade.worldToClip, r, fr.tileSize)});
                    pending.tile.quartersDrawn |= 1u << q;
                    --quartersLeft;
                    ++quartersThisFrame;
                    ++unitsThisFrame;
                }
            pending.completes = pending.tile.quartersDrawn == 0xfu;
            if (pending.completes) state.pending.reset();
            else state.pending = pending.tile;
        }
        for (size_t c = 0; c < fr.cascades.size(); ++c) {
            if (!lags[c]) continue;
            const size_t tile = size_t(fr.cascades[c].tile);
            const bool isPending = pending.active && pending.tile.tile == fr.cascades[c].tile;
            if (isPending && pending.completes) {
                // The new square is whole in the spare tile: copied over, it serves from this frame on.
                fr.cascades[c] = servedFromThisCamera(pending.tile.cascade, fr.cascades[c], frame);
                keys[c] = pending.tile.key;
                work[c].fromSpare = true;
                what[c] = "redrawn (" + why[c].text + "; drawn a quarter at a time within --shadow-redraw-budget, done)";
                lags[c] = false;
                continue;
            }
            fr.cascades[c] = servedFromThisCamera(*kept->squares[tile], fr.cascades[c], frame);
            keys[c] = *kept->tiles[tile];
            what[c] = "kept its previous square (" + why[c].text + ": " +
                      (scrollWaits[c] ? std::string("its scroll waits for --shadow-redraw-budget")
                       : isPending ? "the new square is drawn a quarter at a time, " +
                                       std::to_string(std::bitset<4>(pending.tile.quartersDrawn).count()) + " of 4 quarters done"
                                 : std::string("waits for --shadow-redraw-budget")) +
                      "; pixels it misses use the next cascade)";
        }
        // Casters of the squares actually drawn (the lagging ones keep their previous square).
        casters.assign(fr.cascades.size(), {});
        for (size_t c = 0; c < fr.cascades.size(); ++c) {
            const glm::mat4& worldToClip = fr.cascades[c].worldToClip;
            casters[c] = cullCasters(clusters, *frame.scene, worldToClip, 2.0f / float(fr.tileSize),
                                     frame.settings->shadows.cullCasters);
            if (!why[c].kept() && !work[c].scrolled && !work[c].fromSpare && !lags[c])
                work[c].regions.push_back({{0, 0, fr.tileSize, fr.tileSize}, casters[c]});
            const CasterList& l = casters[c];
            graph.notePass(name, "cascade " + std::to_string(c) + ": " + std::to_string(l.draws.size() + l.alphaDraws.size()) +
                                     " draws, " + std::to_string(l.clusters) + " of " + std::to_string(clusters.size()) +
                                     " clusters, " + std::to_string(l.triangles) + " of " + std::to_string(sceneTriangles) +
                                     " triangles" +
                                     (l.alphaTriangles ? ", " + std::to_string(l.alphaTriangles) + " alpha-tested" : "") + " (" +
                                     rasterNote +
                                     (frame.settings->shadows.cullCasters ? "" : ", culling off") + "); " + what[c]);
            if (c < size_t(kMaxShadowCascades) && lags[c]) ++state.cacheStats.laggingPerCascade[c];
            state.cacheStats.lagging += lags[c] ? 1 : 0;
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
                readPosedVertices(b, frame);
            },
            [s, frame, fr, casters, caching, light, keys, work, casterKey, pending](const Data& out, const fg::PassResources& res) {
                const fg::TextureDesc& d = res.desc(out.depth);
                const GLuint texture = res.texture(out.depth);
                ShadowSettings::Raster raster = frame.settings->shadows.raster;
                const std::vector<ShadowTileWork> everyTile = wholeTiles(fr, casters);
                if (raster == ShadowSettings::Raster::Auto)
                    raster = resolveAutoRaster(*s, [&](ShadowSettings::Raster r) {
                        drawAtlas(*s, frame, fr, everyTile, r, texture, d.width, d.height);
                    });
                s->atlasMarked = atlasIsMarked(raster);
                std::vector<ShadowTileWork> atlasWork = work;
                for (ShadowTileWork& w : atlasWork) w.fromSpare = false;  // copied below, after the spare is drawn
                drawAtlas(*s, frame, fr, atlasWork, raster, texture, d.width, d.height);
                ShadowAtlasCache* a = caching ? &s->atlases[light] : nullptr;
                if (a && pending.active && !pending.quarters.empty()) {
                    // The pending square's quarters into the spare atlas, at its tile's place.
                    if (!s->spareAtlas || s->spareAtlas.width != d.width || s->spareAtlas.height != d.height)
                        s->spareAtlas = gl::makeTexture2D(GL_DEPTH_COMPONENT32F, d.width, d.height, 1, "shadow_map.spare_atlas");
                    ShadowFrustum one = fr;
                    one.cascades = {pending.tile.cascade};
                    std::vector<ShadowTileWork> quarterWork(1);
                    quarterWork[0].regions = pending.quarters;
                    drawAtlas(*s, frame, one, quarterWork, raster, s->spareAtlas.id(), d.width, d.height);
                }
                for (size_t c = 0; c < work.size(); ++c)
                    if (a && work[c].fromSpare) {
                        const glm::ivec2 origin = tileOrigin(fr, c);
                        const GLint x = origin.x, y = origin.y;
                        glCopyImageSubData(s->spareAtlas.id(), GL_TEXTURE_2D, 0, x, y, 0, texture, GL_TEXTURE_2D, 0, x, y, 0,
                                           fr.tileSize, fr.tileSize, 1);
                    }
                // Counted: drawn whole, scrolled, completed from the spare tile (its quarters were
                // counted as drawn), or kept (lagging ones too).
                size_t drawn = 0, wholeDrawn = 0, completed = 0;
                for (size_t c = 0; c < work.size(); ++c) {
                    drawn += work[c].drawn() ? 1 : 0;
                    wholeDrawn += !work[c].regions.empty() && !work[c].scrolled ? 1 : 0;
                    completed += work[c].fromSpare ? 1 : 0;
                    if (c >= size_t(kMaxShadowCascades)) continue;
                    ++(work[c].scrolled             ? s->cacheStats.scrolledPerCascade[c]
                       : work[c].fromSpare          ? s->cacheStats.completedPerCascade[c]
                       : !work[c].regions.empty()   ? s->cacheStats.drawnPerCascade[c]
                                                    : s->cacheStats.keptPerCascade[c]);
                }
                s->cacheStats.drawn += wholeDrawn;
                s->cacheStats.completed += completed;
                s->cacheStats.scrolled += drawn - wholeDrawn - completed;
                s->cacheStats.kept += work.size() - drawn;
                if (!a) return;
                // What the tiles now hold. A new caster set or a whole-atlas clear (every tile
                // drawn whole) leaves tiles past this frame's cascades unknown.
                if (a->casters != casterKey || wholeDrawn == work.size()) {
                    a->tiles.assign(a->tiles.size(), std::nullopt);
                    a->squares.assign(a->squares.size(), std::nullopt);
                }
                a->casters = casterKey;
                const size_t tiles = size_t(fr.columns * fr.rows);
                if (a->tiles.size() < tiles) a->tiles.resize(tiles);
                if (a->squares.size() < tiles) a->squares.resize(tiles);
                for (size_t c = 0; c < keys.size(); ++c)
                    if (work[c].drawn()) {
                        const size_t tile = size_t(fr.cascades[c].tile);
                        a->tiles[tile] = keys[c];
                        a->tiles[tile]->raster = raster;
                        a->tiles[tile]->hardwareConservative = growsCastersInHardware(raster, s->hardwareConservative);
                        a->squares[tile] = fr.cascades[c];
                    }
            });
        map.depth = data.depth;
        map.marked = &state.atlasMarked;
        maps.push_back(std::move(map));
    }
    state.cacheStats.quarters += quartersThisFrame;
    state.cacheStats.mostBudgetUnitsInAFrame = std::max(state.cacheStats.mostBudgetUnitsInAFrame, unitsThisFrame);
    ++state.cacheStats.frames;
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

namespace {
// The uniforms of common/shadow_alpha.glsl in an LP_SHADOW_ALPHA_TEST program.
struct ShadowAlphaUniforms {
    GLint modelToClip, opacity, hasDiffuseMap, secondUvMaps, alphaCutoff, alphaHashed;
    explicit ShadowAlphaUniforms(const gl::Uniforms& u) {
        auto loc = [&u](const char* name) { return u.location(name); };
        modelToClip = loc("uModelToClip"); opacity = loc("uOpacity"); hasDiffuseMap = loc("uHasDiffuseMap");
        secondUvMaps = loc("uSecondUvMaps"); alphaCutoff = loc("uAlphaCutoff"); alphaHashed = loc("uAlphaHashed");
    }
    void set(GLuint prog, const GpuMaterial& m) const {
        glProgramUniform1f(prog, opacity, m.opacity);
        glProgramUniform1i(prog, hasDiffuseMap, m.diffuseMap != 0);
        glProgramUniform1ui(prog, secondUvMaps, m.secondUvMaps);
        glProgramUniform1f(prog, alphaCutoff, m.alphaCutoff);
        glProgramUniform1i(prog, alphaHashed, m.alphaBlend);  // BLEND and MTL d < 1: hashed; MASK: the cutoff
        glBindTextureUnit(0, m.diffuseMap);  // LP_MATERIAL_BIND_DIFFUSE (common/material.glsl)
    }
};
}  // namespace

void drawAlphaCasterList(const FrameData& frame, GLuint prog, const glm::mat4& worldToClip, const CasterList& casters) {
    if (casters.alphaDraws.empty()) return;
    const ShadowAlphaUniforms u(gl::Uniforms(frame.shaders, prog));
    int boundModel = -1, boundMaterial = -1;
    for (const CasterDraw& draw : casters.alphaDraws) {
        if (draw.model < 0 || size_t(draw.model) >= frame.gpu->meshes.size()) continue;
        if (draw.material < 0 || size_t(draw.material) >= frame.gpu->materials.size()) continue;
        const GpuMesh& mesh = frame.gpu->meshes[size_t(draw.model)];
        if (draw.model != boundModel) {
            const glm::mat4 mvp = worldToClip * mesh.model;
            glProgramUniformMatrix4fv(prog, u.modelToClip, 1, GL_FALSE, glm::value_ptr(mvp));
            glBindVertexArray(mesh.vao.id());
            boundModel = draw.model;
        }
        if (draw.material != boundMaterial) {
            u.set(prog, frame.gpu->materials[size_t(draw.material)]);
            boundMaterial = draw.material;
        }
        glDrawElements(GL_TRIANGLES, GLsizei(draw.indexCount), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(size_t(draw.firstIndex) * sizeof(uint32_t)));
    }
    glBindTextureUnit(0, 0);
}

void drawCasters(const FrameData& frame, GLuint opaque, GLuint alphaTested, const glm::mat4& worldToClip,
                 const CasterList& casters) {
    if (!casters.draws.empty()) {
        glUseProgram(opaque);
        drawCasterList(frame, opaque, gl::Uniforms(frame.shaders, opaque).location("uModelToClip"), worldToClip, casters);
    }
    if (alphaTested && !casters.alphaDraws.empty()) {
        glUseProgram(alphaTested);
        drawAlphaCasterList(frame, alphaTested, worldToClip, casters);
    }
}

}  // namespace lp

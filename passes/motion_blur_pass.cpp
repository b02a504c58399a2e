#include "passes/motion_blur_pass.hpp"

#include <algorithm>
#include <cmath>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/render/local_lights.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/gl/uniforms.hpp"

namespace lp {

namespace {
struct TileData {
    fg::ResourceId velocity, tiles;
};
struct GatherData {
    fg::ResourceId source, velocity, depth, neighbors, hdr;
};
}  // namespace

namespace {
// Whether light globes are drawn and one of their lights is elsewhere than at the previous frame's time.
bool globesMoved(const FrameData& frame) {
    const LocalLightSettings& s = frame.settings->localLights;
    if (!s.globes.value_or(frame.scene->lightGlobes) || frame.time == frame.previousTime) return false;
    const std::shared_ptr<const std::vector<PointLight>> frameLights = frameLocalLights(frame);
    const std::vector<PointLight>& now = *frameLights;
    const std::vector<PointLight> before = localLightsForFrame(*frame.scene, s, frame.previousTime);
    for (size_t i = 0; i < now.size() && i < before.size(); ++i)
        if (now[i].position != before[i].position) return true;
    return false;
}
// Whether an animated model puts some vertex elsewhere than at the previous frame's time.
bool modelsMoved(const FrameData& frame) {
    if (frame.time == frame.previousTime) return false;
    if (frame.gpu) return frame.gpu->animatedMotion;  // what SceneGpu::pose found
    for (const ModelInstance& m : frame.scene->models)  // 'lightpass graph': nothing is posed
        if (m.movesBetween(frame.previousTime, frame.time)) return true;
    return false;
}
}  // namespace

int motionBlurTileSize(int renderHeight) { return std::max(8, int(std::lround(renderHeight / 36.0))); }

std::string motionBlurSkipReason(const FrameData& frame) {
    const MotionBlurSettings& s = frame.settings->motionBlur;
    if (!s.enabled) return "motion blur is off (--motion-blur)";
    if (!frame.hasPrevious) return "no previous frame (first frame or a camera cut): nothing moves";
    // The camera, the globes of orbiting lights and animated models move pixels.
    if (frame.previousViewProjection == frame.unjitteredProjection * frame.view && !globesMoved(frame) && !modelsMoved(frame))
        return "the camera did not move since the previous frame and no light globe or animated model moved: nothing moves";
    return "";
}

fg::ResourceId addMotionBlurPasses(fg::FrameGraph& graph, MotionBlurPass& state, const FrameData& frame,
                                   const GBuffer& gbuffer, fg::ResourceId hdr) {
    const int k = motionBlurTileSize(frame.height);
    const int tilesX = (frame.width + k - 1) / k, tilesY = (frame.height + k - 1) / k;
    const MotionBlurSettings settings = frame.settings->motionBlur;
    constexpr fg::Usage sampled = fg::Usage::Sampled, store = fg::Usage::ImageStore;

    const TileData& tiles = graph.addPass<TileData>(
        "motion_blur_tiles", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, TileData& d) {
            d.velocity = b.read(gbuffer.velocity, sampled);
            d.tiles = b.create("motion_blur.tiles", {tilesX, tilesY, GL_RG16F}, store);
        },
        [&state, frame, k, tilesX, tilesY, settings](const TileData& d, const fg::PassResources& res) {
            if (!state.tiles) state.tiles = frame.shaders->compute("motion_blur_tiles.comp");
            const GLuint prog = state.tiles.id();
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uTileSize", k);
            u.set("uShutter", settings.shutter);
            glBindTextureUnit(0, res.texture(d.velocity));
            glBindImageTexture(0, res.texture(d.tiles), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
            glUseProgram(prog);
            glDispatchCompute(GLuint(tilesX), GLuint(tilesY), 1);  // one work group per tile
            glUseProgram(0);
            glBindTextureUnit(0, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
        });
    const fg::ResourceId tileMax = tiles.tiles;

    const TileData& neighbors = graph.addPass<TileData>(
        "motion_blur_neighbors", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, TileData& d) {
            d.velocity = b.read(tileMax, sampled);
            d.tiles = b.create("motion_blur.neighbors", {tilesX, tilesY, GL_RG16F}, store);
        },
        [&state, frame, tilesX, tilesY](const TileData& d, const fg::PassResources& res) {
            if (!state.neighbors) state.neighbors = frame.shaders->compute("motion_blur_neighbors.comp");
            glBindTextureUnit(0, res.texture(d.velocity));
            glBindImageTexture(0, res.texture(d.tiles), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
            glUseProgram(state.neighbors.id());
            gl::dispatch2D(tilesX, tilesY);
            glUseProgram(0);
            glBindTextureUnit(0, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
        });
    const fg::ResourceId neighborMax = neighbors.tiles;

    const GatherData& gather = graph.addPass<GatherData>(
        "motion_blur", fg::PassKind::Compute,
        // The gather reads around each pixel, so it reads a copy of the HDR buffer and writes the
        // buffer itself: switched off (--disable-pass motion_blur), the frame passes through unblurred.
        [&](fg::PassBuilder& b, GatherData& d) {
            d.velocity = b.read(gbuffer.velocity, sampled);
            d.depth = b.read(gbuffer.depth, sampled);
            d.neighbors = b.read(neighborMax, sampled);
            d.source = b.create("motion_blur.source", {frame.width, frame.height, GL_RGBA16F},
                                fg::Usage::Transfer | sampled);
            d.hdr = b.write(hdr, fg::Usage::Transfer | store);
        },
        [&state, frame, k, settings](const GatherData& d, const fg::PassResources& res) {
            if (!state.gather) state.gather = frame.shaders->compute("motion_blur.comp");
            const GLuint prog = state.gather.id();
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uTileSize", k);
            u.set("uSamples", settings.samples);
            u.set("uShutter", settings.shutter);
            u.set("uNearFar", glm::vec2(frame.nearPlane, frame.farPlane));
            u.set("uReversedZ", frame.settings->gbuffer.position == GBufferPositionMode::ReversedZ);
            glCopyImageSubData(res.texture(d.hdr), GL_TEXTURE_2D, 0, 0, 0, 0, res.texture(d.source), GL_TEXTURE_2D, 0,
                               0, 0, 0, frame.width, frame.height, 1);
            glBindTextureUnit(0, res.texture(d.source));
            glBindTextureUnit(1, res.texture(d.velocity));
            glBindTextureUnit(2, res.texture(d.depth));
            glBindTextureUnit(3, res.texture(d.neighbors));
            glBindImageTexture(0, res.texture(d.hdr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            glUseProgram(prog);
            gl::dispatch2D(frame.width, frame.height);
            glUseProgram(0);
            for (GLuint u = 0; u < 4; ++u) glBindTextureUnit(u, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        });
    return gather.hdr;
}

}  // namespace lp

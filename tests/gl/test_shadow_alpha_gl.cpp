// Alpha in the shadow maps (docs/shadows.md, "Alpha in shadows"): a MASK card's shadow is the shadow
// of a mesh of just its opaque texels, under the sun (every caster raster) and a spot; a BLEND card
// casts by its opacity (1: as opaque, 0: nothing, 0.5: half the light on average, hashed), the same
// every frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/graph/texture_pool.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/renderer.hpp"
#include "passes/shadow_map_pass.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/render_fixture.hpp"

using namespace lp;

namespace {

constexpr int kW = 128, kH = 96;
constexpr int kCardTexels = 8;        // the alpha texture's side
constexpr float kCardSide = 2.0f;     // the card: a 2 m square at y = 1
constexpr float kCardTexel = kCardSide / float(kCardTexels);

// The card texture's opaque texels: an annulus about the centre (symmetric under flips of either
// axis, so which way the loader orders rows does not matter).
bool opaqueTexel(int i, int j) {
    const float x = float(i) + 0.5f - 0.5f * kCardTexels, y = float(j) + 0.5f - 0.5f * kCardTexels;
    const float r2 = x * x + y * y;
    return r2 > 2.0f && r2 < 12.0f;
}

// White, alpha 255 on the opaque texels and 0 elsewhere, or `alpha` everywhere (alpha >= 0).
TextureRef cardTexture(int alpha = -1) {
    Image8 img;
    img.width = img.height = kCardTexels;
    img.rgba.assign(size_t(kCardTexels * kCardTexels * 4), 255);
    for (int j = 0; j < kCardTexels; ++j)
        for (int i = 0; i < kCardTexels; ++i)
            img.rgba[size_t(j * kCardTexels + i) * 4 + 3] = uint8_t(alpha >= 0 ? alpha : opaqueTexel(i, j) ? 255 : 0);
    TextureRef t;
    t.encoded = std::make_shared<const std::string>(encodePng(img));
    t.key = "shadow-alpha-card-" + std::to_string(alpha);
    t.sampler.magFilter = 9728;  // GL_NEAREST: the opaque set's edges are the texels' edges
    t.sampler.minFilter = 9728;
    return t;
}

glm::mat4 cardTransform() {
    return glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.0f)) *
           glm::scale(glm::mat4(1.0f), glm::vec3(kCardSide, 1.0f, kCardSide));
}

// The card: makePlane's unit square (uv u = x + 0.5, v = 0.5 - z) with `mat`.
ModelInstance card(Material mat) {
    ModelInstance m;
    m.name = "card";
    m.mesh = makePlane(1.0f, 1);
    mat.diffuse = glm::vec3(0.6f);
    m.mesh.materials = {mat};
    m.transform = cardTransform();
    return m;
}

// One opaque quad per opaque texel of the card, where the card has it.
ModelInstance opaqueTexelsMesh() {
    ModelInstance m;
    m.name = "opaque_texels";
    for (int j = 0; j < kCardTexels; ++j)
        for (int i = 0; i < kCardTexels; ++i) {
            if (!opaqueTexel(i, j)) continue;
            const uint32_t base = uint32_t(m.mesh.vertices.size());
            for (int c = 0; c < 4; ++c) {
                Vertex v;
                const float u = float(i + (c & 1)) / kCardTexels, w = float(j + (c >> 1)) / kCardTexels;
                v.position = glm::vec3(u - 0.5f, 0.0f, w - 0.5f);
                v.normal = glm::vec3(0, 1, 0);
                v.uv = glm::vec2(u, w);
                v.tangent = glm::vec4(1, 0, 0, 1);
                m.mesh.vertices.push_back(v);
            }
            m.mesh.indices.insert(m.mesh.indices.end(), {base, base + 2, base + 1, base + 1, base + 2, base + 3});
        }
    m.mesh.subMeshes = {SubMesh{0, uint32_t(m.mesh.indices.size()), 0}};
    Material mat;
    mat.diffuse = glm::vec3(0.6f);
    m.mesh.materials = {mat};
    m.mesh.boundsMin = glm::vec3(-0.5f, 0.0f, -0.5f);
    m.mesh.boundsMax = glm::vec3(0.5f, 0.0f, 0.5f);
    m.transform = cardTransform();
    return m;
}

// The sun's direction: the card's shadow falls 0.8 m to -x and 1.5 m towards the camera, where the
// card hides none of it.
const glm::vec3 kSunDirection(-0.8f, -1.0f, 1.5f);
// The spot: 3 m up behind the card, pointing at its shadow's centre (0, 0, 1.25).
const glm::vec3 kSpotPosition(0.0f, 3.0f, -2.5f);

// A 10 m ground and the card's place lit by the sun, or by the spot (no sun); no ambient, so a
// shadowed ground pixel is black.
Scene groundScene(bool spot) {
    Scene s;
    ModelInstance ground;
    ground.name = "ground";
    ground.mesh = makePlane(1.0f, 4);
    ground.mesh.materials[0].diffuse = glm::vec3(0.5f);
    ground.transform = glm::scale(glm::mat4(1.0f), glm::vec3(10.0f));
    s.models.push_back(std::move(ground));
    if (spot) {
        PointLight l;
        l.position = kSpotPosition;
        l.intensity = 40.0f;
        l.range = 12.0f;
        SpotCone cone;
        cone.direction = glm::normalize(glm::vec3(0.0f, 0.0f, 1.25f) - kSpotPosition);
        cone.innerDegrees = 39.0f;
        cone.outerDegrees = 40.0f;
        l.spot = cone;
        l.castsShadow = true;
        s.pointLights.push_back(l);
    } else {
        DirectionalLight sun;
        sun.direction = glm::normalize(kSunDirection);
        sun.intensity = 3.0f;
        sun.castsShadows = true;
        s.directionalLights.push_back(sun);
    }
    s.ambient = glm::vec3(0.0f);
    s.camera.position = glm::vec3(0.0f, 7.0f, 4.0f);
    s.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
    s.camera.fovYDegrees = 55.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 40.0f;
    return s;
}

RenderSettings alphaSettings(ShadowSettings::Raster raster = ShadowSettings::Raster::Conservative) {
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;
    settings.autoExposure = false;
    settings.width = kW;
    settings.height = kH;
    settings.shadows.size = 1024;
    settings.shadows.filter = ShadowSettings::Filter::Pcf3x3;
    settings.shadows.raster = raster;
    settings.shadows.cache = false;
    return settings;
}

struct GroundPixel {
    int x, y;
    glm::dvec3 card;  // where the light's ray to the ground point crosses the card's plane (y = 1)
};

// The ground pixels that see the ground directly (not the card's square) and get light without the
// card, with the card-plane point of the ray from their ground point to the light.
std::vector<GroundPixel> groundPixels(const Scene& s, const ImageF& unshadowed) {
    std::vector<GroundPixel> out;
    const glm::dmat4 inv =
        glm::inverse(glm::dmat4(s.camera.projection(float(kW) / float(kH))) * glm::dmat4(s.camera.view()));
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const double nx = (x + 0.5) / kW * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / kH * 2.0;
            glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
            const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
            if (d.y >= 0.0) continue;
            const glm::dvec3 atCard = o + d * ((1.0 - o.y) / d.y);
            if (std::abs(atCard.x) <= 1.01 && std::abs(atCard.z) <= 1.01) continue;  // sees the card's square
            const glm::dvec3 p = o + d * (-o.y / d.y);
            if (std::abs(p.x) > 4.5 || std::abs(p.z) > 4.5) continue;
            if (unshadowed.rgba[(size_t(y) * kW + x) * 4 + 1] < 1e-3f) continue;  // outside the spot's cone
            glm::dvec3 q;
            if (!s.pointLights.empty()) {
                const glm::dvec3 l(s.pointLights[0].position);
                q = p + (l - p) * (1.0 / l.y);
            } else {
                const glm::dvec3 toLight = -glm::normalize(glm::dvec3(s.directionalLights[0].direction));
                q = p + toLight * (1.0 / toLight.y);
            }
            out.push_back({x, y, q});
        }
    return out;
}

// Distance (m, in the card's plane) from card-plane point q to the edge of the card's opaque texel
// set: to the nearest texel (or the outside) whose state differs from q's.
double opaqueEdgeDistance(glm::dvec3 q) {
    const double s = (q.x / kCardSide + 0.5) * kCardTexels, t = (q.z / kCardSide + 0.5) * kCardTexels;
    auto state = [](int i, int j) { return i >= 0 && j >= 0 && i < kCardTexels && j < kCardTexels && opaqueTexel(i, j); };
    const bool here = state(int(std::floor(s)), int(std::floor(t)));
    double best = 1e9;
    for (int j = -1; j <= kCardTexels; ++j)
        for (int i = -1; i <= kCardTexels; ++i) {
            if (state(i, j) == here) continue;
            const double dx = std::max({double(i) - s, 0.0, s - double(i + 1)});
            const double dy = std::max({double(j) - t, 0.0, t - double(j + 1)});
            best = std::min(best, std::hypot(dx, dy));
        }
    return best * kCardTexel;
}

// The fraction of the light each ground pixel gets (the render over the unshadowed render's green).
double lightFraction(const ImageF& img, const ImageF& unshadowed, const GroundPixel& p) {
    const size_t i = (size_t(p.y) * kW + p.x) * 4 + 1;
    return double(img.rgba[i]) / double(unshadowed.rgba[i]);
}

// The shadowed ground pixels (under half the light) of `got` and `want` agree everywhere farther
// than `margin` (m, in the card's plane) from the edge of the opaque texels; the first pixel that
// does not is named. At least `minEach` pixels on each side (in shadow, lit under the card's holes
// and around it) were checked, so the test can fail.
void expectSameShadow(const ImageF& got, const ImageF& want, const ImageF& unshadowed, const std::vector<GroundPixel>& pixels,
                      double margin, const std::string& what) {
    int shadowed = 0, litUnderCard = 0, differing = 0;
    std::string first;
    for (const GroundPixel& p : pixels) {
        if (opaqueEdgeDistance(p.card) < margin) continue;
        const bool g = lightFraction(got, unshadowed, p) < 0.5, w = lightFraction(want, unshadowed, p) < 0.5;
        shadowed += w ? 1 : 0;
        litUnderCard += !w && std::abs(p.card.x) < 1.0 && std::abs(p.card.z) < 1.0 ? 1 : 0;
        if (g != w && differing++ == 0)
            first = "pixel (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ") light fraction " +
                    std::to_string(lightFraction(got, unshadowed, p)) + ", reference " +
                    std::to_string(lightFraction(want, unshadowed, p)) + ", card-plane point (" + std::to_string(p.card.x) +
                    ", " + std::to_string(p.card.z) + ")";
    }
    EXPECT_EQ(differing, 0) << what << ": " << differing << " pixels differ; first " << first;
    EXPECT_GT(shadowed, 100) << what;
    EXPECT_GT(litUnderCard, 40) << what << " (the holes of the card)";
}

Material maskMaterial() {
    Material m;
    m.alphaMode = AlphaMode::Mask;
    m.alphaCutoff = 0.5f;
    m.diffuseMap = cardTexture();
    return m;
}

Material blendMaterial(int textureAlpha, float opacity) {
    Material m;
    m.alphaMode = AlphaMode::Blend;
    m.opacity = opacity;
    if (textureAlpha >= 0) m.diffuseMap = cardTexture(textureAlpha);
    return m;
}

}  // namespace

// Under the sun, for every caster raster: the MASK card's shadow is the opaque texels' shadow.
// Margin in the card's plane, as ShadowRender.OccluderShadowMatchesGeometry*: the PCF radius (2
// shadow texels) plus 1.5 texels of raster growth and rounding, stretched by 1 / cos(theta) on a
// horizontal plane, plus the receiver's normal offset (1 texel x tan(theta)). The whole card
// shadowing would fail in the card's holes.
TEST(ShadowAlpha, MaskCardUnderTheSunShadowsLikeItsOpaqueTexels) {
    Scene bare = groundScene(false);
    const ImageF unshadowed = test::renderHdr(bare, alphaSettings());
    const std::vector<GroundPixel> pixels = groundPixels(bare, unshadowed);
    for (ShadowSettings::Raster raster : {ShadowSettings::Raster::Conservative, ShadowSettings::Raster::Plain,
                                          ShadowSettings::Raster::Split, ShadowSettings::Raster::Compute}) {
        const RenderSettings settings = alphaSettings(raster);
        Scene masked = bare, reference = bare;
        masked.models.push_back(card(maskMaterial()));
        reference.models.push_back(opaqueTexelsMesh());
        const ImageF got = test::renderHdr(masked, settings), want = test::renderHdr(reference, settings);
        // A cascade's square is at most the scene's light-space extent (the 10 m ground's diagonal,
        // 14.1 m) grown by the origin step (1/16): at most 16 m over 1024 texels.
        const double texel = 16.0 / 1024.0;
        const double cosTheta = -double(glm::normalize(kSunDirection).y), tanTheta = std::sqrt(1.0 - cosTheta * cosTheta) / cosTheta;
        expectSameShadow(got, want, unshadowed, pixels, (2.0 + 1.5) * texel / cosTheta + texel * tanTheta,
                         std::string("MASK card, raster ") + ShadowSettings::rasterName(raster));
    }
}

TEST(ShadowAlpha, MaskCardUnderASpotShadowsLikeItsOpaqueTexels) {
    Scene bare = groundScene(true);
    const RenderSettings settings = alphaSettings();
    const ImageF unshadowed = test::renderHdr(bare, settings);
    const std::vector<GroundPixel> pixels = groundPixels(bare, unshadowed);
    Scene masked = bare, reference = bare;
    masked.models.push_back(card(maskMaterial()));
    reference.models.push_back(opaqueTexelsMesh());
    const ImageF got = test::renderHdr(masked, settings), want = test::renderHdr(reference, settings);
    // The spot's tile (512 texels over an 82 degree cone) at the card's farthest corner (3.9 m from
    // the light), seen at up to 60 degrees from the card's normal (x 2 in its plane).
    const double texel = 2.0 * std::tan(glm::radians(41.0)) * 3.9 / 512.0 * 2.0;
    expectSameShadow(got, want, unshadowed, pixels, (2.0 + 1.5 + 1.0) * texel, "MASK card, spot");
}

// BLEND by opacity: a texture of alpha 1 (the hashed path, not the opaque one) shadows exactly as
// the opaque card, alpha 0 casts nothing, for the sun (conservative and plain rasters) and the spot.
TEST(ShadowAlpha, BlendCardAtOpacityOneShadowsAsOpaqueAndAtZeroCastsNothing) {
    for (bool spot : {false, true})
        for (ShadowSettings::Raster raster : {ShadowSettings::Raster::Conservative, ShadowSettings::Raster::Plain}) {
            if (spot && raster != ShadowSettings::Raster::Conservative) continue;  // spots draw plainly anyway
            const std::string what = std::string(spot ? "spot" : "sun") + ", raster " + ShadowSettings::rasterName(raster);
            const RenderSettings settings = alphaSettings(raster);
            Scene bare = groundScene(spot);
            const ImageF unshadowed = test::renderHdr(bare, settings);
            const std::vector<GroundPixel> pixels = groundPixels(bare, unshadowed);
            Scene full = bare, none = bare, opaque = bare;
            full.models.push_back(card(blendMaterial(255, 1.0f)));
            none.models.push_back(card(blendMaterial(0, 1.0f)));
            opaque.models.push_back(card(Material{}));
            const ImageF fullImg = test::renderHdr(full, settings), noneImg = test::renderHdr(none, settings),
                         opaqueImg = test::renderHdr(opaque, settings);
            int shadowed = 0;
            for (const GroundPixel& p : pixels) {
                const double f = lightFraction(fullImg, unshadowed, p), o = lightFraction(opaqueImg, unshadowed, p);
                const double n = lightFraction(noneImg, unshadowed, p);
                ASSERT_NEAR(f, o, 1e-5) << what << ": BLEND alpha 1 against opaque at pixel (" << p.x << ", " << p.y << ")";
                ASSERT_NEAR(n, 1.0, 1e-5) << what << ": BLEND alpha 0 shadows pixel (" << p.x << ", " << p.y << ")";
                shadowed += o < 0.5 ? 1 : 0;
            }
            EXPECT_GT(shadowed, 300) << what;
        }
}

// BLEND at opacity 0.5 (no texture: as an MTL d 0.5 material): the hashed test keeps each cell of
// about a shadow texel with probability 0.5, independently, so over the card's shadow the light's
// mean fraction is 0.5, within 5 standard errors of the mean: the pixels' standard deviation over
// sqrt(n) (pixels 5+ cm apart on the ground read different cells of 1-3 cm, so they are
// independent; a 3x3 PCF average of such cells varies by at most 0.5). Every frame draws the same
// shadow (bit for bit).
TEST(ShadowAlpha, BlendCardAtHalfOpacityLetsHalfTheLightThroughOnAverage) {
    for (bool spot : {false, true}) {
        const RenderSettings settings = alphaSettings();
        Scene bare = groundScene(spot);
        const ImageF unshadowed = test::renderHdr(bare, settings);
        const std::vector<GroundPixel> pixels = groundPixels(bare, unshadowed);
        Scene half = bare;
        half.models.push_back(card(blendMaterial(-1, 0.5f)));
        const ImageF img = test::renderHdr(half, settings);
        double sum = 0.0, sumSquares = 0.0;
        int n = 0;
        for (const GroundPixel& p : pixels) {
            // Inside the card's shadow, away from its outline by the filter's reach.
            if (std::abs(p.card.x) > 0.85 || std::abs(p.card.z) > 0.85) continue;
            const double f = lightFraction(img, unshadowed, p);
            sum += f;
            sumSquares += f * f;
            ++n;
        }
        ASSERT_GT(n, 200) << (spot ? "spot" : "sun");
        const double mean = sum / n, spread = std::sqrt(std::max(sumSquares / n - mean * mean, 0.0));
        const double bound = 5.0 * spread / std::sqrt(double(n));
        std::printf("BLEND 0.5 under the %s: mean light fraction %.4f over %d pixels (bound %.4f), standard deviation %.3f\n",
                    spot ? "spot" : "sun", mean, n, bound, spread);
        EXPECT_NEAR(mean, 0.5, bound) << (spot ? "spot" : "sun");
        // Stochastic, not a uniform half shadow: a 3x3 filter over independent cells kept with
        // probability 0.5 varies by about 0.5 / 3 from pixel to pixel.
        EXPECT_GT(spread, 0.05) << (spot ? "spot" : "sun");
        // Deterministic: a second renderer draws the same frame.
        EXPECT_TRUE(test::imagesNear(test::renderHdr(half, settings), img, 0.0f, "BLEND 0.5, second render"));
    }
}

// shaders/common/hashed_alpha.glsl on the driver: the threshold is uniform in (0, 1] (so alpha >=
// threshold keeps a fraction alpha), both on a grid level (texel a power of two: one hash) and
// between levels, where the blend of two hashes is triangular until the paper's correction makes it
// uniform again (without it the middle bins hold twice the outer ones' share): 10 bins of 20000
// thresholds each within 5 standard errors (sqrt(0.1 x 0.9 / 20000) = 0.0021) of 0.1. And it
// depends on the object-space point only through its cell: a point moved within its cell, on a
// level, keeps its threshold bit for bit.
TEST(ShaderHashedAlpha, ThresholdIsUniformAndStableWithinACell) {
    std::mt19937 rng(2017);
    std::uniform_real_distribution<float> coord(-50.0f, 50.0f), unit(0.0f, 1.0f);
    const int n = 20000;
    for (const char* which : {"on a level", "between levels", "any footprint"}) {
        std::vector<glm::vec4> in;
        for (int i = 0; i < n; ++i) {
            const float level = std::floor(unit(rng) * 12.0f) - 2.0f;  // cells from 4 units down to 1/1024
            const float fraction = which[0] == 'o' ? 0.0f : which[0] == 'b' ? 0.5f : unit(rng);
            in.push_back(glm::vec4(coord(rng), coord(rng), coord(rng), std::exp2(-(level + fraction))));
        }
        const std::vector<glm::vec4> out =
            test::runGlsl({"common/hashed_alpha.glsl"}, "return vec4(hashedAlphaThreshold(x.xyz, x.w));", in);
        int bins[10] = {};
        for (const glm::vec4& t : out) {
            ASSERT_GT(t.x, 0.0f) << which;
            ASSERT_LE(t.x, 1.0f) << which;
            ++bins[std::min(int(t.x * 10.0f), 9)];
        }
        for (int b = 0; b < 10; ++b)
            EXPECT_NEAR(bins[b] / double(n), 0.1, 5.0 * std::sqrt(0.1 * 0.9 / n)) << which << ", bin " << b;
    }
    // Within a cell on a level (texel 1/8: cells 1/8 wide): the cell's corner and points inside it.
    std::vector<glm::vec4> in;
    for (int i = 0; i < 1000; ++i) {
        const glm::vec3 corner = glm::floor(glm::vec3(coord(rng), coord(rng), coord(rng)) * 8.0f) / 8.0f;
        in.push_back(glm::vec4(corner + glm::vec3(1.0f / 64.0f), 0.125f));
        in.push_back(glm::vec4(corner + glm::vec3(unit(rng), unit(rng), unit(rng)) * (7.0f / 64.0f) + glm::vec3(1.0f / 128.0f), 0.125f));
    }
    const std::vector<glm::vec4> out =
        test::runGlsl({"common/hashed_alpha.glsl"}, "return vec4(hashedAlphaThreshold(x.xyz, x.w));", in);
    int differentCells = 0;
    for (size_t i = 0; i + 1 < out.size(); i += 2) {
        ASSERT_EQ(out[i].x, out[i + 1].x) << "points " << i << " and " << i + 1 << " of one cell";
        if (i >= 2 && out[i].x != out[i - 2].x) ++differentCells;
    }
    EXPECT_GT(differentCells, 990);  // and different cells differ
}

namespace {
// The cascade tiles of a frame's atlas (the unused tiles left out).
std::vector<std::vector<float>> cascadeTiles(const test::ShadowAtlasFrame& a) {
    const size_t side = size_t(a.frustum.tileSize), width = side * size_t(a.frustum.columns);
    std::vector<std::vector<float>> tiles;
    for (const ShadowCascade& c : a.frustum.cascades) {
        const size_t x0 = size_t(c.tile % a.frustum.columns) * side, y0 = size_t(c.tile / a.frustum.columns) * side;
        std::vector<float> t;
        for (size_t y = 0; y < side; ++y)
            t.insert(t.end(), a.depth.begin() + std::ptrdiff_t((y0 + y) * width + x0),
                     a.depth.begin() + std::ptrdiff_t((y0 + y) * width + x0 + side));
        tiles.push_back(std::move(t));
    }
    return tiles;
}

// Bit for bit, naming the first differing texel.
testing::AssertionResult sameTiles(const test::ShadowAtlasFrame& kept, const test::ShadowAtlasFrame& fresh) {
    const auto a = cascadeTiles(kept), b = cascadeTiles(fresh);
    if (a.size() != b.size()) return testing::AssertionFailure() << a.size() << " cascades against " << b.size();
    for (size_t c = 0; c < a.size(); ++c)
        for (size_t i = 0; i < a[c].size(); ++i)
            if (std::memcmp(&a[c][i], &b[c][i], sizeof(float)) != 0)
                return testing::AssertionFailure() << "cascade " << c << " texel " << i % size_t(kept.frustum.tileSize) << ", "
                                                   << i / size_t(kept.frustum.tileSize) << ": kept " << a[c][i]
                                                   << ", redrawn " << b[c][i];
    return testing::AssertionSuccess();
}
}  // namespace

// The cascade cache with alpha-tested casters: MASK cards and BLEND cards (opacity 0.5, hashed)
// tilted over a floor; a camera walking along them keeps some tiles and redraws others, and every
// frame's kept atlas equals a fresh pass (cache off) bit for bit, for each raster: the hashed test
// reads the object-space position only, never the camera, so a kept tile stays valid. Changing a
// card's cutoff changes the casters: every tile redrawn ("casters changed"), again bit-exact.
TEST(ShadowAlpha, KeptTilesWithAlphaTestedCastersEqualAFreshRedraw) {
    Scene scene;
    ModelInstance floor;
    floor.name = "floor";
    floor.mesh = makePlane(12.0f, 4);
    scene.models.push_back(std::move(floor));
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (int i = 0; i < 8; ++i) {
        ModelInstance m = card(i % 2 == 0 ? maskMaterial() : blendMaterial(-1, 0.5f));
        m.name = "card" + std::to_string(i);
        m.transform = glm::translate(glm::mat4(1.0f), glm::vec3(4.0f * unit(rng), 1.0f + 0.3f * unit(rng), 5.0f * unit(rng))) *
                      glm::rotate(glm::mat4(1.0f), 0.6f * unit(rng), glm::vec3(1.0f, 0.0f, 0.0f)) *
                      glm::scale(glm::mat4(1.0f), glm::vec3(1.2f));
        scene.models.push_back(std::move(m));
    }
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f));
    scene.directionalLights.push_back(sun);
    scene.camera.position = glm::vec3(0.0f, 1.6f, 6.0f);
    scene.camera.target = glm::vec3(0.0f, 0.6f, 0.0f);
    scene.camera.nearPlane = 0.1f;
    scene.camera.farPlane = 40.0f;
    for (ShadowSettings::Raster raster : {ShadowSettings::Raster::Plain, ShadowSettings::Raster::Conservative,
                                          ShadowSettings::Raster::Split, ShadowSettings::Raster::Compute}) {
        const std::string name = ShadowSettings::rasterName(raster);
        Scene walk = scene;
        SceneGpu gpu(walk);
        RenderSettings settings;
        settings.width = 64;
        settings.height = 48;
        settings.shadows.size = 256;
        settings.shadows.raster = raster;
        settings.shadows.conservativeRaster = ShadowSettings::ConservativeRaster::GeometryShader;
        settings.shadows.redrawBudget = 0;
        settings.shadows.scroll = false;
        RenderSettings fresh = settings;
        fresh.shadows.cache = false;
        ShadowMapPass state;
        fg::TexturePool pool;
        const test::ShadowAtlasFrame first = test::drawShadowAtlas(walk, gpu, settings, state, pool);
        size_t alphaNotes = 0;
        for (const std::string& n : first.notes) alphaNotes += n.find("alpha-tested") != std::string::npos ? 1 : 0;
        EXPECT_GT(alphaNotes, 0u) << name << ": no cascade drew alpha-tested casters";
        const uint64_t firstDrawn = state.cacheStats.drawn;
        for (int step = 1; step <= 4; ++step) {
            walk.camera.position += glm::vec3(0.02f, 0.0f, -0.35f);
            walk.camera.target += glm::vec3(0.02f, 0.0f, -0.35f);
            const test::ShadowAtlasFrame kept = test::drawShadowAtlas(walk, gpu, settings, state, pool);
            ShadowMapPass freshState;
            fg::TexturePool freshPool;
            EXPECT_TRUE(sameTiles(kept, test::drawShadowAtlas(walk, gpu, fresh, freshState, freshPool)))
                << name << ", step " << step;
        }
        EXPECT_GT(state.cacheStats.kept, 0u) << name << ": the walk kept nothing";
        EXPECT_GT(state.cacheStats.drawn, firstDrawn) << name << ": the walk redrew nothing";
        for (GpuMaterial& m : gpu.materials)
            if (m.alphaMask) m.alphaCutoff = 0.8f;
        const test::ShadowAtlasFrame changed = test::drawShadowAtlas(walk, gpu, settings, state, pool);
        size_t castersChanged = 0;
        for (const std::string& n : changed.notes) castersChanged += n.find("redrawn (casters changed)") != std::string::npos ? 1 : 0;
        EXPECT_EQ(castersChanged, changed.frustum.cascades.size()) << name;
        ShadowMapPass freshState;
        fg::TexturePool freshPool;
        EXPECT_TRUE(sameTiles(changed, test::drawShadowAtlas(walk, gpu, fresh, freshState, freshPool))) << name << ", new cutoff";
    }
}

// The material-input views (base-color, metallic, roughness, occlusion, emissive) and the lit frame's
// term views (term-diffuse, term-specular) on a generated glTF quad of known factors: each input view
// reads back the factor (the occlusion map's texel through its strength), the emissive view the
// emitted radiance, and the term views the specification's diffuse and specular lobes of the sun
// (engine/render/gltf_brdf.hpp), in the classic and visibility G-buffers and forward+.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/io/gltf_loader.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/gltf_brdf.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/render_fixture.hpp"
#include "tests/unit/gltf_test_files.hpp"

using namespace lp;

namespace {

// The quad's material: glTF factors chosen away from 8-bit rounding ties.
const glm::dvec3 kBase(0.8, 0.4, 0.2);
constexpr double kMetallic = 0.3, kRoughness = 0.6;
constexpr int kOcclusionTexel = 100;  // the occlusion map's one texel (r, linear)
constexpr double kOcclusionStrength = 0.5;
const glm::dvec3 kEmissiveFactor(0.5, 0.25, 0.125);
constexpr double kEmissiveStrength = 2.0;  // KHR_materials_emissive_strength
const glm::dvec3 kToSun = glm::normalize(glm::dvec3(0.3, 1.0, 0.2));
constexpr double kSunIrradiance = 3.0;

double occlusion() { return 1.0 + (kOcclusionTexel / 255.0 - 1.0) * kOcclusionStrength; }

// A 2 x 2 quad in the y = 0 plane facing +Y, with uvs, and a 1 x 1 occlusion map: quad.gltf + .bin + .png.
std::filesystem::path writeQuad(const test::TempDir& dir) {
    const float positions[] = {-1, 0, 1, 1, 0, 1, 1, 0, -1, -1, 0, -1};
    const float normals[] = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
    const float uvs[] = {0, 1, 1, 1, 1, 0, 0, 0};
    const uint16_t indices[] = {0, 1, 2, 0, 2, 3};
    std::string bin;
    bin.append(reinterpret_cast<const char*>(positions), sizeof(positions));
    bin.append(reinterpret_cast<const char*>(normals), sizeof(normals));
    bin.append(reinterpret_cast<const char*>(uvs), sizeof(uvs));
    bin.append(reinterpret_cast<const char*>(indices), sizeof(indices));
    dir.write("quad.bin", bin);
    Image8 map{1, 1, {uint8_t(kOcclusionTexel), 0, 0, 255}};
    dir.write("occlusion.png", encodePng(map));
    nlohmann::json material = {
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {kBase.x, kBase.y, kBase.z, 1.0}}, {"metallicFactor", kMetallic}, {"roughnessFactor", kRoughness}}},
        {"occlusionTexture", {{"index", 0}, {"strength", kOcclusionStrength}}},
        {"emissiveFactor", {kEmissiveFactor.x, kEmissiveFactor.y, kEmissiveFactor.z}},
        {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", kEmissiveStrength}}}}}};
    nlohmann::json d = {
        {"asset", {{"version", "2.0"}}},
        {"extensionsUsed", {"KHR_materials_emissive_strength"}},
        {"buffers", {{{"byteLength", bin.size()}, {"uri", "quad.bin"}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}}, {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
          {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 32}}, {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 12}}}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}, {"min", {-1, 0, -1}}, {"max", {1, 0, 1}}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
          {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
          {{"bufferView", 3}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
        {"images", {{{"uri", "occlusion.png"}}}},
        {"textures", {{{"source", 0}}}},
        {"materials", {material}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}, {"material", 0}}}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"scenes", {{{"nodes", {0}}}}},
        {"scene", 0}};
    return dir.write("quad.gltf", d.dump());
}

Scene quadScene(const std::filesystem::path& gltf) {
    Scene s;
    ModelInstance m;
    m.name = "quad";
    m.mesh = loadGltf(gltf).mesh;
    s.models.push_back(std::move(m));
    s.ambient = glm::vec3(0.0f);
    s.environment.color = glm::vec3(0.0f);
    s.camera.position = {0.0f, 2.6f, 1.2f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.fovYDegrees = 50.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 20.0f;
    DirectionalLight sun;
    sun.direction = -glm::vec3(kToSun);
    sun.intensity = float(kSunIrradiance);
    sun.castsShadows = false;
    s.directionalLights.push_back(sun);
    return s;
}

struct Path {
    const char* name;
    RenderPath path;
    GBufferMode mode;
};
const Path kPaths[] = {{"deferred classic", RenderPath::Deferred, GBufferMode::Classic},
                       {"deferred visibility", RenderPath::Deferred, GBufferMode::Visibility},
                       {"forward+", RenderPath::ForwardPlus, GBufferMode::Auto}};

constexpr int kWidth = 64, kHeight = 48;

RenderSettings viewSettings(const Path& path, DebugView view) {
    RenderSettings s;
    s.width = kWidth;
    s.height = kHeight;
    s.keepHdr = true;
    s.renderPath = path.path;
    s.gbuffer.mode = path.mode;
    s.view = view;
    return s;
}

// Calls f(x, y, p) for each pixel whose ray meets the quad 0.1 inside its edges (p: the world point).
template <class F>
int forQuadPixels(const Scene& scene, F f) {
    int n = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const std::optional<glm::dvec3> hit = test::planePoint(scene.camera, kWidth, kHeight, x, y);
            if (!hit) continue;
            const glm::dvec3 p = *hit;
            if (std::abs(p.x) > 0.9 || std::abs(p.z) > 0.9) continue;
            f(x, y, p);
            ++n;
        }
    return n;
}

}  // namespace

// Each material-input view shows its input at every quad pixel: base-color as the sRGB code of the
// linear factor (as an image viewer shows a colour), metallic, roughness and occlusion (map texel
// 100/255 at strength 0.5) as grey = the value; the background black. Bound: 1 code of 255.
TEST(MaterialViews, InputViewsReadBackTheGltfFactorsInEveryPath) {
    test::TempDir dir("lp_material_views_");
    const Scene scene = quadScene(writeQuad(dir));
    struct Expect {
        DebugView view;
        glm::dvec3 value;
    };
    const Expect expects[] = {
        {DebugView::BaseColor, {test::srgbEncode(kBase.x), test::srgbEncode(kBase.y), test::srgbEncode(kBase.z)}},
        {DebugView::Metallic, glm::dvec3(kMetallic)},
        {DebugView::Roughness, glm::dvec3(kRoughness)},
        {DebugView::Occlusion, glm::dvec3(occlusion())}};
    for (const Path& path : kPaths) {
        SCOPED_TRACE(path.name);
        Renderer r(scene);
        for (const Expect& e : expects) {
            SCOPED_TRACE(viewName(e.view));
            r.render(viewSettings(path, e.view), 0.0f, false);
            const Image8 img = r.readDisplay();
            const int n = forQuadPixels(scene, [&](int x, int y, glm::dvec3) {
                const uint8_t* px = &img.rgba[(size_t(y) * kWidth + size_t(x)) * 4];
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(px[c], e.value[c] * 255.0, 1.0) << "pixel " << x << "," << y << " channel " << c;
            });
            EXPECT_GT(n, 200);
            const uint8_t* corner = &img.rgba[0];  // the top-left pixel sees the background
            EXPECT_EQ(corner[0] + corner[1] + corner[2], 0);
        }
    }
}

// The emissive view's HDR buffer is the emitted radiance alone (emissiveFactor x emissiveStrength;
// no reflected light, though a sun shines), and the term views are the sun's light through the
// specification's diffuse and specular lobes, each at the pixel's ray; their sum is the lit frame.
// Bound: 1% + 1e-3 per channel (the G-buffer's 8-bit kd, half-float sums).
TEST(MaterialViews, EmissiveAndTermViewsAreTheSpecificationsTermsInEveryPath) {
    test::TempDir dir("lp_material_views_");
    const Scene scene = quadScene(writeQuad(dir));
    const GltfBrdfMaterial material{kBase, kMetallic, kRoughness, 1.5};
    const glm::dvec3 emitted = kEmissiveFactor * kEmissiveStrength;
    const glm::dvec3 eye(scene.camera.position);
    for (const Path& path : kPaths) {
        SCOPED_TRACE(path.name);
        Renderer r(scene);
        std::vector<ImageF> hdr;
        for (DebugView view : {DebugView::Emissive, DebugView::TermDiffuse, DebugView::TermSpecular, DebugView::Final}) {
            r.render(viewSettings(path, view), 0.0f, false);
            hdr.push_back(r.readHdr());
        }
        double specularSeen = 0.0;
        const int n = forQuadPixels(scene, [&](int x, int y, glm::dvec3 p) {
            const glm::dvec3 N(0, 1, 0), V = glm::normalize(eye - p);
            const GltfBrdfLobes lobes = gltfBrdfLobes(material, N, V, kToSun);
            const double light = kSunIrradiance * glm::dot(N, kToSun);
            const glm::dvec3 want[3] = {emitted, lobes.diffuse * light, lobes.specular * light};
            const size_t at = (size_t(y) * kWidth + size_t(x)) * 4;
            for (int c = 0; c < 3; ++c) {
                for (int v = 0; v < 3; ++v)
                    ASSERT_NEAR(hdr[size_t(v)].rgba[at + c], want[v][c], 0.01 * want[v][c] + 1e-3)
                        << "view " << v << " pixel " << x << "," << y << " channel " << c;
                const double sum = hdr[0].rgba[at + c] + hdr[1].rgba[at + c] + hdr[2].rgba[at + c];
                ASSERT_NEAR(hdr[3].rgba[at + c], sum, 0.005 * sum + 1e-3) << "final pixel " << x << "," << y;
            }
            specularSeen = std::max(specularSeen, want[2].x);
        });
        EXPECT_GT(n, 200);
        EXPECT_GT(specularSeen, 0.05);  // the specular term is not negligible where it is checked
    }
}

// The term views leave out the sky, the transparent pass and emission; the emissive view keeps
// emission alone; the material-input views add gbuffer.material_input, which no other view allocates.
TEST(MaterialViews, GraphAddsOnlyWhatEachViewShows) {
    test::TempDir dir("lp_material_views_");
    Scene scene = quadScene(writeQuad(dir));
    scene.environment.color = glm::vec3(0.2f);  // a sky to leave out
    Renderer r(scene);
    auto decision = [&](const std::string& pass) {
        for (const fg::PassDecision& d : r.graph().explain())
            if (d.name == pass) return d;
        return fg::PassDecision{};
    };
    auto hasTarget = [&](const std::string& name) {
        const std::string text = r.graph().describe();
        return text.find(name) != std::string::npos;
    };
    const Path classic = kPaths[0];
    r.render(viewSettings(classic, DebugView::TermSpecular), 0.0f, false);
    EXPECT_FALSE(decision("sky").runs);
    EXPECT_NE(decision("sky").reason.find("term-specular"), std::string::npos) << decision("sky").reason;
    EXPECT_FALSE(decision("emission").runs);
    EXPECT_FALSE(hasTarget("gbuffer.material_input"));
    r.render(viewSettings(classic, DebugView::Emissive), 0.0f, false);
    EXPECT_TRUE(decision("emission").runs);
    EXPECT_FALSE(decision("sky").runs);
    r.render(viewSettings(classic, DebugView::Final), 0.0f, false);
    EXPECT_TRUE(decision("sky").runs);
    EXPECT_FALSE(hasTarget("gbuffer.material_input"));
    r.render(viewSettings(classic, DebugView::Roughness), 0.0f, false);
    EXPECT_TRUE(hasTarget("gbuffer.material_input"));
}

// The C++ side's numbers are the shaders' constants: LP_HIDE_* (common/brdf.glsl) for the term views
// and LP_MATERIAL_INPUT_* (common/material.glsl) for the input views; the viewer's m / t keys step
// through each cycle and back to the final view.
TEST(MaterialViews, ViewTablesAreTheShadersConstants) {
    const auto out = test::runGlsl({"common/material.glsl"},
                                   "return x.x == 0.0 ? vec4(LP_HIDE_DIFFUSE, LP_HIDE_SPECULAR, LP_HIDE_EMISSION, LP_HIDE_CLEARCOAT)"
                                   " : vec4(LP_MATERIAL_INPUT_BASE_COLOR, LP_MATERIAL_INPUT_METALLIC,"
                                   " LP_MATERIAL_INPUT_ROUGHNESS, LP_MATERIAL_INPUT_OCCLUSION);",
                                   {glm::vec4(0.0f), glm::vec4(1.0f)});
    EXPECT_EQ(out[0], glm::vec4(float(kHideDiffuse), float(kHideSpecular), float(kHideEmission), float(kHideClearcoat)));
    // Each term view hides the other three terms (KHR_materials_clearcoat's layer is the fourth).
    EXPECT_EQ(hiddenShadingTerms(DebugView::TermDiffuse), kHideSpecular | kHideEmission | kHideClearcoat);
    EXPECT_EQ(hiddenShadingTerms(DebugView::TermSpecular), kHideDiffuse | kHideEmission | kHideClearcoat);
    EXPECT_EQ(hiddenShadingTerms(DebugView::TermClearcoat), kHideDiffuse | kHideSpecular | kHideEmission);
    EXPECT_EQ(hiddenShadingTerms(DebugView::Emissive), kHideDiffuse | kHideSpecular | kHideClearcoat);
    EXPECT_EQ(hiddenShadingTerms(DebugView::Final), 0);
    EXPECT_EQ(hiddenShadingTerms(DebugView::Lighting), 0);
    EXPECT_EQ(out[1], glm::vec4(float(materialInputShown(DebugView::BaseColor)), float(materialInputShown(DebugView::Metallic)),
                                float(materialInputShown(DebugView::Roughness)), float(materialInputShown(DebugView::Occlusion))));
    for (DebugView v : allViews()) {
        const bool input = v == DebugView::BaseColor || v == DebugView::Metallic || v == DebugView::Roughness ||
                           v == DebugView::Occlusion;
        EXPECT_EQ(materialInputShown(v) != 0, input) << viewName(v);
    }
    DebugView v = DebugView::Normals;
    std::vector<std::string> seen;
    for (int i = 0; i < 6; ++i) seen.push_back(viewName(v = nextViewInCycle(materialInputViews(), v)));
    EXPECT_EQ(seen, (std::vector<std::string>{"base-color", "metallic", "roughness", "occlusion", "emissive", "final"}));
    EXPECT_EQ(nextViewInCycle(termViews(), DebugView::TermDiffuse), DebugView::TermSpecular);
    EXPECT_EQ(nextViewInCycle(termViews(), DebugView::TermSpecular), DebugView::TermClearcoat);
    EXPECT_EQ(nextViewInCycle(termViews(), DebugView::TermClearcoat), DebugView::Final);
}

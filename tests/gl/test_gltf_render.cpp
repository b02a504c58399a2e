// glTF and MTL materials rendered: a normal-mapped plane shades as its analytic normal (glTF with and
// without tangents, MTL norm), an MTL bump map as the height field's normal, emission adds exactly
// its radiance, alpha MASK drops exactly the texels below the cutoff. Each in both G-buffer modes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "engine/io/gltf_loader.hpp"
#include "engine/io/image_io.hpp"
#include "engine/io/obj_loader.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/mesh_ops.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/render_fixture.hpp"

using namespace lp;
namespace fs = std::filesystem;

namespace {

const double kPi = 3.14159265358979;

fs::path dataPath(const std::string& name) { return fs::path(test::repoPath("tests/data/gltf/" + name)); }

Scene modelScene(MeshData mesh) {
    Scene s;
    ModelInstance m;
    m.name = "model";
    m.mesh = std::move(mesh);
    s.models.push_back(std::move(m));
    s.ambient = glm::vec3(0.0f);
    s.environment.color = glm::vec3(0.0f);
    return s;
}

// The HDR buffer of a w x h render in G-buffer mode `mode` on render path `path`.
ImageF renderHdr(const Scene& s, GBufferMode mode, int w, int h, RenderPath path = RenderPath::Deferred) {
    RenderSettings settings;
    settings.gbuffer.mode = mode;
    settings.renderPath = path;
    settings.width = w;
    settings.height = h;
    return test::renderHdr(s, settings);
}

// HDR radiance at the centre pixel of a w x h render.
glm::vec3 centre(const Scene& s, GBufferMode mode, int w = 48, int h = 48) {
    const ImageF hdr = renderHdr(s, mode, w, h);
    const size_t i = (size_t(h / 2) * size_t(w) + size_t(w / 2)) * 4;
    return {hdr.rgba[i], hdr.rgba[i + 1], hdr.rgba[i + 2]};
}

// The HDR radiance of a 96 x 48 render where each of `points` (world, on z = 0) lands.
std::vector<glm::vec3> radianceAtPoints(const Scene& s, GBufferMode mode, const std::vector<glm::vec2>& points,
                                        RenderPath path = RenderPath::Deferred) {
    const int w = 96, h = 48;
    const ImageF hdr = renderHdr(s, mode, w, h, path);
    const glm::mat4 vp = s.camera.projection(float(w) / float(h)) * s.camera.view();
    std::vector<glm::vec3> out;
    for (const glm::vec2 p : points) {
        const glm::vec4 c = vp * glm::vec4(p, 0.0f, 1.0f);
        const int px = int((c.x / c.w * 0.5f + 0.5f) * float(w)), py = int((0.5f - c.y / c.w * 0.5f) * float(h));
        const size_t i = (size_t(py) * size_t(w) + size_t(px)) * 4;
        out.emplace_back(hdr.rgba[i], hdr.rgba[i + 1], hdr.rgba[i + 2]);
    }
    return out;
}

// A 2 x 1 quad in z = 0 (x -1..1, y -0.5..0.5, facing +Z) with one white, non-specular material,
// `corner` giving each corner's uv and colour; in a scene lit by ambient 1 alone (the radiance is the
// base colour), seen head-on from z = 3.
Scene facingQuadScene(const std::function<void(Vertex&, glm::vec2)>& corner) {
    MeshData quad;
    for (const glm::vec2 c : {glm::vec2(-1, -0.5f), glm::vec2(1, -0.5f), glm::vec2(1, 0.5f), glm::vec2(-1, 0.5f)}) {
        Vertex v;
        v.position = glm::vec3(c, 0.0f);
        v.normal = {0, 0, 1};
        corner(v, c);
        quad.vertices.push_back(v);
    }
    quad.indices = {0, 1, 2, 0, 2, 3};
    quad.subMeshes = {{0, 6, 0}};
    Material m;
    m.diffuse = glm::vec3(1.0f);
    m.specular = glm::vec3(0.0f);
    quad.materials = {m};
    Scene s = modelScene(std::move(quad));
    s.ambient = glm::vec3(1.0f);
    s.camera.position = {0.0f, 0.0f, 3.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.fovYDegrees = 45.0f;
    return s;
}

// Their red channel.
std::vector<float> redAtPoints(const Scene& s, GBufferMode mode, const std::vector<glm::vec2>& points) {
    std::vector<float> red;
    for (const glm::vec3 c : radianceAtPoints(s, mode, points)) red.push_back(c.x);
    return red;
}

// A 2 x 2 plane at y = 0 seen from straight above, lit by one sun from `toLight` (no shadows, no
// ambient), Lambertian white: the centre's radiance is E / pi * max(N.L, 0).
double lambertAtCentre(MeshData mesh, glm::vec3 toLight, GBufferMode mode) {
    for (Material& m : mesh.materials) {
        m.diffuse = glm::vec3(1.0f);
        m.specular = glm::vec3(0.0f);
        m.metallic = 0.0f;
    }
    Scene s = modelScene(std::move(mesh));
    s.camera.position = {0.0f, 3.0f, 0.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.up = {0.0f, 0.0f, -1.0f};
    s.camera.fovYDegrees = 30.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 10.0f;
    DirectionalLight sun;
    sun.direction = -glm::normalize(toLight);
    sun.intensity = 2.0f;
    sun.castsShadows = false;
    s.directionalLights.push_back(sun);
    return centre(s, mode).x;
}

void expectShadesAsNormal(const MeshData& mesh, glm::dvec3 normal, const std::string& what, GBufferMode mode) {
    // Two lights: one tells the tangent's sign, one the bitangent's.
    for (glm::vec3 L : {glm::vec3(0.8f, 0.6f, 0.0f), glm::vec3(0.0f, 0.6f, -0.8f), glm::vec3(-0.6f, 0.8f, 0.0f)}) {
        const double expected = 2.0 / kPi * std::max(glm::dot(glm::normalize(normal), glm::dvec3(L)), 0.0);
        EXPECT_NEAR(lambertAtCentre(mesh, L, mode), expected, 0.02 * 2.0 / kPi + 0.02 * expected)
            << what << ", light from " << L.x << " " << L.y << " " << L.z;
    }
}

fs::path tempDir() {
    std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::replace(test.begin(), test.end(), '/', '_');  // parameterised: "Case/classic"
    const fs::path d = fs::temp_directory_path() / ("lp_gltf_gl_" + std::to_string(::getpid()) + "_" + test);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

// A 2 x 2 OBJ plane at y = 0: u along +X, v along -Z (OBJ v up the image), with material `mtl`.
fs::path objPlane(const fs::path& dir, const std::string& mtl) {
    std::ofstream(dir / "plane.mtl") << mtl;
    std::ofstream(dir / "plane.obj") << "mtllib plane.mtl\nusemtl m\n"
                                        "v -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\n"
                                        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 1 0\n"
                                        "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
    return dir / "plane.obj";
}

Image8 constantImage(int w, int h, glm::u8vec4 texel) {
    Image8 img{w, h, {}};
    for (int i = 0; i < w * h; ++i) img.rgba.insert(img.rgba.end(), {texel.x, texel.y, texel.z, texel.w});
    return img;
}

// Every case in both G-buffer modes: what the materials do (normal and bump maps, emission, MASK alpha,
// single-sided faces) must hold for the visibility buffer's resolve as for the classic raster (CI's
// llvmpipe makes the classic one under the default --gbuffer-mode auto, a GPU the visibility one).
class GltfRender : public ::testing::TestWithParam<GBufferMode> {};

}  // namespace

INSTANTIATE_TEST_SUITE_P(GBufferModes, GltfRender, ::testing::ValuesIn(allGBufferModes()),
                         [](const ::testing::TestParamInfo<GBufferMode>& info) { return std::string(gbufferModeName(info.param)); });

// The plane's normal map holds tangent-space (0.36, 0.48, 0.8); with the tangent +X and the
// bitangent -Z (up the image), the shading normal is (0.36, 0.8, -0.48).
TEST_P(GltfRender, NormalMappedPlaneShadesAsItsAnalyticNormal) {
    const glm::dvec3 n(0.36, 0.8, -0.48);
    expectShadesAsNormal(loadGltf(dataPath("normal_plane.glb")).mesh, n, "glTF with tangents", GetParam());
    expectShadesAsNormal(loadGltf(dataPath("normal_plane_notangent.glb")).mesh, n, "glTF, generated tangents", GetParam());
}

// MTL: "norm" is read as a tangent-space normal map (the same normal as above), "bump" as a height map:
// a ramp rising 8/255 per texel along +u tilts the normal towards -X by the height step.
TEST_P(GltfRender, MtlNormIsANormalMapAndBumpIsAHeightMap) {
    const fs::path dir = tempDir();
    writePng(dir / "n.png", constantImage(8, 8, {173, 189, 230, 255}));  // round((n * 0.5 + 0.5) * 255)
    MeshData normMapped = loadObj(objPlane(dir, "newmtl m\nKd 1 1 1\nnorm n.png\n"));
    ASSERT_FALSE(normMapped.materials[0].normalMap.empty());
    expectShadesAsNormal(normMapped, glm::dvec3(0.36, 0.8, -0.48), "MTL norm", GetParam());

    Image8 ramp{16, 16, {}};
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) ramp.rgba.insert(ramp.rgba.end(), {uint8_t(8 * x), uint8_t(8 * x), uint8_t(8 * x), 255});
    writePng(dir / "h.png", ramp);
    fs::remove(dir / "plane.obj");
    MeshData bumped = loadObj(objPlane(dir, "newmtl m\nKd 1 1 1\nbump h.png\n"));
    ASSERT_FALSE(bumped.materials[0].bumpMap.empty());
    ASSERT_TRUE(bumped.materials[0].normalMap.empty());
    // gbuffer.frag: N - 4 scale ((h(u+1) - h(u-1)) T + ...), h in [0, 1]: a step of 2 texels = 16/255.
    const double slope = 4.0 * 16.0 / 255.0;
    expectShadesAsNormal(bumped, glm::dvec3(-slope, 1.0, 0.0), "MTL bump", GetParam());
    fs::remove_all(dir);
}

// An emissive panel (emissiveFactor (1, 0.5, 0.25) x strength 4) in the dark: exactly (4, 2, 1).
TEST_P(GltfRender, EmissionAddsExactlyItsRadiance) {
    Scene s = modelScene(loadGltf(dataPath("emissive.gltf")).mesh);
    s.camera.position = {0.0f, 0.0f, 2.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    const glm::vec3 c = centre(s, GetParam());
    EXPECT_NEAR(c.x, 4.0f, 4e-3f);
    EXPECT_NEAR(c.y, 2.0f, 2e-3f);
    EXPECT_NEAR(c.z, 1.0f, 1e-3f);
    // And on top of reflected light: a grey panel under ambient 0.5 gives 0.5 kd + emission, kd the glTF
    // dielectric's diffuse layer base (1 - 0.04) (the constant ambient lights the diffuse alone).
    for (Material& m : s.models[0].mesh.materials) m.diffuse = glm::vec3(0.5f);
    s.ambient = glm::vec3(0.5f);
    const glm::vec3 lit = centre(s, GetParam());
    EXPECT_NEAR(lit.x, 4.0f + 0.25f * 0.96f, 1e-2f);
    EXPECT_NEAR(lit.z, 1.0f + 0.25f * 0.96f, 1e-2f);
}

// alpha_mask.gltf: quads at x = 0, 1.5, 3 (1 x 1, y 0..1), MASK at cutoff 0.5: base alpha 0.3 (not
// drawn), 0.7 (drawn), and a texture whose left half is alpha 0 (that half not drawn).
TEST_P(GltfRender, AlphaMaskDropsTexelsBelowTheCutoff) {
    Scene s = modelScene(loadGltf(dataPath("alpha_mask.gltf")).mesh);
    // White base, ambient 1: where drawn the diffuse layer's 1 - 0.04 (glTF's dielectric F0), 0 (black
    // sky) elsewhere.
    s.ambient = glm::vec3(1.0f);
    s.camera.position = {2.0f, 0.5f, 6.0f};
    s.camera.target = {2.0f, 0.5f, 0.0f};
    s.camera.fovYDegrees = 45.0f;
    const std::vector<float> at = redAtPoints(s, GetParam(), {{0.5f, 0.5f}, {2.0f, 0.5f}, {3.25f, 0.5f}, {3.75f, 0.5f}});
    EXPECT_NEAR(at[0], 0.0f, 1e-4f) << "alpha 0.3 is below the cutoff";
    EXPECT_NEAR(at[1], 0.96f, 1e-2f) << "alpha 0.7 is above it";
    EXPECT_NEAR(at[2], 0.0f, 1e-4f) << "the texture's transparent half";
    EXPECT_NEAR(at[3], 0.96f, 1e-2f) << "the texture's opaque half";
}

// A glTF sampler's wrap modes, on a quad whose u runs 0..2 across it (x = -1..1) with a 4 x 1 texture
// black on its left half, white on its right (nearest magnification: no blend between them). Ambient 1 on
// a white base: the radiance is the texel. At u = 1.125 repeat reads u 0.125 (black), clamp the edge
// (white), mirror u 0.875 (white); at u = 1.875 repeat and clamp read white, mirror u 0.125 (black).
// One image under two samplers is two textures; under one, one.
TEST_P(GltfRender, SamplerWrapModesAreApplied) {
    Scene s = facingQuadScene([](Vertex& v, glm::vec2 c) { v.uv = {c.x + 1.0f, c.y + 0.5f}; });
    Image8 halves{4, 1, {0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255}};
    Material& m = s.models[0].mesh.materials[0];
    m.diffuseMap.encoded = std::make_shared<const std::string>(encodePng(halves));
    m.diffuseMap.key = "halves.png";
    m.diffuseMap.sampler.magFilter = 9728;  // GL_NEAREST (and so no anisotropy)
    const Material repeating = m;           // before texelsAt changes its wrap
    auto texelsAt = [&](int wrapS) {  // at u = 0.125, 1.125, 1.875
        s.models[0].mesh.materials[0].diffuseMap.sampler.wrapS = wrapS;
        return redAtPoints(s, GetParam(), {{-0.875f, 0.0f}, {0.125f, 0.0f}, {0.875f, 0.0f}});
    };
    const std::vector<float> repeat = texelsAt(10497), clamp = texelsAt(33071), mirror = texelsAt(33648);
    const float expected[3][3] = {{0, 0, 1}, {0, 1, 1}, {0, 1, 0}};
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(repeat[size_t(i)], expected[0][i], 1e-2f) << "repeat, point " << i;
        EXPECT_NEAR(clamp[size_t(i)], expected[1][i], 1e-2f) << "clamp to edge, point " << i;
        EXPECT_NEAR(mirror[size_t(i)], expected[2][i], 1e-2f) << "mirrored repeat, point " << i;
    }

    MeshData quad = s.models[0].mesh;
    quad.materials = {repeating, repeating, repeating};
    quad.materials[1].diffuseMap.sampler.wrapS = 33071;
    SceneGpu gpu(modelScene(quad));
    ASSERT_EQ(gpu.materials.size(), 3u);
    EXPECT_NE(gpu.materials[0].diffuseMap, gpu.materials[1].diffuseMap) << "two samplers: two textures";
    EXPECT_EQ(gpu.materials[0].diffuseMap, gpu.materials[2].diffuseMap) << "one sampler: one texture";
    GLint mag = 0, wrap = 0;
    glGetTextureParameteriv(gpu.materials[1].diffuseMap, GL_TEXTURE_MAG_FILTER, &mag);
    glGetTextureParameteriv(gpu.materials[1].diffuseMap, GL_TEXTURE_WRAP_S, &wrap);
    EXPECT_EQ(mag, GL_NEAREST);
    EXPECT_EQ(wrap, GL_CLAMP_TO_EDGE);
}

// Vertex colours (glTF COLOR_0) multiply the base colour: a white quad under ambient 1 whose left
// vertices are red and right vertices blue shows the colour interpolated across it, on both render
// paths. Their alpha multiplies the base alpha: under MASK (cutoff 0.5) with alpha 0.2 on the left
// and 1 on the right, the texels left of u = 0.375 are dropped; under BLEND the transparent pass
// covers the black sky by that alpha.
TEST_P(GltfRender, VertexColoursMultiplyTheBaseColourAndAlpha) {
    Scene s = facingQuadScene([](Vertex& v, glm::vec2 c) {
        v.uv = {0.5f * (c.x + 1.0f), c.y + 0.5f};
        v.color = c.x < 0.0f ? glm::vec4(1, 0, 0, 0.2f) : glm::vec4(0, 0, 1, 1);
    });
    auto rgbAt = [&](RenderPath path, const std::vector<float>& xs) {
        std::vector<glm::vec2> points;
        for (const float x : xs) points.emplace_back(x, 0.0f);
        return radianceAtPoints(s, GetParam(), points, path);
    };
    EXPECT_TRUE(SceneGpu(s).vertexColors) << "the programs read vertex colours (LP_VERTEX_COLOR)";
    Scene white = s;
    for (Vertex& v : white.models[0].mesh.vertices) v.color = glm::vec4(1.0f);
    EXPECT_FALSE(SceneGpu(white).vertexColors) << "all white: the programs are compiled without them";
    const std::vector<float> xs = {-0.75f, -0.5f, 0.0f, 0.5f, 0.75f};
    for (const RenderPath path : {RenderPath::Deferred, RenderPath::ForwardPlus}) {
        SCOPED_TRACE(renderPathName(path));
        s.models[0].mesh.materials[0].alphaMode = AlphaMode::Opaque;
        const std::vector<glm::vec3> got = rgbAt(path, xs);
        for (size_t i = 0; i < xs.size(); ++i) {
            // The pixel centre nearest x lies within half a pixel of it: about 0.011 of u here.
            const float u = 0.5f * (xs[i] + 1.0f);
            EXPECT_NEAR(got[i].x, 1.0f - u, 0.03f) << "red at x = " << xs[i];
            EXPECT_NEAR(got[i].y, 0.0f, 1e-3f) << "green at x = " << xs[i];
            EXPECT_NEAR(got[i].z, u, 0.03f) << "blue at x = " << xs[i];
        }
        s.models[0].mesh.materials[0].alphaMode = AlphaMode::Mask;
        const std::vector<glm::vec3> masked = rgbAt(path, {-0.75f, -0.4f, 0.5f});
        EXPECT_NEAR(masked[0].x + masked[0].z, 0.0f, 1e-4f) << "alpha 0.3 is below the cutoff: not drawn";
        EXPECT_NEAR(masked[1].x + masked[1].z, 0.0f, 1e-4f) << "alpha 0.44: not drawn";
        EXPECT_NEAR(masked[2].z, 0.75f, 0.03f) << "alpha 0.8: drawn";
        // BLEND (the transparent pass, over the black sky): the colour times its alpha 0.2 + 0.8 u.
        s.models[0].mesh.materials[0].alphaMode = AlphaMode::Blend;
        const std::vector<glm::vec3> blended = rgbAt(path, {-0.5f, 0.5f});
        EXPECT_NEAR(blended[0].x, 0.4f * 0.75f, 0.03f) << "u 0.25: alpha 0.4 x red 0.75";
        EXPECT_NEAR(blended[0].z, 0.4f * 0.25f, 0.03f) << "u 0.25: alpha 0.4 x blue 0.25";
        EXPECT_NEAR(blended[1].x, 0.8f * 0.25f, 0.03f) << "u 0.75: alpha 0.8 x red 0.25";
        EXPECT_NEAR(blended[1].z, 0.8f * 0.75f, 0.03f) << "u 0.75: alpha 0.8 x blue 0.75";
    }
}

// A second uv set (glTF TEXCOORD_1) is read by exactly the maps that ask for it, in every path: a
// quad whose first set holds u = 0.125 everywhere and whose second runs u1 = 0..1 across it, with a
// 4 x 1 texture (nearest) black on its left half and white on its right. On set 0 every map reads
// black; on set 1 the left half (u1 0.25) black and the right (u1 0.75) white. Lit by ambient 1
// alone, the radiance is base x occlusion, plus the emission: base colour, occlusion, emissive map,
// MASK alpha (the visibility buffer's own alpha test) and BLEND alpha (the transparent pass) each
// show the halves, on both render paths.
TEST_P(GltfRender, SecondUvSetIsSampledByTheMapsThatAskForIt) {
    Scene s = facingQuadScene([](Vertex& v, glm::vec2 c) {
        v.uv = {0.125f, 0.5f};
        v.uv1 = {0.5f * (c.x + 1.0f), 0.5f};
    });
    const Image8 halves{4, 1, {0, 0, 0, 0, 0, 0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255}};
    TextureRef map;
    map.encoded = std::make_shared<const std::string>(encodePng(halves));
    map.key = "halves.png";
    map.sampler.magFilter = 9728;  // GL_NEAREST
    map.uvSet = 1;
    EXPECT_FALSE(SceneGpu(s).secondUvSet) << "no map on set 1: the programs are compiled without it";
    const Material plain = s.models[0].mesh.materials[0];
    auto redAt = [&](const Material& m, RenderPath path) {
        s.models[0].mesh.materials[0] = m;
        std::vector<float> red;
        for (const glm::vec3 c : radianceAtPoints(s, GetParam(), {{-0.5f, 0.0f}, {0.5f, 0.0f}}, path)) red.push_back(c.x);
        return red;
    };
    std::vector<std::pair<std::string, Material>> cases;
    Material base = plain;
    base.diffuseMap = map;
    cases.emplace_back("base colour", base);
    Material occlusion = plain;
    occlusion.occlusionMap = map;
    cases.emplace_back("occlusion", occlusion);
    Material emissive = plain;
    emissive.diffuse = glm::vec3(0.0f);
    emissive.emission = glm::vec3(1.0f);
    emissive.emissiveMap = map;
    cases.emplace_back("emission", emissive);
    Material masked = plain;
    masked.diffuseMap = map;  // its alpha is 0 on the left: cut away, and the black sky shows
    masked.alphaMode = AlphaMode::Mask;
    cases.emplace_back("MASK", masked);
    Material blended = masked;  // the transparent pass: alpha 0 shows the sky, alpha 1 the texel
    blended.alphaMode = AlphaMode::Blend;
    cases.emplace_back("BLEND", blended);
    for (const RenderPath path : {RenderPath::Deferred, RenderPath::ForwardPlus})
        for (auto& [what, m] : cases) {
            SCOPED_TRACE(std::string(renderPathName(path)) + ", " + what);
            s.models[0].mesh.materials[0] = m;
            EXPECT_TRUE(SceneGpu(s).secondUvSet);
            const std::vector<float> second = redAt(m, path);
            // Black within 1/255: the deferred G-buffer keeps occlusion above 0 (0 marks flat-lit texels).
            EXPECT_NEAR(second[0], 0.0f, 5e-3f) << "set 1, u1 0.25: black";
            EXPECT_NEAR(second[1], 1.0f, 1e-2f) << "set 1, u1 0.75: white";
            Material first = m;
            for (TextureRef* t : {&first.diffuseMap, &first.occlusionMap, &first.emissiveMap}) t->uvSet = 0;
            const std::vector<float> zero = redAt(first, path);
            EXPECT_NEAR(zero[0], 0.0f, 5e-3f) << "set 0, u 0.125: black";
            EXPECT_NEAR(zero[1], 0.0f, 5e-3f) << "set 0, u 0.125: black";
        }
}

// Single-sided glTF materials are not drawn from behind; MTL (double-sided) ones are.
TEST_P(GltfRender, SingleSidedMaterialsHideBackFaces) {
    Scene s = modelScene(loadGltf(dataPath("emissive.gltf")).mesh);
    s.camera.position = {0.0f, 0.0f, -2.0f};  // behind the panel (it faces +Z)
    s.camera.target = {0.0f, 0.0f, 0.0f};
    EXPECT_NEAR(centre(s, GetParam()).x, 0.0f, 1e-4f);
    for (Material& m : s.models[0].mesh.materials) m.doubleSided = true;
    EXPECT_NEAR(centre(s, GetParam()).x, 4.0f, 4e-3f);
}

// A glTF spot (node at (0, 1, 0) turned -90 deg about +X: its -Z points down; cone 0.3 / 0.5 rad) over
// a white plane seen from above: the centre, on the axis, is lit; points beyond the outer angle
// (28.6 deg, 0.55 m from the foot) on either side are exactly black.
TEST_P(GltfRender, GltfSpotLightsItsConeOnly) {
    const fs::path dir = tempDir();
    const double s = std::sqrt(0.5);
    std::ofstream(dir / "spot.gltf")
        << R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
              "extensions": {"KHR_lights_punctual": {"lights": [{"type": "spot", "intensity": 2, "range": 5,
                             "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.5}}]}},
              "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
              "bufferViews": [{"buffer": 0, "byteLength": 36}],
              "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
              "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
              "nodes": [{"mesh": 0, "translation": [0, -5, 0]},
                        {"translation": [0, 1, 0], "rotation": [)"
        << -s << ", 0, 0, " << s << R"(], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
              "scenes": [{"nodes": [0, 1]}], "scene": 0})";
    const GltfContent g = loadGltf(dir / "spot.gltf");
    ASSERT_EQ(g.pointLights.size(), 1u);
    MeshData plane = loadObj(objPlane(dir, "newmtl m\nKd 1 1 1\n"));
    Scene scene = modelScene(std::move(plane));
    scene.pointLights = g.pointLights;
    scene.camera.position = {0.0f, 3.0f, 0.0f};
    scene.camera.target = {0.0f, 0.0f, 0.0f};
    scene.camera.up = {0.0f, 0.0f, -1.0f};  // image right is +X
    scene.camera.fovYDegrees = 30.0f;
    scene.camera.nearPlane = 0.1f;
    scene.camera.farPlane = 10.0f;
    const int w = 48, h = 48;
    Renderer r(scene);
    RenderSettings settings;
    settings.gbuffer.mode = GetParam();
    settings.width = w;
    settings.height = h;
    settings.keepHdr = true;
    r.render(settings);
    const ImageF hdr = r.readHdr();
    auto at = [&](int x, int y) { return hdr.rgba[(size_t(y) * size_t(w) + size_t(x)) * 4]; };
    // Column c's centre lies at x = ((c + 0.5) / 24 - 1) * 3 tan 15 deg on the plane: columns 4 and 43 at
    // |x| = 0.64 m, 32.7 deg off the axis, outside the cone.
    EXPECT_GT(at(w / 2, h / 2), 0.1f);
    EXPECT_EQ(at(4, h / 2), 0.0f);
    EXPECT_EQ(at(43, h / 2), 0.0f);
    EXPECT_EQ(at(w / 2, 4), 0.0f);
    EXPECT_EQ(at(w / 2, 43), 0.0f);
    fs::remove_all(dir);
}

// A UV sphere (64 x 32, seam at u = 0 / 1 facing +X) with a constant tilted normal map (the plane's
// (0.36, 0.48, 0.8)), white Lambertian under one sun, seen with the seam down the middle of the image.
// Its tangents generated (MikkTSpace rules, computeTangents) against the generator's analytic dp/du
// (continuous, what a file's tangents would hold): every sphere pixel within 2% of the brightest, and
// across the seam the step between the two columns either side of it within 2% as well (the
// analytic render's own step there is the smooth gradient).
TEST_P(GltfRender, GeneratedTangentsShadeAUvSphereWithoutASeam) {
    const GBufferMode mode = GetParam();
    auto render = [mode](MeshData mesh, bool normalMapped = true) {
        Material m;
        m.diffuse = glm::vec3(1.0f);
        m.specular = glm::vec3(0.0f);
        TextureRef normal;
        normal.encoded = std::make_shared<const std::string>(encodePng(constantImage(8, 8, {173, 189, 230, 255})));
        normal.key = "tilted-normal";
        if (normalMapped) m.normalMap = normal;
        mesh.materials = {m};
        mesh.subMeshes = {SubMesh{0, uint32_t(mesh.indices.size()), 0}};
        Scene s = modelScene(std::move(mesh));
        s.camera.position = {4.0f, 0.0f, 0.0f};
        s.camera.target = {0.0f, 0.0f, 0.0f};
        s.camera.fovYDegrees = 35.0f;
        DirectionalLight sun;
        sun.direction = -glm::normalize(glm::vec3(1.0f, 0.5f, 0.3f));
        sun.intensity = 2.0f;
        sun.castsShadows = false;
        s.directionalLights.push_back(sun);
        Renderer r(s);
        RenderSettings settings;
        settings.gbuffer.mode = mode;
        settings.width = 64;
        settings.height = 64;
        settings.keepHdr = true;
        r.render(settings);
        return r.readHdr();
    };
    const MeshData analytic = makeSphere(1.0f, 64, 32);
    MeshData generated = analytic;
    computeTangents(generated);
    const ImageF a = render(analytic), g = render(generated);
    float peak = 0.0f;
    for (size_t i = 0; i < a.rgba.size(); i += 4) peak = std::max(peak, a.rgba[i]);
    ASSERT_GT(peak, 0.3f);
    // The map matters: without it the shading moves by far more than the bounds below.
    const ImageF plain = render(analytic, false);
    double tilt = 0.0;
    for (size_t i = 0; i < a.rgba.size(); i += 4) tilt = std::max(tilt, double(std::abs(a.rgba[i] - plain.rgba[i])));
    EXPECT_GT(tilt, 0.2 * peak);
    double worst = 0.0;
    for (size_t i = 0; i < a.rgba.size(); i += 4) worst = std::max(worst, double(std::abs(a.rgba[i] - g.rgba[i])));
    EXPECT_LT(worst, 0.02 * peak);
    // The seam projects onto the image's middle columns (31 | 32), rows within the sphere's middle half.
    for (int y = 20; y < 44; ++y) {
        auto at = [&](const ImageF& img, int x) { return img.rgba[(size_t(y) * 64 + size_t(x)) * 4]; };
        const float stepGenerated = at(g, 32) - at(g, 31), stepAnalytic = at(a, 32) - at(a, 31);
        EXPECT_NEAR(stepGenerated, stepAnalytic, 0.02f * peak) << "row " << y;
        EXPECT_GT(at(g, 31), 0.0f) << "row " << y;
    }
}

// The raster IBL against the in-tree path tracer (lightpass reference --direct-only --pixel-centre):
// textured and normal-mapped metals, a rough sphere and a rough plane at grazing view under a map with
// one large hard-edged window. Small images and bakes (llvmpipe).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include <unistd.h>

#include "engine/io/image_io.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/render_fixture.hpp"

using namespace lp;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::filesystem::path tempPath(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("lightpass-ibl-truth-" + std::to_string(::getpid()) + "-" + name);
}

// An equirectangular map (lightpass's convention, docs/ibl-and-tonemapping.md) of `radiance(d)`.
template <class F>
ImageF equirectMap(int width, F radiance) {
    ImageF img;
    img.width = width;
    img.height = width / 2;
    img.rgba.resize(size_t(img.width) * size_t(img.height) * 4);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const double phi = ((x + 0.5) / img.width - 0.5) * 2.0 * kPi, theta = (y + 0.5) / img.height * kPi;
            const glm::dvec3 d(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
            float* p = &img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
            p[0] = p[1] = p[2] = float(radiance(d));
            p[3] = 1.0f;
        }
    return img;
}

// A smooth sky: 1 + 0.6 y + 0.3 x (0.1 .. 1.9), brighter above and to +X, no edge a fixed sample set
// could meet badly: what is left against the tracer is the method, not its sample pattern.
ImageF gradientMap() {
    return equirectMap(128, [](glm::dvec3 d) { return 1.0 + 0.6 * d.y + 0.3 * d.x; });
}

// A dim room (0.2 above the horizon, 0.1 below) with one hard-edged window of 20, 60 x 35 degrees,
// centred 25 degrees up behind a camera looking down -Z: bench/mitsuba/make_maps.py's window map.
ImageF windowMap() {
    return equirectMap(256, [](glm::dvec3 d) {
        const double elevation = std::asin(std::clamp(d.y, -1.0, 1.0)) * 180.0 / kPi;
        const double azimuth = std::atan2(d.x, d.z) * 180.0 / kPi;  // 0: +Z
        return std::abs(azimuth) <= 30.0 && std::abs(elevation - 25.0) <= 17.5 ? 20.0 : (d.y > 0.0 ? 0.2 : 0.1);
    });
}

struct MapFile {
    std::filesystem::path path;
    MapFile(const std::string& name, const ImageF& img) : path(tempPath(name)) { writeExr(path, img); }
    ~MapFile() { std::filesystem::remove(path); }
};

RenderSettings rasterSettings(int w, int h, IblSpecular method, RenderPath path = RenderPath::Deferred) {
    RenderSettings s;
    s.width = w;
    s.height = h;
    s.keepHdr = true;
    s.autoExposure = false;
    s.aa.method = AntiAliasing::Off;
    s.aa.dither = false;
    s.ao.enabled = false;
    s.environment = test::smallIblBake(256);
    s.environment.cubeSize = 128;
    s.environment.specularSize = 64;
    s.environment.specularSamples = 256;
    s.environment.specular = method;
    s.renderPath = path;
    return s;
}

// lightpass reference --direct-only --pixel-centre: the environment seen from the first surface through
// the pixel's centre, which is what the IBL models.
RenderSettings tracerSettings(int w, int h, int samples) {
    RenderSettings s = rasterSettings(w, h, IblSpecular::SplitSum);
    s.renderPath = RenderPath::PathTraced;
    s.pathTrace.samples = samples;
    s.pathTrace.directOnly = true;
    s.pathTrace.pixelCentre = true;
    return s;
}

double luminanceAt(const ImageF& img, int x, int y) {
    const float* p = &img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// sum(image) / sum(reference) - 1 over `pixels` (x, y).
double relativeError(const ImageF& image, const ImageF& reference, const std::vector<glm::ivec2>& pixels) {
    double got = 0.0, want = 0.0;
    for (glm::ivec2 p : pixels) {
        got += luminanceAt(image, p.x, p.y);
        want += luminanceAt(reference, p.x, p.y);
    }
    return got / want - 1.0;
}

std::shared_ptr<const std::string> constantPng(glm::u8vec4 texel) {
    Image8 img{4, 4, {}};
    for (int i = 0; i < 16; ++i) img.rgba.insert(img.rgba.end(), {texel.x, texel.y, texel.z, texel.w});
    return std::make_shared<const std::string>(encodePng(img));
}

Material metal(glm::vec3 base, float roughness) {
    Material m;
    m.diffuse = base;
    m.specular = glm::vec3(0.04f);
    m.metallic = 1.0f;
    m.roughness = roughness;
    m.shininess = shininessFromRoughness(roughness);
    m.doubleSided = false;
    return m;
}

struct Quad {
    const char* name;
    double centreX;
    bool normalMapped;
    bool metalRoughMap;
};
const Quad kQuads[] = {
    {"gold, factors", -2.4, false, false},
    {"gold, metallic-roughness map", -0.8, false, true},
    {"gold, normal map", 0.8, true, false},
    {"gold, normal and metallic-roughness maps", 2.4, true, true},
};

// Gold (metallic 1, roughness 0.5) quads 1.5 m wide in a row, as factors or from maps: a
// metallic-roughness map of roughness 0.502 (g 128, factor 1) and metallic 1 (b 255), and a tangent-space
// normal map tilted 36 degrees towards -X and +Z (test_gltf_brdf.cpp's texel), whose lobe reaches
// through the quad's plane. Seen from above at 47 degrees.
Scene goldQuads(const std::filesystem::path& map) {
    Scene s;
    for (const Quad& q : kQuads) {
        ModelInstance m;
        m.name = q.name;
        m.mesh = makePlane(1.5f);  // tangents +X
        m.transform = glm::translate(glm::mat4(1.0f), glm::vec3(float(q.centreX), 0, 0));
        Material mat = metal({1.0f, 0.766f, 0.336f}, 0.5f);
        if (q.normalMapped) {
            mat.normalMap.encoded = constantPng({173, 189, 230, 255});
            mat.normalMap.key = "ibl-truth-tilted-normal";
        }
        if (q.metalRoughMap) {  // roughness = factor x g, metallic = factor x b
            mat.roughness = 1.0f;
            mat.shininess = shininessFromRoughness(1.0f);
            mat.metallicRoughnessMap.encoded = constantPng({0, 128, 255, 255});
            mat.metallicRoughnessMap.key = "ibl-truth-metal-rough";
        }
        m.mesh.materials.assign(m.mesh.materials.size(), mat);
        s.models.push_back(std::move(m));
    }
    s.ambient = glm::vec3(0.0f);
    s.environment.map = map;
    s.camera.position = {0.0f, 3.2f, 3.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.fovYDegrees = 50.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 20.0f;
    return s;
}

// The pixels whose centre ray meets the plane y = 0 inside [x0, x1] x [z0, z1].
std::vector<glm::ivec2> planePixels(const Camera& camera, int w, int h, double x0, double x1, double z0, double z1) {
    std::vector<glm::ivec2> out;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::optional<glm::dvec3> p = test::planePoint(camera, w, h, x, y);
            if (p && p->x > x0 && p->x < x1 && p->z > z0 && p->z < z1) out.push_back({x, y});
        }
    return out;
}

}  // namespace

// Issue #38's fault: the sampled specular (--ibl-specular sampled) read every sample of the GGX lobe
// around the normal-mapped normal from the map, also those below the triangle's own plane, from where
// no light reaches it: the normal-mapped gold quads came out +80% / +74% against the path tracer under
// this smooth map (192 x 96; +42% / +44% under a window map). Now a sample below the geometric normal
// (the G-buffer depth's face normal in the deferred ibl pass, the triangle's plane in forward+) brings
// no light but keeps its weight, as the tracer ends such paths. Gold quads with factors, a
// metallic-roughness map, a normal map, and both, under a smooth sky, against the tracer (64 samples
// through each pixel's centre): every quad within 5% by forward+ and by the deferred ibl pass after
// either G-buffer (classic, visibility); measured -2.6% .. -0.3%. The split sum has no such cut (its
// one lookup cannot tell which part of its lobe is below the plane): recorded, not bounded (+47% / +35%
// on the normal-mapped quads, -4.7% / -2.6% on the others).
TEST(IblTruth, SampledSpecularOfNormalMappedAndTexturedMetalsMatchesThePathTracer) {
    const MapFile map("gradient-quads.exr", gradientMap());
    const Scene scene = goldQuads(map.path);
    const int w = 96, h = 48;
    const ImageF traced = test::renderHdr(scene, tracerSettings(w, h, 64));
    const ImageF deferred = test::renderHdr(scene, rasterSettings(w, h, IblSpecular::Sampled));
    const ImageF forward = test::renderHdr(scene, rasterSettings(w, h, IblSpecular::Sampled, RenderPath::ForwardPlus));
    RenderSettings visibility = rasterSettings(w, h, IblSpecular::Sampled);
    visibility.gbuffer.mode = GBufferMode::Visibility;  // the resolve pass's G-buffer, lit by the same ibl pass
    const ImageF resolved = test::renderHdr(scene, visibility);
    const ImageF splitSum = test::renderHdr(scene, rasterSettings(w, h, IblSpecular::SplitSum));
    for (const Quad& q : kQuads) {
        const std::vector<glm::ivec2> pixels = planePixels(scene.camera, w, h, q.centreX - 0.6, q.centreX + 0.6, -0.6, 0.6);
        ASSERT_GT(pixels.size(), 60u) << q.name;
        const double d = relativeError(deferred, traced, pixels), f = relativeError(forward, traced, pixels);
        const double v = relativeError(resolved, traced, pixels);
        EXPECT_NEAR(d, 0.0, 0.05) << q.name << ", deferred";
        EXPECT_NEAR(f, 0.0, 0.05) << q.name << ", forward+";
        EXPECT_NEAR(v, 0.0, 0.05) << q.name << ", deferred, visibility G-buffer";
        RecordProperty(std::string(q.name) + ": sampled deferred / forward+ / visibility, split sum",
                       std::to_string(d) + " / " + std::to_string(f) + " / " + std::to_string(v) + ", " +
                           std::to_string(relativeError(splitSum, traced, pixels)));
    }
}

// A rough metal plane (Ks 1, roughness 0.5) seen at grazing angles (eye 0.3 m up, 6 degrees down, as
// bench/mitsuba/grazing_plane.py) under the smooth sky, against the tracer over the plane: the sampled
// specular within 10% (the target; measured -0.7% at 64 x 32), the split sum recorded (-15%: its
// round lobe along R' cannot follow the grazing lobe's stretch and horizon cut).
TEST(IblTruth, RoughPlaneAtGrazingViewMatchesThePathTracerWithTheSampledSpecular) {
    const MapFile map("gradient-plane.exr", gradientMap());
    Scene scene;
    ModelInstance m;
    m.name = "plane";
    m.mesh = makePlane(40.0f);
    m.mesh.materials.assign(m.mesh.materials.size(), metal(glm::vec3(1.0f), 0.5f));
    scene.models.push_back(std::move(m));
    scene.ambient = glm::vec3(0.0f);
    scene.environment.map = map.path;
    scene.camera.position = {0.0f, 0.3f, 0.0f};
    scene.camera.target = {0.0f, 0.3f - 10.0f * std::tan(6.0f * float(kPi) / 180.0f), -10.0f};
    scene.camera.fovYDegrees = 24.0f;
    scene.camera.nearPlane = 0.05f;
    scene.camera.farPlane = 200.0f;
    const int w = 64, h = 32;
    const ImageF traced = test::renderHdr(scene, tracerSettings(w, h, 64));
    const std::vector<glm::ivec2> pixels = planePixels(scene.camera, w, h, -18.0, 18.0, -18.0, 0.0);
    ASSERT_GT(pixels.size(), 300u);
    const double sampled = relativeError(test::renderHdr(scene, rasterSettings(w, h, IblSpecular::Sampled)), traced, pixels);
    const double splitSum = relativeError(test::renderHdr(scene, rasterSettings(w, h, IblSpecular::SplitSum)), traced, pixels);
    EXPECT_NEAR(sampled, 0.0, 0.10) << "sampled specular";
    RecordProperty("sampled / split sum", std::to_string(sampled) + " / " + std::to_string(splitSum));
}

// Rough metal spheres (Ks 1, roughness 0.5 and 0.75) under the hard-edged window, against the tracer,
// whole sphere within 0.9 of its radius: the sampled specular with 256 samples within 3% (measured -1.2%
// and -2.5% at 64 x 32); 64 samples and the split sum recorded (-3.2% / -5.3% and -7.6% / -15.7%: the
// split sum's round lobe cannot follow the lobe across the window's edge, the method's limit; 64 fixed
// samples, each widened by its sub-lobe, spread the lobe a little wider than GGX's).
TEST(IblTruth, RoughSpheresUnderAHardEdgedWindowMatchThePathTracerWithTheSampledSpecular) {
    const MapFile map("window-spheres.exr", windowMap());
    Scene scene;
    const double roughness[] = {0.5, 0.75};
    for (int i = 0; i < 2; ++i) {
        ModelInstance m;
        m.name = "sphere";
        m.mesh = makeSphere(0.5f, 64, 32);
        m.mesh.materials.assign(m.mesh.materials.size(), metal(glm::vec3(1.0f), float(roughness[i])));
        m.transform = glm::translate(glm::mat4(1.0f), glm::vec3(i == 0 ? -0.7f : 0.7f, 0.0f, 0.0f));
        scene.models.push_back(std::move(m));
    }
    scene.ambient = glm::vec3(0.0f);
    scene.environment.map = map.path;
    scene.camera.position = {0.0f, 0.0f, 4.0f};
    scene.camera.target = {0.0f, 0.0f, 0.0f};
    scene.camera.fovYDegrees = 30.0f;
    scene.camera.nearPlane = 0.1f;
    scene.camera.farPlane = 20.0f;
    const int w = 64, h = 32;
    const ImageF traced = test::renderHdr(scene, tracerSettings(w, h, 64));
    RenderSettings s256 = rasterSettings(w, h, IblSpecular::Sampled);
    s256.environment.specularRuntimeSamples = 256;
    const ImageF sampled256 = test::renderHdr(scene, s256);
    const ImageF sampled64 = test::renderHdr(scene, rasterSettings(w, h, IblSpecular::Sampled));
    const ImageF splitSum = test::renderHdr(scene, rasterSettings(w, h, IblSpecular::SplitSum));
    const glm::dmat4 inv = glm::inverse(glm::dmat4(scene.camera.projection(float(w) / float(h))) * glm::dmat4(scene.camera.view()));
    for (int i = 0; i < 2; ++i) {
        const glm::dvec3 centre(i == 0 ? -0.7 : 0.7, 0.0, 0.0);
        std::vector<glm::ivec2> pixels;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double nx = (x + 0.5) / w * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / h * 2.0;
                const glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
                const glm::dvec3 o = glm::dvec3(a) / a.w - centre, d = glm::normalize(glm::dvec3(b) / b.w - glm::dvec3(a) / a.w);
                const double bq = glm::dot(o, d);
                if (bq * bq - (glm::dot(o, o) - 0.45 * 0.45) > 0.0) pixels.push_back({x, y});
            }
        ASSERT_GT(pixels.size(), 80u);
        const double e256 = relativeError(sampled256, traced, pixels), e64 = relativeError(sampled64, traced, pixels);
        const double eSplit = relativeError(splitSum, traced, pixels);
        EXPECT_NEAR(e256, 0.0, 0.03) << "roughness " << roughness[i] << ", 256 samples";
        RecordProperty("roughness " + std::to_string(roughness[i]) + ": sampled 256 / 64, split sum",
                       std::to_string(e256) + " / " + std::to_string(e64) + ", " + std::to_string(eSplit));
    }
}

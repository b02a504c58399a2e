// Which way an equirectangular map faces, through every path that reads it (engine/render/ibl_sh.hpp
// equirectDirection, shaders/common/ibl.glsl): seen from inside, a map reads as the flat image does,
// not mirrored. An asymmetric map (coloured patches at known texels) must show each patch in the sky
// at the pixel its world direction projects to, and a lamp at +X must light the +X side of a sphere
// through the irradiance (SH and cube), the prefiltered cube and the extracted light alike.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "engine/render/ibl_environment.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;

namespace {

std::filesystem::path tempMap(const std::string& name) {
    return std::filesystem::temp_directory_path() /
           ("lightpass-orientation-" + std::to_string(::getpid()) + "-" + name + ".exr");
}

// A w x h map of `background` with a 4 x 4-texel patch of `colour` centred on (u, v) (texel edges).
void addPatch(ImageF& map, double u, double v, glm::vec3 colour) {
    const int cx = int(std::lround(u * map.width)), cy = int(std::lround(v * map.height));
    for (int y = cy - 2; y < cy + 2; ++y)
        for (int x = cx - 2; x < cx + 2; ++x) {
            float* p = &map.rgba[(size_t(y) * size_t(map.width) + size_t((x + map.width) % map.width)) * 4];
            p[0] = colour.x;
            p[1] = colour.y;
            p[2] = colour.z;
        }
}

ImageF plainMap(int w, int h, float background) {
    ImageF map;
    map.width = w;
    map.height = h;
    map.rgba.assign(size_t(w) * size_t(h) * 4, background);
    for (size_t i = 3; i < map.rgba.size(); i += 4) map.rgba[i] = 1.0f;
    return map;
}

// A scene whose one model (a small sphere) sits out of the way of what is looked at.
Scene skyScene(const std::filesystem::path& map, glm::vec3 spherePosition) {
    Scene scene;
    ModelInstance m;
    m.name = "sphere";
    m.primitive = "sphere";
    m.mesh = makeSphere(0.5f, 48, 24);
    m.transform = glm::mat4(1.0f);
    m.transform[3] = glm::vec4(spherePosition, 1.0f);
    scene.models.push_back(std::move(m));
    scene.ambient = glm::vec3(0.0f);
    scene.environment.map = map;
    return scene;
}

}  // namespace

// Camera at the origin looking down -Z (+Y up, 90 degree fov, 64 x 64), a 128 x 64 map of 0.05 with
// a red patch right of the centre column (u = 0.5625, on the horizon), a green one left of it
// (u = 0.4375) and a blue one above it (u = 0.5, v = 0.3125). Their world directions, written out:
// red (sin 22.5, 0, -cos 22.5), green (-sin 22.5, 0, -cos 22.5), blue (0, sin 33.75, -cos 33.75):
// through the camera red lands at x = 32 + 32 tan 22.5 = 45.3, green at x = 18.7 (both y = 32), blue at
// y = 32 - 32 tan 33.75 = 10.6 (x = 32). Each must be its colour there (the patch covers +-3 pixels),
// in the sky (the cube) and in the map rotated by 360 degrees; rotated by +90 degrees (right-handed
// about +Y, as Filament's and Mitsuba's to_world) the centre column faces -X, so looking down -X
// shows the same picture.
TEST(EnvironmentOrientation, SkyReadsAsTheFlatImage) {
    const auto path = tempMap("patches");
    ImageF map = plainMap(128, 64, 0.05f);
    addPatch(map, 0.5625, 0.5, {4.0f, 0.0f, 0.0f});
    addPatch(map, 0.4375, 0.5, {0.0f, 4.0f, 0.0f});
    addPatch(map, 0.5, 0.3125, {0.0f, 0.0f, 4.0f});
    writeExr(path, map);
    struct View {
        float rotation;
        glm::vec3 forward;
    };
    for (const View& view : {View{0.0f, {0, 0, -1}}, View{360.0f, {0, 0, -1}}, View{90.0f, {-1, 0, 0}}}) {
        Scene scene = skyScene(path, -view.forward * 50.0f);  // behind the camera
        scene.environment.rotationDegrees = view.rotation;
        scene.camera.position = glm::vec3(0.0f);
        scene.camera.target = view.forward;
        scene.camera.fovYDegrees = 90.0f;
        scene.camera.nearPlane = 0.1f;
        scene.camera.farPlane = 100.0f;
        Renderer r(scene);
        RenderSettings s;
        s.width = s.height = 64;
        s.keepHdr = true;
        s.environment = lp::test::smallIblBake(64);
        s.environment.ibl = false;
        s.environment.cubeSize = 128;
        r.render(s, 0.0f, false);
        ASSERT_TRUE(r.graph().isLive("sky"));
        const ImageF hdr = r.readHdr();
        auto at = [&](int x, int y) {
            const float* p = &hdr.rgba[(size_t(y) * 64 + size_t(x)) * 4];
            return glm::vec3(p[0], p[1], p[2]);
        };
        struct Expect {
            const char* name;
            int x, y, channel;
        };
        for (const Expect& e : {Expect{"red", 45, 32, 0}, Expect{"green", 19, 32, 1}, Expect{"blue", 32, 11, 2}}) {
            const glm::vec3 c = at(e.x, e.y);
            EXPECT_GT(c[e.channel], 2.0f) << e.name << " at " << e.x << "," << e.y << " rotation " << view.rotation;
            EXPECT_LT(c[(e.channel + 1) % 3] + c[(e.channel + 2) % 3], 0.5f)
                << e.name << " at " << e.x << "," << e.y << " rotation " << view.rotation;
        }
        // And nowhere mirrored: the patches' mirror images hold the background.
        for (const Expect& e : {Expect{"red mirrored", 18, 32, 0}, Expect{"green mirrored", 45, 32, 1}, Expect{"blue mirrored", 32, 53, 2}})
            EXPECT_LT(at(e.x, e.y)[e.channel], 0.2f) << e.name << " rotation " << view.rotation;
    }
    std::filesystem::remove(path);
}

// A white sphere (radius 0.5 at the origin) seen from +Z, under a 128 x 64 map of 0.05 with a lamp
// of 2000 at u = 0.75 on the horizon: +X. Its right half (normals towards +X) must be lit and its
// left half not, through every path: diffuse from SH and from the irradiance cube, a Lambertian and a
// glossy sphere (the prefiltered cube), the lamp extracted as a light (the default) or left in the
// map. Bound: the right half's mean at least 5x the left half's (the left half sees the lamp not at
// all, only the background and the blur of the coarse levels). The extracted light points at +X
// within 3 degrees.
TEST(EnvironmentOrientation, LampAtPlusXLightsThePlusXSide) {
    const auto path = tempMap("lamp");
    ImageF map = plainMap(128, 64, 0.05f);
    addPatch(map, 0.75, 0.5, {2000.0f, 2000.0f, 2000.0f});
    writeExr(path, map);
    Scene scene = skyScene(path, glm::vec3(0.0f));
    scene.camera.position = glm::vec3(0.0f, 0.0f, 2.5f);
    scene.camera.target = glm::vec3(0.0f);
    scene.camera.fovYDegrees = 40.0f;
    scene.camera.nearPlane = 0.1f;
    scene.camera.farPlane = 10.0f;
    for (int extract : {0, 4})
        for (IrradianceSource source : {IrradianceSource::SphericalHarmonics, IrradianceSource::Cubemap})
            for (bool glossy : {false, true}) {
                for (auto& mat : scene.models[0].mesh.materials) {
                    mat.diffuse = glm::vec3(glossy ? 0.0f : 0.8f);
                    mat.specular = glm::vec3(glossy ? 1.0f : 0.0f);
                    mat.shininess = 30.0f;
                }
                Renderer r(scene);
                RenderSettings s;
                s.width = 48;
                s.height = 32;
                s.keepHdr = true;
                s.ao.enabled = false;
                s.environment = lp::test::smallIblBake(64);
                s.environment.cubeSize = 64;
                s.environment.extractLights = extract;
                s.environment.diffuse = source;
                s.disabledPasses.insert("sky");  // the sphere's pixels alone
                r.render(s, 0.0f, false);
                ASSERT_TRUE(r.graph().isLive("ibl"));
                const ImageF hdr = r.readHdr();
                double left = 0.0, right = 0.0;
                for (int y = 0; y < s.height; ++y)
                    for (int x = 0; x < s.width; ++x) {
                        const float* p = &hdr.rgba[(size_t(y) * size_t(s.width) + size_t(x)) * 4];
                        (x < s.width / 2 ? left : right) += p[0] + p[1] + p[2];
                    }
                const std::string what = std::string(glossy ? "glossy" : "Lambertian") + ", extract " +
                                         std::to_string(extract) + ", diffuse " +
                                         (source == IrradianceSource::Cubemap ? "cube" : "SH");
                std::printf("  %s: right half / left half %.1f\n", what.c_str(), right / std::max(left, 1e-30));
                EXPECT_GT(right, 0.0) << what;
                EXPECT_GT(right, 5.0 * left) << what << ": left " << left << ", right " << right;
                if (extract > 0) {
                    const BakedEnvironment& env = r.environments().get(scene, s.environment, r.shaders(), true);
                    ASSERT_EQ(env.lights.size(), 1u) << what;
                    EXPECT_GT(env.lights[0].direction.x, std::cos(3.0 * 3.14159265 / 180.0)) << what;
                }
            }
    std::filesystem::remove(path);
}

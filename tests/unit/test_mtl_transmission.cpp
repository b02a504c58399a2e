// MTL's refraction/glass illumination models onto KHR_materials_transmission (engine/io/obj_loader):
// illum 6 and 7 transmit all that is not reflected, tinted by Tf, bent by Ni; illum 4 refracts its
// dissolved share 1 - d; a plain d < 1 stays alpha-blended; the volume's thickness is the smallest
// extent of the material's triangles.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "engine/io/obj_loader.hpp"
#include "engine/scene/mesh.hpp"

using namespace lp;
namespace fs = std::filesystem;

namespace {

struct Folder {
    fs::path dir;
    Folder() {
        dir = fs::temp_directory_path() / ("lightpass-mtl-transmission-" + std::to_string(getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    ~Folder() { fs::remove_all(dir); }
    fs::path write(const std::string& name, const std::string& text) const {
        std::ofstream(dir / name, std::ios::binary) << text;
        return dir / name;
    }
};

const Material& named(const MeshData& mesh, const std::string& name) {
    for (const Material& m : mesh.materials)
        if (m.name == name) return m;
    ADD_FAILURE() << "no material " << name;
    return mesh.materials.front();
}

// Two triangles per material: "box" spans 2 x 1 x 0.5 (thickness 0.5), "pane" is flat (0).
const char* kObj =
    "mtllib m.mtl\n"
    "v 0 0 0\nv 2 0 0\nv 2 1 0.5\nv 0 1 0.5\n"
    "v 0 0 3\nv 1 0 3\nv 1 1 3\n"
    "usemtl glass7\nf 1 2 3\nf 1 3 4\n"
    "usemtl glass6\nf 1 2 3\nf 1 3 4\n"
    "usemtl glass4\nf 1 2 3\nf 1 3 4\n"
    "usemtl opaque4\nf 1 2 3\n"
    "usemtl blended\nf 1 2 3\n"
    "usemtl pane\nf 5 6 7\n"
    "usemtl lowNi\nf 1 2 3\nf 1 3 4\n";

const char* kMtl =
    "newmtl glass7\nKd 0.01 0.01 0.01\nKs 0.3 0.3 0.3\nTf 0.1 0.5 0.9\nNi 2.5\nillum 7\n"
    "newmtl glass6\nKd 0.5 0.5 0.5\nTf 1 1 1\nNi 1.33\nillum 6\n"
    "newmtl glass4\nKd 0.2 0.4 0.6\nd 0.25\nNi 1.5\nillum 4\n"
    "newmtl opaque4\nKd 0.2 0.4 0.6\nNi 1.5\nillum 4\n"
    "newmtl blended\nKd 0.2 0.4 0.6\nd 0.5\nNi 1.5\nillum 2\n"
    "newmtl pane\nTf 1 1 1\nNi 1.5\nillum 7\n"
    "newmtl lowNi\nTf 1 1 1\nNi 0.001\nillum 7\n";

}  // namespace

TEST(MtlTransmission, GlassIlluminationModelsMapOntoTransmission) {
    Folder f;
    f.write("m.mtl", kMtl);
    MeshLoadReport report;
    const MeshData mesh = loadObj(f.write("a.obj", kObj), &report);

    const Material& g7 = named(mesh, "glass7");
    EXPECT_TRUE(g7.transmissive());
    EXPECT_EQ(g7.transmission, 1.0f);
    EXPECT_EQ(g7.diffuse, glm::vec3(0.1f, 0.5f, 0.9f)) << "illum 7: the transmitted light is filtered by Tf";
    EXPECT_FLOAT_EQ(g7.ior, 2.5f);
    EXPECT_EQ(g7.specular, glm::vec3(0.3f)) << "F0 stays Ks";
    EXPECT_EQ(g7.alphaMode, AlphaMode::Opaque) << "refracted, not blended";
    EXPECT_FLOAT_EQ(g7.thickness, 0.5f) << "the smallest extent of its triangles' box (2 x 1 x 0.5)";

    const Material& g6 = named(mesh, "glass6");
    EXPECT_EQ(g6.transmission, 1.0f);
    EXPECT_FLOAT_EQ(g6.ior, 1.33f);
    EXPECT_EQ(g6.diffuse, glm::vec3(1.0f));

    const Material& g4 = named(mesh, "glass4");
    EXPECT_FLOAT_EQ(g4.transmission, 0.75f) << "illum 4: the dissolved share 1 - d refracts";
    EXPECT_EQ(g4.opacity, 1.0f);
    EXPECT_EQ(g4.alphaMode, AlphaMode::Opaque);
    EXPECT_EQ(g4.diffuse, glm::vec3(0.2f, 0.4f, 0.6f)) << "illum 4 keeps Kd";

    EXPECT_FALSE(named(mesh, "opaque4").transmissive()) << "illum 4 with d 1 is opaque glass: nothing refracts";
    const Material& blended = named(mesh, "blended");
    EXPECT_FALSE(blended.transmissive());
    EXPECT_EQ(blended.alphaMode, AlphaMode::Blend) << "plain d < 1: alpha-blended as before";
    EXPECT_FLOAT_EQ(blended.opacity, 0.5f);

    EXPECT_EQ(named(mesh, "pane").thickness, 0.0f) << "a flat pane is thin-walled";

    const Material& low = named(mesh, "lowNi");
    EXPECT_EQ(low.ior, 1.0f) << "Ni below 1: no bend";
    bool warned = false;
    for (const std::string& w : report.warnings)
        warned |= w.find("a.obj: material 'lowNi': Ni 0.001") != std::string::npos && w.find("bends no ray") != std::string::npos;
    EXPECT_TRUE(warned) << "Ni below 1 on a glass material is one warning naming the file and material";
}

// McGuire's Cornell boxes (when /work/shared/assets or LIGHTPASS_ASSETS has them; not in CI): the
// glass sphere of CornellBox-Sphere (illum 7, Ni 2.5, Tf 0.1) is transmissive with its diameter as the
// volume's thickness; the mirror sphere (illum 5) and the walls (illum 2) are not.
TEST(MtlTransmission, McGuireGlassSphereIsTransmissive) {
    const char* env = std::getenv("LIGHTPASS_ASSETS");
    const fs::path obj = fs::path(env ? env : "/work/shared/assets") / "cornell-box-mcguire" / "CornellBox-Sphere.obj";
    if (!fs::exists(obj)) GTEST_SKIP() << obj << " is not here";
    const MeshData mesh = loadObj(obj);
    int transmissive = 0;
    for (const Material& m : mesh.materials) transmissive += m.transmissive() ? 1 : 0;
    EXPECT_EQ(transmissive, 1);
    const Material& glass = named(mesh, "rightSphere");
    EXPECT_TRUE(glass.transmissive());
    EXPECT_FLOAT_EQ(glass.ior, 2.5f);
    EXPECT_NEAR(glass.diffuse.x, 0.1f, 1e-6f);
    EXPECT_GT(glass.thickness, 0.5f) << "the sphere's diameter (about 0.6 of the 2-unit box)";
    EXPECT_LT(glass.thickness, 0.8f);
    EXPECT_FALSE(named(mesh, "leftSphere").transmissive());
}

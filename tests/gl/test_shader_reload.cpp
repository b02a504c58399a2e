// Shader hot reload on the real driver: a saved edit to a file under shaders/ rebuilds exactly the
// programs that include it, a broken edit is reported as file:line while the old programs keep
// rendering, and a good edit shows up in the next frame after Renderer::resetPasses.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/gl/shader_reload.hpp"
#include "frame/renderer.hpp"
#include "engine/scene/scene_loader.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;
namespace fs = std::filesystem;

namespace {
std::string readText(const fs::path& p) {
    std::ifstream in(p);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}
void writeText(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::trunc) << text;
    // Two saves within the file system's timestamp granularity must still differ in size or time.
    fs::last_write_time(p, fs::last_write_time(p) + std::chrono::seconds(1));
}
bool hasStage(const std::vector<gl::ProgramRecipe>& recipes, const std::string& stage) {
    return std::any_of(recipes.begin(), recipes.end(), [&](const gl::ProgramRecipe& r) {
        return std::find(r.stages.begin(), r.stages.end(), stage) != r.stages.end();
    });
}
struct TempShaderTree {
    fs::path root = fs::temp_directory_path() / ("lightpass-reload-test-" + std::to_string(::getpid()));
    TempShaderTree() {
        fs::remove_all(root);
        fs::copy(test::repoPath("shaders"), root, fs::copy_options::recursive);
    }
    ~TempShaderTree() { fs::remove_all(root); }
};
}  // namespace

TEST(ShaderReload, WatcherReportsEditedAddedAndRemovedFiles) {
    TempShaderTree tree;
    gl::ShaderFileWatcher w = gl::watchShaderFiles(tree.root);
    EXPECT_TRUE(gl::pollChangedShaderFiles(w).empty());
    writeText(tree.root / "common/post.glsl", readText(tree.root / "common/post.glsl") + "\n");
    writeText(tree.root / "extra.glsl", "// new\n");
    fs::remove(tree.root / "fill_rate.frag");
    auto changed = gl::pollChangedShaderFiles(w);
    std::sort(changed.begin(), changed.end());
    EXPECT_EQ(changed, (std::vector<std::string>{"common/post.glsl", "extra.glsl", "fill_rate.frag"}));
    EXPECT_TRUE(gl::pollChangedShaderFiles(w).empty());  // reported once
}

TEST(ShaderReload, BrokenEditKeepsOldProgramsAndGoodEditTakesEffect) {
    TempShaderTree tree;
    Scene scene = loadScene(test::repoPath("scenes/cornell.json"));
    Renderer r(scene, gl::ShaderLibrary(tree.root));
    RenderSettings s;
    s.width = 48;
    s.height = 32;
    r.render(s, 0.0f, false);
    const Image8 before = r.readDisplay();
    const long liveObjects = gl::liveObjectCount();
    ASSERT_TRUE(hasStage(r.shaders().builtPrograms(), "tonemap.comp"));
    gl::ShaderFileWatcher w = gl::watchShaderFiles(tree.root);

    // Line 3 of common/tonemap.glsl becomes a syntax error.
    const fs::path common = tree.root / "common/tonemap.glsl";
    const std::string good = readText(common);
    const size_t line3 = good.find('\n', good.find('\n') + 1) + 1;
    writeText(common, good.substr(0, line3) + "this is not glsl;\n" + good.substr(line3));
    auto changed = gl::pollChangedShaderFiles(w);
    ASSERT_EQ(changed, std::vector<std::string>{"common/tonemap.glsl"});
    gl::ShaderReloadResult broken = gl::rebuildProgramsReading(r.shaders(), changed);
    EXPECT_FALSE(broken.ok());
    EXPECT_NE(broken.error.find("common/tonemap.glsl:3:"), std::string::npos) << broken.error;
    EXPECT_TRUE(hasStage(broken.affected, "tonemap.comp"));
    ASSERT_TRUE(hasStage(r.shaders().builtPrograms(), "shadow_depth.vert"));
    EXPECT_FALSE(hasStage(broken.affected, "shadow_depth.vert"));  // includes nothing
    // The old programs are untouched: the next frame is the same image.
    r.render(s, 0.0f, false);
    EXPECT_EQ(r.readDisplay().rgba, before.rgba);

    // Restore the include and make tonemap.comp write magenta: the reload succeeds and shows it.
    writeText(common, good);
    const fs::path top = tree.root / "tonemap.comp";
    std::string src = readText(top);
    const size_t store = src.find("imageStore(uLdr, p,");
    ASSERT_NE(store, std::string::npos);
    src = src.substr(0, store) + "imageStore(uLdr, p, vec4(1.0, 0.0, 1.0, 1.0));\n}\n";
    writeText(top, src);
    changed = gl::pollChangedShaderFiles(w);
    EXPECT_EQ(changed.size(), 2u);
    gl::ShaderReloadResult fixed = gl::rebuildProgramsReading(r.shaders(), changed);
    EXPECT_TRUE(fixed.ok()) << fixed.error;
    r.resetPasses();
    r.render(s, 0.0f, false);
    const Image8 after = r.readDisplay();
    EXPECT_EQ(gl::liveObjectCount(), liveObjects);  // the dropped programs and pass state were freed
    for (size_t i = 0; i < after.rgba.size(); i += 4)
        ASSERT_TRUE(after.rgba[i] == 255 && after.rgba[i + 1] == 0 && after.rgba[i + 2] == 255) << "pixel " << i / 4;
}

// Every program the frame builds binds each texture unit, image unit and storage-buffer binding to at
// most one of its resources. Binding numbers live in #defines and C++ constants kept by hand; two
// features that pick the same number compile and link, and one of them silently reads the other's
// texture (point shadows and the clearcoat maps once shared unit 18 in the forward programs). Scenes
// that switch on the features together (clearcoat, KHR_materials_specular, alpha cut-outs, spot and
// point shadows, IBL, AO, the transparent pass) through each render path, G-buffer mode and local-light
// method, then every program they compiled is inspected on the driver.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "engine/scene/scene_loader.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;

namespace {

bool isSamplerType(GLenum t) {
    static const std::set<GLenum> kSamplers = {
        GL_SAMPLER_1D, GL_SAMPLER_2D, GL_SAMPLER_3D, GL_SAMPLER_CUBE, GL_SAMPLER_2D_SHADOW, GL_SAMPLER_2D_ARRAY,
        GL_SAMPLER_2D_ARRAY_SHADOW, GL_SAMPLER_CUBE_SHADOW, GL_SAMPLER_2D_MULTISAMPLE, GL_SAMPLER_BUFFER,
        GL_SAMPLER_CUBE_MAP_ARRAY, GL_INT_SAMPLER_2D, GL_INT_SAMPLER_3D, GL_INT_SAMPLER_2D_ARRAY, GL_UNSIGNED_INT_SAMPLER_2D,
        GL_UNSIGNED_INT_SAMPLER_3D, GL_UNSIGNED_INT_SAMPLER_2D_ARRAY, GL_UNSIGNED_INT_SAMPLER_BUFFER, GL_INT_SAMPLER_BUFFER};
    return kSamplers.count(t) > 0;
}
bool isImageType(GLenum t) {
    static const std::set<GLenum> kImages = {
        GL_IMAGE_2D, GL_IMAGE_3D, GL_IMAGE_CUBE, GL_IMAGE_2D_ARRAY, GL_IMAGE_BUFFER, GL_INT_IMAGE_2D, GL_INT_IMAGE_3D,
        GL_INT_IMAGE_2D_ARRAY, GL_UNSIGNED_INT_IMAGE_2D, GL_UNSIGNED_INT_IMAGE_3D, GL_UNSIGNED_INT_IMAGE_2D_ARRAY,
        GL_UNSIGNED_INT_IMAGE_BUFFER, GL_INT_IMAGE_BUFFER};
    return kImages.count(t) > 0;
}

// "unit 18: uClearcoatMap and uPointShadowAtlas" for each unit two resources of one kind share.
std::vector<std::string> sharedBindings(GLuint program) {
    std::map<std::string, std::map<GLint, std::set<std::string>>> used;  // kind -> binding -> names
    GLint uniforms = 0;
    glGetProgramInterfaceiv(program, GL_UNIFORM, GL_ACTIVE_RESOURCES, &uniforms);
    for (GLint i = 0; i < uniforms; ++i) {
        const GLenum props[] = {GL_TYPE, GL_ARRAY_SIZE, GL_LOCATION, GL_BLOCK_INDEX};
        GLint values[4] = {};
        glGetProgramResourceiv(program, GL_UNIFORM, GLuint(i), 4, props, 4, nullptr, values);
        const GLenum type = GLenum(values[0]);
        if (values[3] != -1 || values[2] < 0 || !(isSamplerType(type) || isImageType(type))) continue;
        char name[256] = {};
        glGetProgramResourceName(program, GL_UNIFORM, GLuint(i), sizeof name, nullptr, name);
        for (GLint element = 0; element < values[1]; ++element) {
            GLint unit = -1;
            glGetUniformiv(program, values[2] + element, &unit);
            used[isSamplerType(type) ? "texture unit" : "image unit"][unit].insert(
                std::string(name) + (values[1] > 1 ? "[" + std::to_string(element) + "]" : ""));
        }
    }
    GLint blocks = 0;
    glGetProgramInterfaceiv(program, GL_SHADER_STORAGE_BLOCK, GL_ACTIVE_RESOURCES, &blocks);
    for (GLint i = 0; i < blocks; ++i) {
        const GLenum prop = GL_BUFFER_BINDING;
        GLint binding = -1;
        glGetProgramResourceiv(program, GL_SHADER_STORAGE_BLOCK, GLuint(i), 1, &prop, 1, nullptr, &binding);
        char name[256] = {};
        glGetProgramResourceName(program, GL_SHADER_STORAGE_BLOCK, GLuint(i), sizeof name, nullptr, name);
        used["storage buffer"][binding].insert(name);
    }
    std::vector<std::string> shared;
    for (const auto& [kind, bindings] : used)
        for (const auto& [binding, names] : bindings) {
            if (names.size() < 2) continue;
            std::string list;
            for (const std::string& n : names) list += (list.empty() ? "" : " and ") + n;
            shared.push_back(kind + " " + std::to_string(binding) + ": " + list);
        }
    return shared;
}

std::string describe(const gl::ProgramRecipe& r) {
    std::string s;
    for (const std::string& stage : r.stages) s += (s.empty() ? "" : " + ") + stage;
    for (const std::string& d : r.defines) s += " -D" + d;
    return s;
}

// A scene with every local-light shadow kind added: a shadowed point light and a shadowed spot above
// the camera's target.
Scene withShadowedLocalLights(Scene s) {
    PointLight point;
    point.position = s.camera.target + glm::vec3(0.5f, 2.0f, 0.5f);
    point.range = 8.0f;
    point.intensity = 2.0f;
    point.castsShadow = true;
    s.pointLights.push_back(point);
    PointLight spot = point;
    spot.position = s.camera.target + glm::vec3(-0.5f, 2.5f, 0.5f);
    spot.spot = SpotCone{};
    spot.spot->direction = glm::vec3(0.0f, -1.0f, 0.0f);
    spot.castsShadow = true;
    s.pointLights.push_back(spot);
    return s;
}

}  // namespace

TEST(BindingUnits, NoProgramBindsTwoResourcesToOneUnit) {
    gl::ShaderLibrary shaders;
    const char* kScenes[] = {"clearcoat-spheres", "specular-spheres", "leaf-cards", "cornell", "transmission"};
    struct Variant {
        RenderPath path;
        GBufferMode gbuffer;
        LocalLightMethod lights;
    };
    const Variant kVariants[] = {{RenderPath::Deferred, GBufferMode::Classic, LocalLightMethod::Tiled},
                                 {RenderPath::Deferred, GBufferMode::Visibility, LocalLightMethod::Clustered},
                                 {RenderPath::Deferred, GBufferMode::Classic, LocalLightMethod::Volumes},
                                 {RenderPath::ForwardPlus, GBufferMode::Classic, LocalLightMethod::Clustered}};
    for (const char* name : kScenes) {
        SCOPED_TRACE(name);
        Scene scene = withShadowedLocalLights(loadScene(test::repoPath("scenes/" + std::string(name) + ".json")));
        scene.models.front().opacityOverride = 0.5f;  // the transparent pass too
        Renderer r(scene, shaders);
        for (const Variant& v : kVariants) {
            RenderSettings s;
            s.width = 48;
            s.height = 32;
            s.renderPath = v.path;
            s.gbuffer.mode = v.gbuffer;
            s.localLights.method = v.lights;
            s.environment.ibl = true;
            s.allPasses = true;
            r.render(s, 0.0f, false);
        }
    }
    // Deliberate aliases: one buffer read through two layouts.
    const std::map<std::string, std::string> kAliases = {
        {"storage buffer 0: VertexQuads and Vertices", "visibility_resolve.comp: the vertex buffer as floats and as vec4 quads"}};
    const std::vector<gl::ProgramRecipe> recipes = shaders.builtPrograms();
    EXPECT_GT(recipes.size(), 20u) << "the scenes compiled too few programs to check much";
    for (const gl::ProgramRecipe& recipe : recipes) {
        const gl::Program program = shaders.build(recipe);
        for (const std::string& shared : sharedBindings(program.id()))
            if (!kAliases.count(shared)) ADD_FAILURE() << describe(recipe) << ": " << shared;
    }
}

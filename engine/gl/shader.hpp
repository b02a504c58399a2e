#pragma once
// GLSL loading: resolves `#include "common/x.glsl"` from the shader root, inserts `#line` markers so
// the driver's error log can be mapped back to the original file and line, and injects #defines.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/gl/handles.hpp"

namespace lp::gl {

// What one compute()/graphics() call built: enough to build it again (shader hot reload).
struct ProgramRecipe {
    std::vector<std::string> stages;  // one compute file, or vertex (+ geometry) + fragment files
    std::vector<std::string> defines;
    bool operator==(const ProgramRecipe& o) const { return stages == o.stages && defines == o.defines; }
};

struct ShaderSource {
    std::string text;
    std::vector<std::string> files;  // #line source-string number -> file, relative to the root
};

// Where shaders/ lives: $LIGHTPASS_SHADER_DIR, else dataRoot()/shaders (engine/core/paths.hpp: an
// install beside the executable, the source tree it was built from, or the working directory).
std::filesystem::path findShaderRoot();

class ShaderLibrary {
public:
    explicit ShaderLibrary(std::filesystem::path root = findShaderRoot());
    const std::filesystem::path& root() const { return root_; }

    // Throws lp::Error naming the file for a missing file, a bad include or an include cycle.
    ShaderSource preprocess(const std::string& path, const std::vector<std::string>& defines = {}) const;
    // Throws lp::Error whose first line names file:line of the first error in the original source.
    Program compute(const std::string& path, const std::vector<std::string>& defines = {}) const;
    Program graphics(const std::string& vertexPath, const std::string& fragmentPath,
                     const std::vector<std::string>& defines = {}) const;
    Program graphics(const std::string& vertexPath, const std::string& geometryPath, const std::string& fragmentPath,
                     const std::vector<std::string>& defines = {}) const;
    // A compute program from source text (whose #includes resolve from the root); `name` labels it
    // in errors. The shader tests build their harness kernels this way.
    Program computeFromSource(const std::string& name, const std::string& text) const;
    // Every distinct program compute()/graphics() built successfully (copies of a library share it).
    std::vector<ProgramRecipe> builtPrograms() const { return *built_; }
    // Builds a recipe again from the current files (throws like compute()/graphics()).
    Program build(const ProgramRecipe& recipe) const;
    // The uniform names the stages of a program this library (or a copy) built declare, and its label
    // (gl::Uniforms checks names against them); null and "" for a program it did not build. The names
    // stay valid until the library builds another program of the same GL name.
    const std::vector<std::string>* declaredUniforms(GLuint program) const;
    std::string programLabel(GLuint program) const;

private:
    struct ProgramInterface {
        std::vector<std::string> uniforms;
        std::string label;
    };
    void remember(ProgramRecipe recipe) const;
    // Records a linked program's declared uniforms (a later program with the same GL name replaces it).
    void note(const Program& program, const std::vector<const ShaderSource*>& stages, const std::string& label) const;
    std::filesystem::path root_;
    std::shared_ptr<std::vector<ProgramRecipe>> built_ = std::make_shared<std::vector<ProgramRecipe>>();
    std::shared_ptr<std::map<GLuint, ProgramInterface>> programs_ = std::make_shared<std::map<GLuint, ProgramInterface>>();
};

// Rewrites "0:12(5): error" (Mesa) and "0(12) : error" (NVIDIA) to "shaders/file.glsl:12: error".
std::string mapCompileLog(const std::string& log, const std::vector<std::string>& files);

}  // namespace lp::gl

#pragma once
// Uniforms set by name through a helper that knows its program: a name no stage of the program
// declares (a typo, a uniform renamed in the shader but not in C++) is an lp::Error in checked builds
// (LIGHTPASS_GL_CHECKS, the default build and the tests), instead of a glUniform call on location -1
// that silently does nothing. A declared uniform the compiler dropped (unused in this variant) is
// skipped, as GL does.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gl/gl.hpp"

namespace lp::gl {

class ShaderLibrary;

// The names a GLSL source declares as plain uniforms (`[layout(...)] uniform T name[, name2][N];`,
// samplers and images included, uniform blocks not), sorted and unique. Declarations inside any #if
// branch count: the check is for names no variant declares.
std::vector<std::string> declaredUniforms(const std::string& source);

// Whether a uniform name as glGetUniformLocation takes it ("uX", "uX[2]", "uLights[1].color") starts
// with one of `declared` (sorted).
bool declaresUniform(const std::vector<std::string>& declared, const std::string& name);

// Whether undeclared names are checked (checked builds).
constexpr bool kUniformNamesChecked =
#ifdef LIGHTPASS_GL_CHECKS
    true;
#else
    false;
#endif

class Uniforms {
public:
    // The helper of a program `shaders` built; unchecked for a program it did not build or with
    // null. Short-lived: it points into the library's record of the program.
    Uniforms(const ShaderLibrary* shaders, GLuint program);

    GLuint program() const { return program_; }
    // glGetUniformLocation, after the check: -1 for a declared uniform the compiler dropped.
    GLint location(const std::string& name) const;

    void set(const std::string& name, bool v) const { set(name, int(v)); }
    void set(const std::string& name, int v) const;
    void set(const std::string& name, unsigned v) const;
    void set(const std::string& name, float v) const;
    void set(const std::string& name, const glm::vec2& v) const;
    void set(const std::string& name, const glm::vec3& v) const;
    void set(const std::string& name, const glm::vec4& v) const;
    void set(const std::string& name, const glm::ivec2& v) const;
    void set(const std::string& name, const glm::ivec3& v) const;
    void set(const std::string& name, const glm::ivec4& v) const;
    void set(const std::string& name, const glm::uvec2& v) const;
    void set(const std::string& name, const glm::mat3& v) const;
    void set(const std::string& name, const glm::mat4& v) const;
    // Arrays: `count` elements from `values`.
    void setArray(const std::string& name, const float* values, int count) const;
    void setArray(const std::string& name, const int* values, int count) const;
    void setArray(const std::string& name, const glm::vec2* values, int count) const;
    void setArray(const std::string& name, const glm::vec3* values, int count) const;
    void setArray(const std::string& name, const glm::vec4* values, int count) const;
    void setArray(const std::string& name, const glm::mat3* values, int count) const;
    void setArray(const std::string& name, const glm::mat4* values, int count) const;

private:
    GLuint program_;
    const ShaderLibrary* shaders_;                 // names the program in the error
    const std::vector<std::string>* declared_;     // null: unchecked
};

}  // namespace lp::gl

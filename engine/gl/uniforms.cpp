#include "engine/gl/uniforms.hpp"

#include <algorithm>
#include <cctype>

#include <glm/gtc/type_ptr.hpp>

#include "engine/core/error.hpp"
#include "engine/gl/shader.hpp"

namespace lp::gl {

namespace {

bool identifierChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// The source without comments (declarations split by a comment still read whole).
std::string withoutComments(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (size_t i = 0; i < s.size();) {
        if (s.compare(i, 2, "//") == 0) {
            while (i < s.size() && s[i] != '\n') ++i;
        } else if (s.compare(i, 2, "/*") == 0) {
            const size_t end = s.find("*/", i + 2);
            i = end == std::string::npos ? s.size() : end + 2;
            out += ' ';
        } else {
            out += s[i++];
        }
    }
    return out;
}

// The identifiers a declaration's text (after `uniform`, up to its ';') names: the last identifier of
// each comma-separated part before any '[' or '='.
void declaredNames(const std::string& decl, std::vector<std::string>& out) {
    int depth = 0;
    std::string part;
    auto finish = [&] {
        std::string last, word;
        for (size_t i = 0; i <= part.size(); ++i) {
            const char c = i < part.size() ? part[i] : ' ';
            if (c == '[' || c == '=') break;
            if (identifierChar(c)) word += c;
            else if (!word.empty()) {
                last = word;
                word.clear();
            }
        }
        if (!word.empty()) last = word;
        if (!last.empty() && !std::isdigit(static_cast<unsigned char>(last[0]))) out.push_back(last);
        part.clear();
    };
    for (char c : decl) {
        if (c == '(' || c == '[') ++depth;
        if (c == ')' || c == ']') --depth;
        if (c == ',' && depth == 0) finish();
        else part += c;
    }
    finish();
}

}  // namespace

std::vector<std::string> declaredUniforms(const std::string& source) {
    const std::string s = withoutComments(source);
    std::vector<std::string> names;
    for (size_t at = s.find("uniform"); at != std::string::npos; at = s.find("uniform", at + 7)) {
        if ((at > 0 && identifierChar(s[at - 1])) || (at + 7 < s.size() && identifierChar(s[at + 7]))) continue;
        const size_t end = s.find_first_of(";{", at);
        if (end == std::string::npos) break;
        if (s[end] == '{') continue;  // a uniform block: its members are set through a buffer
        declaredNames(s.substr(at + 7, end - at - 7), names);
    }
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    return names;
}

bool declaresUniform(const std::vector<std::string>& declared, const std::string& name) {
    const std::string base = name.substr(0, name.find_first_of("[."));
    return std::binary_search(declared.begin(), declared.end(), base);
}

Uniforms::Uniforms(const ShaderLibrary* shaders, GLuint program)
    : program_(program), shaders_(shaders), declared_(shaders ? shaders->declaredUniforms(program) : nullptr) {}

GLint Uniforms::location(const std::string& name) const {
    const GLint at = glGetUniformLocation(program_, name.c_str());
    if (kUniformNamesChecked && at < 0 && declared_ && !declaresUniform(*declared_, name))
        throw Error("shader program " + shaders_->programLabel(program_) + " declares no uniform '" + name +
                    "' (set from C++)");
    return at;
}

void Uniforms::set(const std::string& name, int v) const { glProgramUniform1i(program_, location(name), v); }
void Uniforms::set(const std::string& name, unsigned v) const { glProgramUniform1ui(program_, location(name), v); }
void Uniforms::set(const std::string& name, float v) const { glProgramUniform1f(program_, location(name), v); }
void Uniforms::set(const std::string& name, const glm::vec2& v) const {
    glProgramUniform2fv(program_, location(name), 1, glm::value_ptr(v));
}
void Uniforms::set(const std::string& name, const glm::vec3& v) const {
    glProgramUniform3fv(program_, location(name), 1, glm::value_ptr(v));
}
void Uniforms::set(const std::string& name, const glm::vec4& v) const {
    glProgramUniform4fv(program_, location(name), 1, glm::value_ptr(v));
}
void Uniforms::set(const std::string& name, const glm::ivec2& v) const {
    glProgramUniform2iv(program_, location(name), 1, glm::value_ptr(v));
}
void Uniforms::set(const std::string& name, const glm::ivec3& v) const {
    glProgramUniform3iv(program_, location(name), 1, glm::value_ptr(v));
}
void Uniforms::set(const std::string& name, const glm::ivec4& v) const {
    glProgramUniform4iv(program_, location(name), 1, glm::value_ptr(v));
}
void Uniforms::set(const std::string& name, const glm::uvec2& v) const {
    glProgramUniform2uiv(program_, location(name), 1, glm::value_ptr(v));
}
void Uniforms::set(const std::string& name, const glm::mat3& v) const {
    glProgramUniformMatrix3fv(program_, location(name), 1, GL_FALSE, glm::value_ptr(v));
}
void Uniforms::set(const std::string& name, const glm::mat4& v) const {
    glProgramUniformMatrix4fv(program_, location(name), 1, GL_FALSE, glm::value_ptr(v));
}
void Uniforms::setArray(const std::string& name, const float* values, int count) const {
    const GLint at = location(name);
    if (count <= 0) return;
    glProgramUniform1fv(program_, at, count, values);
}
void Uniforms::setArray(const std::string& name, const int* values, int count) const {
    const GLint at = location(name);
    if (count <= 0) return;
    glProgramUniform1iv(program_, at, count, values);
}
void Uniforms::setArray(const std::string& name, const glm::vec2* values, int count) const {
    const GLint at = location(name);
    if (count <= 0) return;
    glProgramUniform2fv(program_, at, count, glm::value_ptr(values[0]));
}
void Uniforms::setArray(const std::string& name, const glm::vec3* values, int count) const {
    const GLint at = location(name);
    if (count <= 0) return;
    glProgramUniform3fv(program_, at, count, glm::value_ptr(values[0]));
}
void Uniforms::setArray(const std::string& name, const glm::vec4* values, int count) const {
    const GLint at = location(name);
    if (count <= 0) return;
    glProgramUniform4fv(program_, at, count, glm::value_ptr(values[0]));
}
void Uniforms::setArray(const std::string& name, const glm::mat3* values, int count) const {
    const GLint at = location(name);
    if (count <= 0) return;
    glProgramUniformMatrix3fv(program_, at, count, GL_FALSE, glm::value_ptr(values[0]));
}
void Uniforms::setArray(const std::string& name, const glm::mat4* values, int count) const {
    const GLint at = location(name);
    if (count <= 0) return;
    glProgramUniformMatrix4fv(program_, at, count, GL_FALSE, glm::value_ptr(values[0]));
}

}  // namespace lp::gl

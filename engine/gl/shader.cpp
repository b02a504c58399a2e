#include "engine/gl/shader.hpp"

#include <algorithm>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/core/paths.hpp"
#include "engine/gl/uniforms.hpp"

namespace lp::gl {
namespace fs = std::filesystem;

fs::path findShaderRoot() {
    if (const char* env = std::getenv("LIGHTPASS_SHADER_DIR")) return fs::path(env);
    return dataRoot() / "shaders";
}

ShaderLibrary::ShaderLibrary(fs::path root) : root_(std::move(root)) {}

namespace {

std::string readFile(const fs::path& path, const std::string& shown) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("shaders/" + shown + ": file not found (shader root " + path.parent_path().string() + ")");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

struct Expander {
    const fs::path& root;
    ShaderSource& out;
    std::vector<std::string> stack;
    std::set<std::string> included;

    void expand(const std::string& rel, bool isRoot, const std::vector<std::string>& defines,
                const std::string* sourceText = nullptr) {
        for (const auto& s : stack)
            if (s == rel) throw Error("shaders/" + rel + ": #include cycle");
        if (!isRoot && included.count(rel)) return;  // each include once, like #pragma once
        included.insert(rel);
        const std::string text = sourceText ? *sourceText : readFile(root / rel, rel);
        const int index = int(out.files.size());
        out.files.push_back(rel);
        stack.push_back(rel);
        std::istringstream lines(text);
        std::string line;
        int number = 0;
        static const std::regex includeRe(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
        while (std::getline(lines, line)) {
            ++number;
            std::smatch m;
            if (isRoot && number == 1) {
                if (line.rfind("#version", 0) != 0)
                    throw Error("shaders/" + rel + ":1: the first line must be #version");
                out.text += line + "\n";
                for (const auto& d : defines) out.text += "#define " + d + "\n";
                out.text += "#line 2 " + std::to_string(index) + "\n";
                continue;
            }
            if (std::regex_match(line, m, includeRe)) {
                std::string target = m[1].str();
                if (!fs::exists(root / target)) {
                    // Also allow paths relative to the including file.
                    fs::path alt = fs::path(rel).parent_path() / target;
                    if (fs::exists(root / alt)) target = alt.lexically_normal().generic_string();
                    else
                        throw Error("shaders/" + rel + ":" + std::to_string(number) + ": #include \"" + m[1].str() +
                                    "\": file not found");
                }
                out.text += "#line 1 " + std::to_string(out.files.size()) + "\n";
                expand(target, false, defines);
                out.text += "#line " + std::to_string(number + 1) + " " + std::to_string(index) + "\n";
                continue;
            }
            out.text += line + "\n";
        }
        stack.pop_back();
    }
};

Shader compileStage(GLenum stage, const ShaderSource& src, const std::string& name) {
    Shader shader(glCreateShader(stage));
    const char* text = src.text.c_str();
    glShaderSource(shader.id(), 1, &text, nullptr);
    glCompileShader(shader.id());
    GLint ok = 0;
    glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetShaderiv(shader.id(), GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(std::max(len, 1)), '\0');
        glGetShaderInfoLog(shader.id(), len, nullptr, log.data());
        std::string mapped = mapCompileLog(log.c_str(), src.files);
        while (!mapped.empty() && (mapped.back() == '\n' || mapped.back() == '\0')) mapped.pop_back();
        throw Error("shader compile failed: " + mapped + (mapped.find('\n') == std::string::npos ? "" : "") +
                    " [" + name + "]");
    }
    return shader;
}

Program link(const std::vector<const Shader*>& stages, const std::string& name) {
    Program program(glCreateProgram());
    for (auto* s : stages) glAttachShader(program.id(), s->id());
    glLinkProgram(program.id());
    for (auto* s : stages) glDetachShader(program.id(), s->id());
    GLint ok = 0;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(std::max(len, 1)), '\0');
        glGetProgramInfoLog(program.id(), len, nullptr, log.data());
        throw Error("shader link failed for " + name + ": " + std::string(log.c_str()));
    }
    label(GL_PROGRAM, program.id(), name);
    return program;
}

}  // namespace

ShaderSource ShaderLibrary::preprocess(const std::string& path, const std::vector<std::string>& defines) const {
    ShaderSource out;
    Expander{root_, out, {}, {}}.expand(path, true, defines);
    return out;
}

Program ShaderLibrary::compute(const std::string& path, const std::vector<std::string>& defines) const {
    const ShaderSource src = preprocess(path, defines);
    Shader cs = compileStage(GL_COMPUTE_SHADER, src, path);
    Program program = link({&cs}, path);
    note(program, {&src}, path);
    remember({{path}, defines});
    return program;
}

Program ShaderLibrary::computeFromSource(const std::string& name, const std::string& text) const {
    ShaderSource src;
    Expander{root_, src, {}, {}}.expand(name, true, {}, &text);
    Shader cs = compileStage(GL_COMPUTE_SHADER, src, name);
    Program program = link({&cs}, name);
    note(program, {&src}, name);
    return program;
}

Program ShaderLibrary::graphics(const std::string& vertexPath, const std::string& fragmentPath,
                                const std::vector<std::string>& defines) const {
    const ShaderSource vsrc = preprocess(vertexPath, defines), fsrc = preprocess(fragmentPath, defines);
    Shader vs = compileStage(GL_VERTEX_SHADER, vsrc, vertexPath);
    Shader fs = compileStage(GL_FRAGMENT_SHADER, fsrc, fragmentPath);
    Program program = link({&vs, &fs}, vertexPath + "+" + fragmentPath);
    note(program, {&vsrc, &fsrc}, vertexPath + "+" + fragmentPath);
    remember({{vertexPath, fragmentPath}, defines});
    return program;
}

Program ShaderLibrary::graphics(const std::string& vertexPath, const std::string& geometryPath,
                                const std::string& fragmentPath, const std::vector<std::string>& defines) const {
    const ShaderSource vsrc = preprocess(vertexPath, defines), gsrc = preprocess(geometryPath, defines),
                       fsrc = preprocess(fragmentPath, defines);
    Shader vs = compileStage(GL_VERTEX_SHADER, vsrc, vertexPath);
    Shader gs = compileStage(GL_GEOMETRY_SHADER, gsrc, geometryPath);
    Shader fs = compileStage(GL_FRAGMENT_SHADER, fsrc, fragmentPath);
    const std::string label = vertexPath + "+" + geometryPath + "+" + fragmentPath;
    Program program = link({&vs, &gs, &fs}, label);
    note(program, {&vsrc, &gsrc, &fsrc}, label);
    remember({{vertexPath, geometryPath, fragmentPath}, defines});
    return program;
}

Program ShaderLibrary::build(const ProgramRecipe& recipe) const {
    if (recipe.stages.size() == 1) return compute(recipe.stages[0], recipe.defines);
    if (recipe.stages.size() == 2) return graphics(recipe.stages[0], recipe.stages[1], recipe.defines);
    if (recipe.stages.size() == 3) return graphics(recipe.stages[0], recipe.stages[1], recipe.stages[2], recipe.defines);
    throw Error("program recipe needs 1 (compute), 2 (vertex, fragment) or 3 (vertex, geometry, fragment) stages");
}

void ShaderLibrary::note(const Program& program, const std::vector<const ShaderSource*>& stages,
                         const std::string& label) const {
    std::string all;
    for (const ShaderSource* s : stages) all += s->text + "\n";
    (*programs_)[program.id()] = {gl::declaredUniforms(all), label};
}

const std::vector<std::string>* ShaderLibrary::declaredUniforms(GLuint program) const {
    const auto it = programs_->find(program);
    return it == programs_->end() ? nullptr : &it->second.uniforms;
}

std::string ShaderLibrary::programLabel(GLuint program) const {
    const auto it = programs_->find(program);
    return it == programs_->end() ? std::string() : it->second.label;
}

void ShaderLibrary::remember(ProgramRecipe recipe) const {
    if (std::find(built_->begin(), built_->end(), recipe) == built_->end()) built_->push_back(std::move(recipe));
}

std::string mapCompileLog(const std::string& log, const std::vector<std::string>& files) {
    static const std::regex mesa(R"(^(\d+):(\d+)\(\d+\):)");
    static const std::regex nvidia(R"(^(\d+)\((\d+)\)\s*:)");
    std::istringstream in(log);
    std::string line, out;
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_search(line, m, mesa) || std::regex_search(line, m, nvidia)) {
            size_t file = std::stoul(m[1].str());
            std::string name = file < files.size() ? "shaders/" + files[file] : "source " + m[1].str();
            line = name + ":" + m[2].str() + ":" + m.suffix().str();
        }
        if (!out.empty()) out += "\n";
        out += line;
    }
    return out;
}

}  // namespace lp::gl

// gl::Uniforms on the driver: values reach the program, a declared uniform the compiler dropped is
// skipped, and a name the program does not declare is an error naming the program (checked builds).
#include <gtest/gtest.h>

#include <string>

#include "engine/core/error.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/uniforms.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;

namespace {
const char* kKernel = R"(#version 450
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Out { vec4 values[]; };
uniform float uScale;
uniform vec3 uOffset;
uniform int uCount;
uniform float uUnused;  // declared, never read: the compiler drops it
void main() { values[0] = vec4(uOffset * uScale, float(uCount)); }
)";
}  // namespace

TEST(Uniforms, SetValuesReachTheProgram) {
    gl::ShaderLibrary shaders;
    const gl::Program program = shaders.computeFromSource("uniforms_test.comp", kKernel);
    const gl::Uniforms u(&shaders, program.id());
    u.set("uScale", 2.0f);
    u.set("uOffset", glm::vec3(1.0f, 2.0f, 3.0f));
    u.set("uCount", 7);
    float scale = 0.0f;
    glGetUniformfv(program.id(), u.location("uScale"), &scale);
    EXPECT_EQ(scale, 2.0f);
    glm::vec3 offset(0.0f);
    glGetUniformfv(program.id(), u.location("uOffset"), &offset.x);
    EXPECT_EQ(offset, glm::vec3(1.0f, 2.0f, 3.0f));
    int count = 0;
    glGetUniformiv(program.id(), u.location("uCount"), &count);
    EXPECT_EQ(count, 7);
}

TEST(Uniforms, ADroppedUniformIsSkippedAndAnUndeclaredOneIsAnError) {
    gl::ShaderLibrary shaders;
    const gl::Program program = shaders.computeFromSource("uniforms_test.comp", kKernel);
    const gl::Uniforms u(&shaders, program.id());
    EXPECT_NO_THROW(u.set("uUnused", 1.0f)) << "declared but dropped by the compiler: as GL does, nothing happens";
    if (!gl::kUniformNamesChecked) {
        EXPECT_NO_THROW(u.set("uScael", 1.0f)) << "unchecked build";
        return;
    }
    try {
        u.set("uScael", 1.0f);
        FAIL() << "a misspelt uniform name was accepted";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("uScael"), std::string::npos) << what;
        EXPECT_NE(what.find("uniforms_test.comp"), std::string::npos) << what;
    }
    // A program some other code built is not checked (nothing is known of its source).
    EXPECT_NO_THROW(gl::Uniforms(nullptr, program.id()).set("uScael", 1.0f));
}

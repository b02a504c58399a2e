// gl::declaredUniforms: the uniform names a GLSL source declares, which gl::Uniforms checks every name
// set from C++ against (a typo is an error in checked builds).
#include <gtest/gtest.h>

#include "engine/gl/uniforms.hpp"

using namespace lp;

TEST(UniformNames, DeclarationsOfEveryFormAreRead) {
    const std::string source = R"(
#version 450
layout(binding = 3) uniform sampler2D uAlbedo;
uniform float uExposure;  // a comment: uniform float uCommented;
uniform vec3 uLightDir[4], uLightColor[4];
layout(location = 2) uniform mat4
    uModel;
/* uniform int uBlockComment; */
uniform Camera { mat4 view; } uCamera;
#ifdef LP_VARIANT
uniform int uOnlyInAVariant;
#endif
uniform int uDefault = 2;
float notAUniform;
int uniformity;
)";
    const std::vector<std::string> names = gl::declaredUniforms(source);
    const std::vector<std::string> expected = {"uAlbedo", "uDefault", "uExposure", "uLightColor", "uLightDir",
                                               "uModel", "uOnlyInAVariant"};
    EXPECT_EQ(names, expected);
}

TEST(UniformNames, ElementsAndMembersNameTheirArray) {
    const std::vector<std::string> declared = {"uLightDir", "uLights", "uScale"};
    EXPECT_TRUE(gl::declaresUniform(declared, "uScale"));
    EXPECT_TRUE(gl::declaresUniform(declared, "uLightDir[3]"));
    EXPECT_TRUE(gl::declaresUniform(declared, "uLights[1].color"));
    EXPECT_FALSE(gl::declaresUniform(declared, "uScal"));
    EXPECT_FALSE(gl::declaresUniform(declared, "uScales"));
    EXPECT_FALSE(gl::declaresUniform(declared, "uLight"));
}

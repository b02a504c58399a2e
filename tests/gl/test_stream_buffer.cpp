// gl::StreamBuffer: each fill lands in a buffer no command issued before it still reads, so every
// dispatch reads exactly the fill made just before it, however far the GPU runs behind (on an H100 a
// glNamedBufferSubData into a storage buffer did not wait for earlier dispatches that read it).
#include <gtest/gtest.h>

#include <vector>

#include "engine/gl/handles.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/stream_buffer.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;

namespace {
// Reads the fill (binding 0) after some busy work, so the GPU runs behind the CPU's next fills, and
// writes what it read to its slot of the output (binding 1).
const char* kReader = R"(#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Fill { uint uFill[]; };
layout(std430, binding = 1) buffer Out { uint uOut[]; };
uniform uint uSlot;
uniform uint uWords;
void main() {
    uint i = gl_LocalInvocationIndex;
    float busy = float(i);
    for (int k = 0; k < 4000; ++k) busy = fract(busy * 1.0001 + 0.37);
    if (i == 0u) {
        uint sum = 0u;
        for (uint w = 0u; w < uWords; ++w) sum += uFill[w] * (w + 1u);
        uOut[uSlot] = busy > 2.0 ? 0u : sum;  // busy never exceeds 1: keeps the loop
    }
}
)";
}  // namespace

TEST(StreamBuffer, EveryDispatchReadsTheFillMadeJustBeforeIt) {
    gl::ShaderLibrary shaders;
    gl::Program reader = shaders.computeFromSource("stream_buffer_reader.comp", kReader);
    constexpr int kFills = 48;
    constexpr GLuint kWords = 2048;  // 8 KiB a fill
    gl::Buffer out = gl::makeBuffer(kFills * sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT, "test.stream_out");
    gl::StreamBuffer stream("test.stream");
    std::vector<GLuint> expected(kFills);
    glUseProgram(reader.id());
    glUniform1ui(glGetUniformLocation(reader.id(), "uWords"), kWords);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
    for (int f = 0; f < kFills; ++f) {
        std::vector<GLuint> words(kWords);
        GLuint sum = 0;
        for (GLuint w = 0; w < kWords; ++w) {
            words[w] = GLuint(f) * 7919u + w;
            sum += words[w] * (w + 1u);
        }
        expected[size_t(f)] = sum;
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, stream.fill(words.data(), words.size() * sizeof(GLuint)));
        glUniform1ui(glGetUniformLocation(reader.id(), "uSlot"), GLuint(f));
        glDispatchCompute(64, 1, 1);  // no wait between fills: the GPU may be several fills behind
    }
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<GLuint> got(kFills);
    glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(got.size() * sizeof(GLuint)), got.data());
    glUseProgram(0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    for (int f = 0; f < kFills; ++f) EXPECT_EQ(got[size_t(f)], expected[size_t(f)]) << "dispatch " << f;
    std::printf("  %zu buffers in the ring after %d fills without a wait\n", stream.buffers(), kFills);
}

// When the GPU keeps up (every fill's readers finished), the ring reuses its buffers: two at most
// (the current one is never refilled in place).
TEST(StreamBuffer, RingStaysSmallWhenTheGpuKeepsUp) {
    gl::StreamBuffer stream("test.stream");
    GLuint previous = 0;
    for (int f = 0; f < 50; ++f) {
        const GLuint words[4] = {GLuint(f), 1, 2, 3};
        const GLuint id = stream.fill(words, sizeof(words));
        EXPECT_NE(id, 0u);
        if (f > 0) EXPECT_NE(id, previous) << "the current buffer is never refilled in place";
        previous = id;
        EXPECT_EQ(stream.current(), id);
        glFinish();
    }
    EXPECT_LE(stream.buffers(), 2u);
    // The last fill's contents are what the buffer holds.
    GLuint back[4] = {};
    glGetNamedBufferSubData(stream.current(), 0, sizeof(back), back);
    EXPECT_EQ(back[0], 49u);
}

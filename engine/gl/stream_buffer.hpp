#pragma once
// A buffer the CPU refills (every frame, or several times a frame) while commands issued earlier may
// still read what it held. Shader storage and indirect reads are not ordered with a later
// glNamedBufferSubData of the same buffer: on an H100 (driver 580) the next frame's update of the
// local lights' SSBO landed under the previous frame's lighting while it still ran, so some pixels
// were lit by lights of the wrong frame and TAA's history carried it on (final images differed
// between runs). So each fill goes to a buffer that no command issued so far reads: a ring of
// buffers, each fenced when the fill after it begins (every command that read it was issued by
// then) and filled again only once that fence has signaled. The ring grows while all its buffers are
// in flight, so it holds about (frames in flight) x (fills per frame) buffers.
#include <cstddef>
#include <string>
#include <vector>

#include "engine/gl/handles.hpp"

namespace lp::gl {

class StreamBuffer {
public:
    explicit StreamBuffer(std::string label = "stream") : label_(std::move(label)) {}
    // Copies `bytes` of `data` into a buffer no command issued so far reads and returns it (for
    // binding); it stays valid until the next fill. 0 bytes gives a small buffer with undefined data.
    GLuint fill(const void* data, size_t bytes);
    // The last fill's buffer; 0 before the first.
    GLuint current() const { return current_ < 0 ? 0 : slots_[size_t(current_)].buffer.id(); }
    // Buffers in the ring (each made by a fill that found every other one still in flight).
    size_t buffers() const { return slots_.size(); }

private:
    struct Slot {
        Buffer buffer;
        size_t capacity = 0;
        Fence readers;  // after the commands that read this buffer's contents; empty while current
    };
    std::string label_;
    std::vector<Slot> slots_;
    int current_ = -1;
};

}  // namespace lp::gl

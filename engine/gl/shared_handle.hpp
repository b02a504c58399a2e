#pragma once
// A GL object several owners draw from: the last one to go deletes it (the buffers of a mesh that
// several instances draw). Reads like the handle it holds: id(), and false when empty.
#include <memory>
#include <utility>

#include "engine/gl/handles.hpp"

namespace lp::gl {

template <class Handle>
class Shared {
public:
    Shared() = default;
    // Implicit, so that `mesh.vertices = gl::makeBuffer(...)` takes the buffer over.
    Shared(Handle&& handle) : handle_(std::make_shared<Handle>(std::move(handle))) {}
    GLuint id() const { return handle_ ? handle_->id() : 0; }
    explicit operator bool() const { return id() != 0; }

private:
    std::shared_ptr<const Handle> handle_;
};

}  // namespace lp::gl

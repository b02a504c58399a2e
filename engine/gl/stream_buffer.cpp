#include "engine/gl/stream_buffer.hpp"

#include <algorithm>

namespace lp::gl {

GLuint StreamBuffer::fill(const void* data, size_t bytes) {
    // Everything that read the current contents was issued before this call.
    if (current_ >= 0) slots_[size_t(current_)].readers = Fence::insert();
    int pick = -1;
    const int n = int(slots_.size());
    // Never the current buffer itself (its fence was inserted just now), so two fills in a row
    // always use two buffers; the others oldest first, from the one after the current.
    for (int k = 1; k < n && pick < 0; ++k) {
        const int i = (current_ + k) % n;
        if (!slots_[size_t(i)].readers || slots_[size_t(i)].readers.signaled()) pick = i;
    }
    if (pick < 0) {
        slots_.emplace_back();
        pick = int(slots_.size()) - 1;
    }
    Slot& s = slots_[size_t(pick)];
    const size_t need = std::max<size_t>(bytes, 16);
    if (!s.buffer || s.capacity < need) {
        // Room for growth, so a count that creeps up does not remake the buffer every frame.
        s.capacity = std::max(need, s.capacity + s.capacity / 2);
        s.buffer = makeBuffer(GLsizeiptr(s.capacity), nullptr, GL_DYNAMIC_STORAGE_BIT, label_);
    }
    if (bytes > 0) glNamedBufferSubData(s.buffer.id(), 0, GLsizeiptr(bytes), data);
    s.readers = Fence();
    current_ = pick;
    return s.buffer.id();
}

}  // namespace lp::gl

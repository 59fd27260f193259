// Bytes appended through a pointer. The text writers format billions of modules: room is
// made once per module (room()), the module is written without a check per byte, and
// commit() takes what was written. A buffer cleared and refilled keeps its memory and
// never fills it with zeros again, as a std::string resized for each piece would.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <ostream>
#include <string>
#include <string_view>

namespace graftal {

class ByteBuffer {
  public:
    // The capacity is reserved, not filled: a short text touches only the pages it uses.
    ByteBuffer() = default;
    explicit ByteBuffer(std::size_t capacity) { bytes_.reserve(capacity); }
    std::size_t size() const { return used_; }
    bool empty() const { return used_ == 0; }
    void clear() { used_ = 0; }
    // A pointer with room for `n` more bytes after what is written; commit(end) takes them.
    char* room(std::size_t n) {
        if (used_ + n > bytes_.size()) bytes_.resize(std::max(bytes_.size() * 2, used_ + n));
        return bytes_.data() + used_;
    }
    void commit(char* end) { used_ = static_cast<std::size_t>(end - bytes_.data()); }
    void append(const char* p, std::size_t n) {
        std::memcpy(room(n), p, n);
        used_ += n;
    }
    void append(std::string_view s) { append(s.data(), s.size()); }
    const char* data() const { return bytes_.data(); }
    std::string_view view() const { return {bytes_.data(), used_}; }
    void writeTo(std::ostream& out) const {
        out.write(bytes_.data(), static_cast<std::streamsize>(used_));
    }

  private:
    std::string bytes_;
    std::size_t used_ = 0;
};

}  // namespace graftal

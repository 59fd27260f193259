// Matching-bracket positions of a module string, computed once per derivation step so
// that context search jumps over whole branches instead of rescanning them.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "graftal/core/module_string.hpp"

namespace graftal {

class BracketIndex {
  public:
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;

    // For each '[' the position of its ']' (or kNone if unclosed), for each ']' the
    // position of its '[' (or kNone); other positions are not read.
    void build(std::span<const Symbol> symbols);
    std::uint32_t match(std::size_t i) const { return match_[i]; }

  private:
    std::vector<std::uint32_t, UninitializedAllocator<std::uint32_t>> match_;
    std::vector<std::uint32_t> stack_;
};

}  // namespace graftal

#include "bracket_index.hpp"

namespace graftal {

void BracketIndex::build(std::span<const Symbol> symbols) {
    match_.resize(symbols.size());
    stack_.clear();
    for (std::size_t i = 0; i < symbols.size(); ++i) {
        Symbol s = symbols[i];
        if (s == '[') {
            stack_.push_back(static_cast<std::uint32_t>(i));
            match_[i] = kNone;
        } else if (s == ']') {
            if (stack_.empty()) {
                match_[i] = kNone;
            } else {
                std::uint32_t open = stack_.back();
                stack_.pop_back();
                match_[i] = open;
                match_[open] = static_cast<std::uint32_t>(i);
            }
        }
    }
}

}  // namespace graftal

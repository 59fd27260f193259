// The closest of a few known words to a misspelt one, for "did you mean" messages.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

namespace graftal::lang {

// Levenshtein distance: insertions, deletions and substitutions, each costing one.
inline std::size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

// The word of `known` nearest `word`, when it is near enough to be a misspelling of it (a
// quarter of its letters wrong, at least two allowed); empty otherwise.
inline std::string closestWord(std::string_view word, const std::vector<std::string>& known) {
    std::string best;
    std::size_t bestDistance = std::string::npos;
    for (const auto& k : known) {
        std::size_t d = editDistance(word, k);
        if (d < bestDistance) bestDistance = d, best = k;
    }
    if (best.empty() || bestDistance > std::max<std::size_t>(2, best.size() / 4)) return {};
    return best;
}

}  // namespace graftal::lang

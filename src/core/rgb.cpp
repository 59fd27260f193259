#include "graftal/core/rgb.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace graftal {

std::string hexColor(const Rgb& c) {
    static const char kDigits[] = "0123456789abcdef";
    std::string s = "#";
    for (float v : {c.r, c.g, c.b}) {
        const float clamped = std::isfinite(v) ? std::fmin(std::fmax(v, 0.0f), 1.0f) : 0.0f;
        const int byte = static_cast<int>(std::lround(clamped * 255.0f));
        s += kDigits[byte >> 4];
        s += kDigits[byte & 15];
    }
    return s;
}

std::ostream& operator<<(std::ostream& os, const Rgb& c) {
    return os << hexColor(c);
}

}  // namespace graftal

#include "graftal/rgb.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace graftal {

std::ostream& operator<<(std::ostream& os, const Rgb& c) {
    auto byte = [](float v) {
        return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255));
    };
    const char* digits = "0123456789abcdef";
    std::string s = "#";
    for (int b : {byte(c.r), byte(c.g), byte(c.b)}) {
        s += digits[b >> 4];
        s += digits[b & 15];
    }
    return os << s;
}

}  // namespace graftal

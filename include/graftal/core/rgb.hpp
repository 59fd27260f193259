// A colour, as the palettes, the view settings and every writer hold it.
#pragma once

#include <ostream>
#include <string>

namespace graftal {

struct Rgb {
    float r = 0, g = 0, b = 0;  // each in [0, 1]

    friend bool operator==(const Rgb&, const Rgb&) = default;
};

// "#rrggbb", as SVG and cpfg's colour files write it; components are clamped to [0, 1]
// and a NaN counts as 0.
std::string hexColor(const Rgb& c);
std::ostream& operator<<(std::ostream& os, const Rgb& c);  // #rrggbb

}  // namespace graftal

// A colour, as the palettes, the view settings and every writer hold it.
#pragma once

#include <ostream>

namespace graftal {

struct Rgb {
    float r = 0, g = 0, b = 0;  // each in [0, 1]

    friend bool operator==(const Rgb&, const Rgb&) = default;
};

std::ostream& operator<<(std::ostream& os, const Rgb& c);  // #rrggbb

}  // namespace graftal

#include "graftal/core/vec3.hpp"

namespace graftal {

namespace {

// Adding +0.0 turns -0.0 into 0.0, so a turtle that turned by exactly 180 degrees does not
// print "(-0, 1, 0)".
double unsigned0(double v) {
    return v + 0.0;
}

}  // namespace

std::ostream& operator<<(std::ostream& os, const Vec3& v) {
    return os << '(' << unsigned0(v.x) << ", " << unsigned0(v.y) << ", " << unsigned0(v.z) << ')';
}

}  // namespace graftal

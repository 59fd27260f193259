// The small readers, checks and printers the view-setting table's rows are written with
// (view_settings.cpp): a setting's value by kind, numbers and vectors as .l text.
#pragma once

#include <cctype>
#include <cmath>
#include <ostream>
#include <string>
#include <string_view>
#include <variant>

#include "graftal/core/module_string.hpp"
#include "graftal/core/vec3.hpp"
#include "graftal/lang/parser_target.hpp"

namespace graftal::view_setting_values {

inline bool isZero(const Vec3& v) {
    return v.x == 0 && v.y == 0 && v.z == 0;
}

inline std::string lowerCase(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

inline double number(const ViewSetting& s) {
    return std::get<double>(s.value);
}
inline const Vec3& vector(const ViewSetting& s) {
    return std::get<Vec3>(s.value);
}
inline const std::string& text(const ViewSetting& s) {
    return std::get<std::string>(s.value);
}

inline bool isWhole(double d) {
    return d == std::floor(d);
}

// ---- printing -------------------------------------------------------------------------

inline std::string num(double d) {
    return formatNumber(d);
}
inline std::string vec(const Vec3& v) {
    return num(v.x) + ", " + num(v.y) + ", " + num(v.z);
}
inline void line(std::ostream& os, std::string_view name, const std::string& value) {
    os << name << ": " << value << '\n';
}

// ---- checks ---------------------------------------------------------------------------

// A direction stored as a unit vector (the tropisms and the torque).
inline std::string unitDirection(const ViewSetting& s, Vec3& out) {
    const Vec3& v = vector(s);
    double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (n == 0) return "the " + s.name + " must not be zero";
    out = {v.x / n, v.y / n, v.z / n};
    return "";
}

}  // namespace graftal::view_setting_values

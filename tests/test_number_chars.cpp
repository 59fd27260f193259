// The numbers' text where the standard library has no floating-point to_chars/from_chars
// (the web build): the same characters as std::to_chars, the same values as std::from_chars.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "graftal/core/number_chars.hpp"

namespace {

std::string standardText(double v) {
    char buf[64];
    return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

std::string printfText(double v) {
    char buf[64];
    return std::string(buf, graftal::printfNumberToChars(buf, buf + sizeof buf, v).ptr);
}

std::string standardText(float v) {
    char buf[64];
    return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

std::string printfText(float v) {
    char buf[64];
    return std::string(buf, graftal::printfNumberToChars(buf, buf + sizeof buf, v).ptr);
}

}  // namespace

TEST(NumberChars, FallbackWritesWhatToCharsWrites) {
    for (double v : {0.1, 1e-4, 0.0001234, 123.0, 1e15, 1e16, 1e22, 1e23, 1.2345678901234567e20,
                     -2.5, 5e-324, 1.7976931348623157e308, 1.0 / 3, 100.0, -0.0, 86.60254037844386})
        EXPECT_EQ(printfText(v), standardText(v)) << v;
    EXPECT_EQ(printfText(0.1), "0.1");
    EXPECT_EQ(printfText(1e-4), "1e-04");
    EXPECT_EQ(printfText(1e23), "1e+23");
    EXPECT_EQ(printfText(0.1f), "0.1");
    std::mt19937_64 random(7);
    for (int i = 0; i < 20000; ++i) {
        std::uint64_t bits = random();
        double v;
        std::memcpy(&v, &bits, sizeof v);
        if (!std::isfinite(v)) continue;
        ASSERT_EQ(printfText(v), standardText(v));
        const double turtle = std::ldexp(static_cast<double>(random() % 100000), int(random() % 40) - 20);
        ASSERT_EQ(printfText(turtle), standardText(turtle));
        ASSERT_EQ(printfText(static_cast<float>(turtle)), standardText(static_cast<float>(turtle)));
    }
}

TEST(NumberChars, FallbackReadsWhatFromCharsReads) {
    for (const char* text : {"1.5", "-0.25e3", ".5", "5.", "1e", "1e+", "12abc", "inf", "-nan",
                             "0x10", "1e400", "3.14159265358979323846"}) {
        double a = -1, b = -1;
        const std::size_t n = std::strlen(text);
        const auto x = graftal::strtodNumberFromChars(text, text + n, a);
        const auto y = std::from_chars(text, text + n, b);
        EXPECT_EQ(x.ptr - text, y.ptr - text) << text;
        EXPECT_EQ(x.ec, y.ec) << text;
        if (x.ec == std::errc() && !std::isnan(a)) {
            EXPECT_EQ(a, b) << text;
        }
    }
    double v = 0;
    EXPECT_EQ(graftal::strtodNumberFromChars("+1", "+1" + 2, v).ec, std::errc::invalid_argument);
    EXPECT_EQ(graftal::strtodNumberFromChars(" 1", " 1" + 2, v).ec, std::errc::invalid_argument);
}

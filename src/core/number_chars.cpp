// std::to_chars and std::from_chars for floating point, or their equivalent from printf and
// strtod where the standard library lacks them (number_chars.hpp).
#include "graftal/core/number_chars.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <system_error>

namespace graftal {

namespace {

// The shortest digits d1 d2 ... dn and exponent e (v = d1.d2...dn × 10^e) that read back as
// v, from %e at growing precision; `Real` decides what "reads back" means.
template <class Real>
void shortestDigits(Real v, std::string& digits, int& exponent) {
    char buf[64];
    for (int precision = 0; precision <= 17; ++precision) {
        std::snprintf(buf, sizeof buf, "%.*e", precision, static_cast<double>(v));
        const Real back = static_cast<Real>(std::strtod(buf, nullptr));
        if (back == v || precision == 17) break;
    }
    // buf: [-]d[.ddd]e±xx
    const char* p = buf[0] == '-' ? buf + 1 : buf;
    digits.clear();
    for (; *p != 'e'; ++p)
        if (*p != '.') digits += *p;
    exponent = std::atoi(p + 1);
    while (digits.size() > 1 && digits.back() == '0') digits.pop_back();
}

template <class Real>
std::to_chars_result shortest(char* first, char* last, Real v) {
    std::string text;
    if (std::isnan(v)) {
        text = std::signbit(v) ? "-nan" : "nan";
    } else if (std::isinf(v)) {
        text = v < 0 ? "-inf" : "inf";
    } else if (v == 0) {
        text = std::signbit(v) ? "-0" : "0";
    } else {
        std::string digits;
        int e = 0;
        shortestDigits(v, digits, e);
        const int n = static_cast<int>(digits.size());
        // Scientific: d[.ddd]e±XX (at least two exponent digits, as printf writes them).
        std::string scientific = digits.substr(0, 1);
        if (n > 1) scientific += "." + digits.substr(1);
        // A double's exponent has at most three digits; the room is for any int's.
        char exponentText[16];
        std::snprintf(exponentText, sizeof exponentText, "e%c%02d", e < 0 ? '-' : '+',
                      e < 0 ? -e : e);
        scientific += exponentText;
        // Fixed: the digits placed around the point, padded with zeros.
        std::string fixed;
        if (e < 0) {
            fixed = "0." + std::string(static_cast<std::size_t>(-e - 1), '0') + digits;
        } else if (e + 1 >= n) {
            // A whole number: %f prints its exact value, which past 2^53 is not the digits
            // padded with zeros (1e23 is 99999999999999991611392), as std::to_chars does.
            char whole[400];
            std::snprintf(whole, sizeof whole, "%.0f", std::fabs(static_cast<double>(v)));
            fixed = whole;
        } else {
            fixed = digits.substr(0, static_cast<std::size_t>(e + 1)) + "." +
                    digits.substr(static_cast<std::size_t>(e + 1));
        }
        text = fixed.size() <= scientific.size() ? fixed : scientific;
        if (v < 0) text.insert(text.begin(), '-');
    }
    if (static_cast<std::ptrdiff_t>(text.size()) > last - first)
        return {last, std::errc::value_too_large};
    std::memcpy(first, text.data(), text.size());
    return {first + text.size(), std::errc()};
}

bool isDigit(char c) { return c >= '0' && c <= '9'; }

}  // namespace

std::to_chars_result printfNumberToChars(char* first, char* last, double v) {
    return shortest(first, last, v);
}

std::to_chars_result printfNumberToChars(char* first, char* last, float v) {
    return shortest(first, last, v);
}

std::from_chars_result strtodNumberFromChars(const char* first, const char* last, double& v) {
    // The general format's grammar, checked here; strtod only converts what it accepts.
    const char* p = first;
    if (p < last && *p == '-') ++p;
    const auto word = [&](const char* w) {
        const std::size_t n = std::strlen(w);
        if (static_cast<std::size_t>(last - p) < n) return false;
        for (std::size_t i = 0; i < n; ++i)
            if ((p[i] | 0x20) != w[i]) return false;
        return true;
    };
    const char* end = nullptr;
    if (word("infinity")) {
        end = p + 8;
    } else if (word("inf")) {
        end = p + 3;
    } else if (word("nan")) {
        end = p + 3;
    } else {
        const char* q = p;
        bool any = false;
        while (q < last && isDigit(*q)) ++q, any = true;
        if (q < last && *q == '.') {
            ++q;
            while (q < last && isDigit(*q)) ++q, any = true;
        }
        if (!any) return {first, std::errc::invalid_argument};
        if (q < last && (*q == 'e' || *q == 'E')) {
            const char* r = q + 1;
            if (r < last && (*r == '+' || *r == '-')) ++r;
            if (r < last && isDigit(*r)) {
                while (r < last && isDigit(*r)) ++r;
                q = r;
            }
        }
        end = q;
    }
    const std::string text(first, end);
    errno = 0;
    const double parsed = std::strtod(text.c_str(), nullptr);
    if (errno == ERANGE && (std::isinf(parsed) || parsed == 0))
        return {end, std::errc::result_out_of_range};
    v = parsed;
    return {end, std::errc()};
}

#ifdef GRAFTAL_FLOAT_CHARCONV_FALLBACK

std::to_chars_result numberToChars(char* first, char* last, double v) {
    return printfNumberToChars(first, last, v);
}

std::to_chars_result numberToChars(char* first, char* last, float v) {
    return printfNumberToChars(first, last, v);
}

std::from_chars_result numberFromChars(const char* first, const char* last, double& v) {
    return strtodNumberFromChars(first, last, v);
}

#else

std::to_chars_result numberToChars(char* first, char* last, double v) {
    return std::to_chars(first, last, v);
}

std::to_chars_result numberToChars(char* first, char* last, float v) {
    return std::to_chars(first, last, v);
}

std::from_chars_result numberFromChars(const char* first, const char* last, double& v) {
    return std::from_chars(first, last, v);
}

#endif

}  // namespace graftal

// cpfg's printf formatting: C's conversions applied to the doubles an expression computes
// (printf and fprintf in expressions).
#include "graftal/lang/expression.hpp"

#include <cstdio>
#include <cstring>
#include <string>

namespace graftal {

// C's printf conversions applied to doubles: %d %i %c %o %x %u take the value as an
// integer, %e %f %g as a double; %% is a percent sign.
std::string formatPrintf(std::string_view format, std::span<const double> values) {
    std::string out;
    std::size_t next = 0;
    for (std::size_t i = 0; i < format.size(); ++i) {
        if (format[i] != '%') {
            out += format[i];
            continue;
        }
        std::size_t start = i++;
        while (i < format.size() && std::strchr("-+ #0123456789.lh", format[i])) ++i;
        if (i >= format.size()) {
            out += format.substr(start);
            break;
        }
        char conv = format[i];
        if (conv == '%') {
            out += '%';
            continue;
        }
        std::string spec(format.substr(start, i - start));
        std::erase_if(spec, [](char c) { return c == 'l' || c == 'h'; });
        double v = next < values.size() ? values[next++] : 0.0;
        char buf[512];
        if (std::strchr("diouxXc", conv)) {
            spec += std::strchr("di", conv) ? "lld" : conv == 'c' ? "c" : std::string("ll") + conv;
            if (conv == 'c')
                std::snprintf(buf, sizeof buf, spec.c_str(), static_cast<int>(v));
            else
                std::snprintf(buf, sizeof buf, spec.c_str(), static_cast<long long>(v));
        } else if (std::strchr("eEfFgGaA", conv)) {
            spec += conv;
            std::snprintf(buf, sizeof buf, spec.c_str(), v);
        } else {
            out += format.substr(start, i - start + 1);
            continue;
        }
        out += buf;
    }
    return out;
}

}  // namespace graftal

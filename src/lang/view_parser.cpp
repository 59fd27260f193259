// The view settings of a .l file: turn angle, step, and how 3D scenes are drawn (camera,
// light, stems, tropism, surfaces, colour map). cpfg keeps the latter in a separate view
// file; graftal reads them from the L-system file with the same names.
#include <cctype>
#include <cmath>

#include "parser.hpp"
#include "view_setting_table.hpp"

namespace graftal::parsing {

// "x, y, z" or "x y z": three constant expressions.
bool Parser::vectorValue(const SourceLine& line, std::size_t from, Vec3& out) {
    std::string_view text = std::string_view(line.text).substr(from);
    std::vector<std::pair<std::size_t, std::size_t>> parts;  // offsets into text
    bool commas = findTopLevel(text, ',') != std::string_view::npos;
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
        if (i >= text.size()) break;
        std::size_t end = commas ? findTopLevel(text, ',', i) : text.find_first_of(" \t", i);
        if (end == std::string_view::npos) end = text.size();
        parts.push_back({i, end});
        i = end + (commas ? 1 : 0);
    }
    if (parts.size() != 3) {
        diags_.error(at(line, from + (parts.empty() ? 0 : parts[0].first)),
                     "expected three numbers x, y, z");
        return false;
    }
    double v[3];
    for (int k = 0; k < 3; ++k) {
        auto [a, b] = parts[static_cast<std::size_t>(k)];
        std::string_view piece = trimView(text.substr(a, b - a));
        ExpressionScope scope;
        scope.defines = &defines_;
        DiagnosticList local;
        std::size_t lead = firstNonBlank(text.substr(a, b - a));
        Expression e = compileExpression(
            piece, at(line, from + a + (lead == std::string_view::npos ? 0 : lead)), scope, local);
        for (const auto& d : local.items()) diags_.add(d);
        if (e.empty()) return false;
        // As in constantValue: a value that cannot be computed (a modulo by zero) is a
        // diagnostic of the parse, not an exception out of it.
        try {
            v[k] = e.evaluate({});
        } catch (const Error& err) {
            for (const auto& d : err.diagnostics()) diags_.add(d);
            return false;
        }
        if (!std::isfinite(v[k])) {
            diags_.error(at(line, from + a), "not a finite number");
            return false;
        }
    }
    out = {v[0], v[1], v[2]};
    return true;
}

// Reads the value of a view setting by its kind in the table (a vector, a word or text, a
// number) and hands it to the target by name, which checks it (view_settings.cpp).
bool Parser::parseViewSetting(const SourceLine& line, const std::string& kw,
                              std::size_t valueStart) {
    const ViewSettingDescriptor* descriptor = findLFileSetting(kw);
    if (!descriptor) return false;
    std::string_view rest = std::string_view(line.text).substr(valueStart);
    std::string_view value = trimView(rest);
    std::size_t lead = firstNonBlank(rest);
    if (kw == "surface") {
        std::string_view name = value.substr(0, value.find_first_of(" \t"));
        if (name.size() == 1) surfaceLetters_ += name[0];
    }
    ViewSetting setting;
    setting.name = kw;
    setting.location = at(line, valueStart + (lead == std::string_view::npos ? 0 : lead));
    setting.location.endLine = line.number;
    setting.location.endColumn = setting.location.column + static_cast<int>(value.size());
    switch (descriptor->value) {
        case SettingValue::Vector: {
            Vec3 v;
            if (!vectorValue(line, valueStart, v)) return true;
            setting.value = v;
            break;
        }
        case SettingValue::Number: {
            double d = 0;
            if (!constantValue(line, valueStart, d)) return true;
            setting.value = d;
            break;
        }
        case SettingValue::Word:
        case SettingValue::FileOrWord:
        case SettingValue::File:
        case SettingValue::None:
            setting.value = std::string(value);
            break;
    }
    target_.viewSetting(setting);
    return true;
}

}  // namespace graftal::parsing

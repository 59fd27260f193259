// The view settings of a .l file that describe how 3D scenes are drawn: camera, light,
// stems, tropism, surfaces, colour map. cpfg keeps these in a separate view file; graftal
// reads them from the L-system file with the same names.
#include <cctype>
#include <cmath>

#include "parser.hpp"

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
        scope.defines = &ls_.defines;
        DiagnosticList local;
        std::size_t lead = firstNonBlank(text.substr(a, b - a));
        Expression e = compileExpression(
            piece, at(line, from + a + (lead == std::string_view::npos ? 0 : lead)), scope, local);
        for (const auto& d : local.items()) diags_.add(d);
        if (e.empty()) return false;
        v[k] = e.evaluate({});
        if (!std::isfinite(v[k])) {
            diags_.error(at(line, from + a), "not a finite number");
            return false;
        }
    }
    out = {v[0], v[1], v[2]};
    return true;
}

bool Parser::parseViewSetting(const SourceLine& line, const std::string& kw,
                              std::size_t valueStart) {
    ViewSettings& view = ls_.view;
    std::string_view value = trimView(std::string_view(line.text).substr(valueStart));
    std::size_t lead = firstNonBlank(std::string_view(line.text).substr(valueStart));
    SourceLocation loc = at(line, valueStart + (lead == std::string_view::npos ? 0 : lead));
    std::string word = lower(value);
    Vec3 v;
    double d = 0;
    if (kw == "viewpoint") {
        if (vectorValue(line, valueStart, v)) view.viewpoint = v;
    } else if (kw == "view reference point") {
        if (vectorValue(line, valueStart, v)) view.viewReferencePoint = v;
    } else if (kw == "up vector") {
        if (!vectorValue(line, valueStart, v)) return true;
        if (v.x == 0 && v.y == 0 && v.z == 0) {
            diags_.error(loc, "the up vector must not be zero");
            return true;
        }
        view.upVector = v;
    } else if (kw == "light direction") {
        if (!vectorValue(line, valueStart, v)) return true;
        if (v.x == 0 && v.y == 0 && v.z == 0) {
            diags_.error(loc, "the light direction must not be zero");
            return true;
        }
        view.lightDirection = v;
    } else if (kw == "tropism direction") {
        if (!vectorValue(line, valueStart, v)) return true;
        double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
        if (n == 0) {
            diags_.error(loc, "the tropism direction must not be zero");
            return true;
        }
        view.tropism = Vec3{v.x / n, v.y / n, v.z / n};
    } else if (kw == "tropism elasticity" || kw == "initial elasticity" || kw == "elasticity") {
        if (constantValue(line, valueStart, d)) view.elasticity = d;
    } else if (kw == "projection") {
        if (word == "parallel" || word == "orthographic")
            view.parallelProjection = true;
        else if (word == "perspective")
            view.parallelProjection = false;
        else
            diags_.error(
                loc, "projection is 'perspective' or 'parallel', not '" + std::string(value) + "'");
    } else if (kw == "field of view") {
        if (!constantValue(line, valueStart, d)) return true;
        if (d <= 0 || d >= 180) {
            diags_.error(loc, "field of view must be between 0 and 180 degrees");
            return true;
        }
        view.fieldOfView = d;
    } else if (kw == "line style") {
        if (word == "cylinder" || word == "cylinders" || word == "polygon")
            view.lineStyle = LineStyle::Cylinders;
        else if (word == "lines" || word == "line" || word == "pixel")
            view.lineStyle = LineStyle::Lines;
        else
            diags_.error(loc,
                         "line style is 'cylinder' or 'lines', not '" + std::string(value) + "'");
    } else if (kw == "spline subdivisions") {
        if (!constantValue(line, valueStart, d)) return true;
        if (d < 0 || d > 64 || d != std::floor(d)) {
            diags_.error(loc,
                         "spline subdivisions is a whole number from 0 (straight lines) to 64");
            return true;
        }
        view.splineSubdivisions = static_cast<int>(d);
    } else if (kw == "line width") {
        if (!constantValue(line, valueStart, d)) return true;
        if (d <= 0) {
            diags_.error(loc, "line width must be positive (the stem diameter in model units)");
            return true;
        }
        view.initialWidth = d;
    } else if (kw == "width factor") {
        if (!constantValue(line, valueStart, d)) return true;
        if (d <= 0 || d >= 1) {
            diags_.error(loc, "width factor must be between 0 and 1 (what ! multiplies by)");
            return true;
        }
        view.widthFactor = d;
    } else if (kw == "background") {
        std::string hex(value.substr(value.starts_with("#") ? 1 : 0));
        bool ok =
            hex.size() == 6 && hex.find_first_not_of("0123456789abcdefABCDEF") == std::string::npos;
        if (!ok) {
            diags_.error(loc, "background is a colour #rrggbb");
            return true;
        }
        unsigned c = static_cast<unsigned>(std::stoul(hex, nullptr, 16));
        view.background =
            Rgb{((c >> 16) & 255) / 255.0f, ((c >> 8) & 255) / 255.0f, (c & 255) / 255.0f};
    } else if (kw == "color map" || kw == "colour map") {
        if (value.empty())
            diags_.error(loc, "expected a .map file name");
        else
            view.colorMap = std::string(value);
    } else if (kw == "surface") {
        // surface: NAME FILE [SCALE]
        std::vector<std::string> words;
        std::string cur;
        for (char c : value) {
            if (std::isspace(static_cast<unsigned char>(c))) {
                if (!cur.empty()) words.push_back(std::move(cur)), cur.clear();
            } else {
                cur += c;
            }
        }
        if (!cur.empty()) words.push_back(cur);
        if (words.size() < 2 || words.size() > 3) {
            diags_.error(loc,
                         "expected 'surface: NAME FILE [SCALE]', e.g. 'surface: l leaf.s 0.5'");
            return true;
        }
        SurfaceDeclaration s{words[0], words[1], 1, loc};
        if (words.size() == 3) {
            char* end = nullptr;
            s.scale = std::strtod(words[2].c_str(), &end);
            if (*end || !(s.scale > 0)) {
                diags_.error(loc, "the surface scale must be a positive number");
                return true;
            }
        }
        view.surfaces.push_back(std::move(s));
    } else {
        return false;
    }
    return true;
}

}  // namespace graftal::parsing

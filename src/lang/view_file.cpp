// Reading cpfg's view file. Each line is "name: value"; the names and how each writes its
// value are the view-file spellings of the settings' table (view_settings.cpp), so
// "initial color:" and "initial colour:" both work, and a number may be followed by a unit
// word ("initial line width: 3 pixels"). The values are handed to the target under the
// settings' names.
#include "graftal/lang/view_file.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <vector>

#include "view_setting_table.hpp"

namespace graftal {

namespace {

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

bool isBlank(char c) {
    return c == ' ' || c == '\t' || c == '\r';
}

std::string_view trimBlanks(std::string_view s) {
    while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
    while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
    return s;
}

class ViewFileReader {
  public:
    ViewFileReader(const std::string& file, ParserTarget& target, DiagnosticList& diags)
        : file_(file), target_(target), diags_(diags) {}

    void line(std::string_view text, int lineNumber) {
        number_ = lineNumber;
        text_ = text;
        std::size_t colon = text.find(':');
        std::size_t first = 0;
        while (first < text.size() && isBlank(text[first])) ++first;
        if (first == text.size()) return;
        if (text.substr(first).starts_with("//")) return;
        std::string name = colon == std::string_view::npos
                               ? std::string()
                               : lower(text.substr(first, colon - first));
        while (!name.empty() && isBlank(name.back())) name.pop_back();
        const CpfgSpelling* spelling = nullptr;
        const ViewSettingDescriptor* known = findViewFileSetting(name, spelling);
        if (!known) {
            diags_.warning(at(first, text.size()),
                           "unknown view-file line '" + std::string(trim(text)) + "', ignored");
            return;
        }
        const std::string setting(known->name);
        const std::string cpfgName(spelling->name.empty() ? known->name : spelling->name);
        std::size_t value = colon + 1;
        while (value < text.size() && isBlank(text[value])) ++value;
        switch (spelling->syntax) {
            case CpfgSyntax::NotCpfg:
                diags_.warning(at(first, colon),
                               "'" + name + ":' is ignored: " + std::string(known->note));
                return;
            case CpfgSyntax::Ignored:
                diags_.warning(at(first, colon), "'" + name + ":' is read but not drawn: " +
                                                     std::string(known->note));
                return;
            case CpfgSyntax::Same:
                if (known->value == SettingValue::Number) {
                    if (auto d = number(value, cpfgName)) send(setting, *d, value);
                } else if (known->value == SettingValue::Vector) {
                    if (auto v = vector(value, cpfgName)) send(setting, *v, value);
                } else {
                    send(setting, std::string(trim(text.substr(value))), value);
                }
                return;
            case CpfgSyntax::Percent: {
                // cpfg's scale factor is the share of the window the picture fills (0.9);
                // graftal's, as pfg's, is in percent.
                if (auto d = number(value, cpfgName)) send(setting, *d * 100, value);
                return;
            }
            case CpfgSyntax::WidthWithUnit: {
                auto d = number(value, cpfgName);
                if (d) send(setting, *d, value);
                if (d) lineWidthUnit(value);
                return;
            }
            case CpfgSyntax::PolygonizationLevel: {
                // cpfg: the stems' sides are 2^(level + 1), at least 3.
                auto d = number(value, cpfgName);
                if (d) send(setting, std::max(3.0, std::round(std::pow(2.0, *d + 1))), value);
                return;
            }
            case CpfgSyntax::TenthsOfDegree: {
                // cpfg gives the twist in tenths of a degree.
                auto d = number(value, cpfgName);
                if (d) send(setting, *d / 10, value);
                return;
            }
            case CpfgSyntax::StyleWithUnit: {
                send(setting, std::string(trim(text.substr(value))), value);
                // cpfg: pixel lines, or polygons and cylinders as wide as the world width.
                std::string style = lower(trim(text.substr(value)));
                send("cpfg line width unit",
                     std::string(style.starts_with("pixel") ? "pixels" : "model"), value);
                return;
            }
            case CpfgSyntax::Fields:
                fields(value, setting);
                return;
            case CpfgSyntax::Light:
                light(value);
                return;
        }
    }

  private:
    static std::string_view trim(std::string_view s) {
        while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
        while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
        return s;
    }

    SourceLocation at(std::size_t from, std::size_t to) const {
        SourceLocation loc{file_, number_, static_cast<int>(from) + 1};
        loc.endLine = number_;
        loc.endColumn = static_cast<int>(std::max(to, from + 1)) + 1;
        return loc;
    }

    std::size_t tokenEnd(std::size_t from) const {
        std::size_t e = from;
        while (e < text_.size() && !isBlank(text_[e]) && text_[e] != ',') ++e;
        return e;
    }

    // A number at `from`; a unit word after it is allowed (cpfg's "3 pixels").
    std::optional<double> numberAt(std::size_t& from, const std::string& setting,
                                   const char* expected) {
        while (from < text_.size() && isBlank(text_[from])) ++from;
        std::size_t end = tokenEnd(from);
        std::string token(text_.substr(from, end - from));
        char* stop = nullptr;
        double d = token.empty() ? 0 : std::strtod(token.c_str(), &stop);
        if (token.empty() || *stop || !std::isfinite(d)) {
            diags_.error(at(from, end),
                         "'" + setting + "': expected " + expected +
                             (token.empty() ? ", found nothing" : ", found '" + token + "'"));
            return std::nullopt;
        }
        from = end;
        return d;
    }

    std::optional<double> number(std::size_t from, const std::string& setting) {
        return numberAt(from, setting, "a number");
    }

    // "x,y,z" or "x y z".
    std::optional<Vec3> vectorAt(std::size_t& from, const std::string& setting) {
        double v[3];
        for (int k = 0; k < 3; ++k) {
            if (k > 0) {
                while (from < text_.size() && isBlank(text_[from])) ++from;
                if (from < text_.size() && text_[from] == ',') ++from;
            }
            auto d = numberAt(from, setting, "three numbers x, y, z");
            if (!d) return std::nullopt;
            v[k] = *d;
        }
        return Vec3{v[0], v[1], v[2]};
    }

    std::optional<Vec3> vector(std::size_t from, const std::string& setting) {
        return vectorAt(from, setting);
    }

    // cpfg's `initial line width: W [UNIT]`: a word starting with p (`pixels`) keeps the
    // width in pixels; without one (cpfg then draws polygons) or with another (s: cylinders)
    // the width is in world units.
    void lineWidthUnit(std::size_t from) {
        while (from < text_.size() && isBlank(text_[from])) ++from;
        from = tokenEnd(from);  // past the number
        while (from < text_.size() && isBlank(text_[from])) ++from;
        const bool pixels =
            from < text_.size() && std::tolower(static_cast<unsigned char>(text_[from])) == 'p';
        send("cpfg line width unit", std::string(pixels ? "pixels" : "model"), from);
    }

    // cpfg's new-style tropism and torque lines: fields "T: x,y,z", "E: e" and for tropisms
    // "A:", "I:", "S:" (angle, intensity, elasticity step), in any order.
    void fields(std::size_t from, const std::string& setting) {
        std::optional<Vec3> direction;
        std::optional<double> elasticity, step;
        std::size_t start = from;
        while (from < text_.size()) {
            while (from < text_.size() && (isBlank(text_[from]) || text_[from] == ',')) ++from;
            if (from >= text_.size()) break;
            char field = static_cast<char>(std::toupper(static_cast<unsigned char>(text_[from])));
            std::size_t colon = from + 1;
            while (colon < text_.size() && isBlank(text_[colon])) ++colon;
            if (colon >= text_.size() || text_[colon] != ':' ||
                std::string("TAIES").find(field) == std::string::npos) {
                diags_.error(at(from, tokenEnd(from)),
                             "'" + setting + ":' expects fields T: x,y,z  E: e" +
                                 (setting == "tropism" ? "  (and A:, I:, S:)" : ""));
                return;
            }
            from = colon + 1;
            if (field == 'T') {
                direction = vectorAt(from, setting);
                if (!direction) return;
            } else {
                auto d = numberAt(from, setting, "a number after the field name");
                if (!d) return;
                if (field == 'E') elasticity = d;
                if (field == 'S') step = d;
            }
        }
        if (!direction) {
            diags_.error(at(start, text_.size()), "'" + setting + ":' needs a direction T: x,y,z");
            return;
        }
        // Each `tropism:` and `torque:` line adds one to the others of its kind.
        std::string name = setting + " line";
        send(name + " direction", *direction, start);
        send(name + " elasticity", elasticity.value_or(0), start);
        if (step && *step != 0)
            diags_.warning(at(start, text_.size()),
                           "'" + setting + ":' S: (elasticity step) is read but not drawn yet");
    }

    // cpfg's `light:` lines: fields V: x,y,z (a light far away in that direction) or O: x,y,z
    // (a light at that point), A:, D:, S: r g b (ambient, diffuse, specular) and P: (a
    // spot's five numbers), the colon optional. graftal's ray tracer has one sun and a sky:
    // the first light gives the sun's direction (towards O: seen from the origin), its
    // strength (D:) and the sky's (A:); later lights are warned and not drawn.
    void light(std::size_t from) {
        if (++lights_ > 1) {
            diags_.warning(at(from, text_.size()),
                           "'light:' after the first is read but not drawn: graftal's ray "
                           "tracer has one sun");
            return;
        }
        std::size_t start = from;
        while (from < text_.size()) {
            while (from < text_.size() && (isBlank(text_[from]) || text_[from] == ',')) ++from;
            if (from >= text_.size()) break;
            char field = static_cast<char>(std::toupper(static_cast<unsigned char>(text_[from])));
            std::size_t after = from + 1;
            if (std::string("VOADSP").find(field) == std::string::npos ||
                (after < text_.size() && !isBlank(text_[after]) && text_[after] != ':' &&
                 !std::isdigit(static_cast<unsigned char>(text_[after])) && text_[after] != '-' &&
                 text_[after] != '.')) {
                diags_.error(at(from, tokenEnd(from)),
                             "'light:' expects fields V: x,y,z or O: x,y,z, and A:, D:, S: "
                             "r g b, P: (a spot's five numbers)");
                return;
            }
            from = after;
            while (from < text_.size() && isBlank(text_[from])) ++from;
            if (from < text_.size() && text_[from] == ':') ++from;
            if (field == 'P') {
                for (int k = 0; k < 5; ++k) {
                    if (!numberAt(from, "light", "five numbers after P:")) return;
                    while (from < text_.size() && (isBlank(text_[from]) || text_[from] == ','))
                        ++from;
                }
                diags_.warning(at(start, text_.size()),
                               "'light:' P: (a spot light) is read but not drawn");
                continue;
            }
            auto v = vectorAt(from, "light");
            if (!v) return;
            if (field == 'V' || field == 'O') {
                if (v->x == 0 && v->y == 0 && v->z == 0) {
                    diags_.error(at(start, text_.size()), "'light:' direction must not be zero");
                    return;
                }
                send("light direction", *v, start);
            } else if (field == 'D') {
                send("light intensity", (v->x + v->y + v->z) / 3, start);
            } else if (field == 'A') {
                send("sky intensity", (v->x + v->y + v->z) / 3, start);
            }
        }
    }

    void send(const std::string& name, std::variant<double, Vec3, std::string> value,
              std::size_t from) {
        std::size_t end = text_.size();
        while (end > from && isBlank(text_[end - 1])) --end;
        target_.viewSetting(ViewSetting{name, std::move(value), at(from, end)});
    }

    std::string file_;
    ParserTarget& target_;
    DiagnosticList& diags_;
    std::string_view text_;
    int number_ = 0;
    int lights_ = 0;  // `light:` lines seen
};

// The view file with its comments (`/* ... */`, also over several lines) turned into
// blanks, newlines kept so that lines and columns stay the user's. cpfg skips them where
// it looks for a setting's name, and models comment settings out and write notes after
// values ("line style: cylinder /* pixel, polygon or cylinder */").
std::string blankComments(std::string_view text) {
    std::string out(text);
    for (std::size_t i = 0; i + 1 < out.size(); ++i) {
        if (out[i] == '/' && out[i + 1] == '*') {
            std::size_t end = out.find("*/", i + 2);
            end = end == std::string::npos ? out.size() : end + 2;
            for (std::size_t k = i; k < end; ++k)
                if (out[k] != '\n') out[k] = ' ';
            i = end - 1;
        }
    }
    return out;
}

}  // namespace

std::vector<std::string> viewFileValues(std::string_view original, std::string_view wanted) {
    const std::string blanked = blankComments(original);
    std::vector<std::string> values;
    std::size_t at = 0;
    while (at < blanked.size()) {
        std::size_t end = blanked.find('\n', at);
        if (end == std::string::npos) end = blanked.size();
        std::string_view line = std::string_view(blanked).substr(at, end - at);
        at = end + 1;
        std::size_t colon = line.find(':');
        if (colon == std::string_view::npos) continue;
        if (lower(trimBlanks(line.substr(0, colon))) != wanted) continue;
        values.emplace_back(trimBlanks(line.substr(colon + 1)));
    }
    return values;
}

bool viewFileGivesBox(std::string_view text) {
    return !viewFileValues(text, "box").empty();
}

std::string viewFileSurfaceLetters(std::string_view original) {
    std::string letters;
    for (const std::string& rest : viewFileValues(original, "surface")) {
        std::size_t stop = 0;
        while (stop < rest.size() && !isBlank(rest[stop])) ++stop;
        if (stop == 1) letters += rest[0];
    }
    return letters;
}

void parseViewFileInto(std::string_view original, const std::string& fileName, ParserTarget& target,
                       DiagnosticList& diagnostics) {
    const std::string blanked = blankComments(original);
    std::string_view text = blanked;
    ViewFileReader reader(fileName, target, diagnostics);
    int number = 0;
    std::size_t at = 0;
    while (at <= text.size()) {
        std::size_t end = text.find('\n', at);
        if (end == std::string_view::npos) end = text.size();
        ++number;
        if (end > at || end < text.size()) reader.line(text.substr(at, end - at), number);
        at = end + 1;
    }
}

}  // namespace graftal

// Finding a view setting in the table by the name a file gives it, applying a value to the
// settings, and printing all settings as .l lines and view-file lines.
#include <sstream>
#include <variant>

#include "graftal/lang/parser_target.hpp"
#include "view_setting_table.hpp"

namespace graftal {

namespace {

// The .l lines, or with `viewFile` the view-file lines, of the settings.
void printSettings(std::ostream& os, const ViewSettings& v, bool viewFile) {
    for (const auto& d : viewSettingTable())
        if (d.print && d.inLFile() != viewFile) d.print(os, v);
}

}  // namespace

const ViewSettingDescriptor* findLFileSetting(std::string_view name) {
    for (const auto& d : viewSettingTable()) {
        if (!d.inLFile()) continue;
        if (d.name == name) return &d;
        for (auto a : d.aliases)
            if (a == name) return &d;
    }
    return nullptr;
}

const ViewSettingDescriptor* findViewFileSetting(std::string_view name,
                                                 const CpfgSpelling*& spelling) {
    static const CpfgSpelling same{};
    for (const auto& d : viewSettingTable()) {
        if (!d.inViewFile()) continue;
        if (d.cpfg.empty() && d.name == name) {
            spelling = &same;
            return &d;
        }
        for (const auto& s : d.cpfg)
            if (s.name == name) {
                spelling = &s;
                return &d;
            }
    }
    return nullptr;
}

const std::vector<std::string>& lFileSettingNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const auto& d : viewSettingTable()) {
            if (!d.inLFile()) continue;
            out.emplace_back(d.name);
            for (auto a : d.aliases) out.emplace_back(a);
        }
        return out;
    }();
    return names;
}

const std::vector<std::string>& viewSettingNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const auto& d : viewSettingTable()) {
            if (!d.apply) continue;
            out.emplace_back(d.name);
            for (auto a : d.aliases) out.emplace_back(a);
        }
        return out;
    }();
    return names;
}

std::string applyViewSetting(ViewSettings& view, const ViewSetting& setting) {
    const std::string& kw = setting.name;
    const ViewSettingDescriptor* found = nullptr;
    for (const auto& d : viewSettingTable()) {
        if (d.name == kw) found = &d;
        for (auto a : d.aliases)
            if (a == kw) found = &d;
        if (found) break;
    }
    if (!found || !found->apply) return "unknown view setting '" + kw + "'";
    switch (found->value) {
        case SettingValue::Vector:
            if (!std::holds_alternative<Vec3>(setting.value))
                return "'" + kw + ":' expects three numbers x, y, z";
            break;
        case SettingValue::Word:
            if (!std::holds_alternative<std::string>(setting.value))
                return "'" + kw + ":' expects a word, not a number";
            break;
        case SettingValue::FileOrWord:
            if (!std::holds_alternative<std::string>(setting.value))
                return "'" + kw + ":' expects a word or a file name, not a number";
            break;
        case SettingValue::Number:
            if (!std::holds_alternative<double>(setting.value))
                return "'" + kw + ":' expects a number";
            break;
        case SettingValue::File:
        case SettingValue::None:
            break;
    }
    return found->apply(view, setting);
}

std::ostream& operator<<(std::ostream& os, const ViewSettings& v) {
    printSettings(os, v, false);
    std::ostringstream viewFile;
    printSettings(viewFile, v, true);
    std::istringstream lines(viewFile.str());
    for (std::string l; std::getline(lines, l);) os << "/* view file: " << l << " */\n";
    return os;
}

void printViewFile(std::ostream& os, const ViewSettings& v) {
    printSettings(os, v, true);
}

}  // namespace graftal

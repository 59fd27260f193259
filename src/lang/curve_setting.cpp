// Reading the curve a view file names (see curve_setting.hpp).
#include "curve_setting.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "graftal/lang/curve_xyz.hpp"
#include "setting_file.hpp"

namespace graftal {

namespace {

// cpfg samples a curve 100 times when its `curve:` line gives no number.
constexpr int kDefaultCurveSamples = 100;

}  // namespace

void loadCurveSetting(LSystem& lsystem, const ViewSetting& setting, DiagnosticList& diagnostics) {
    const auto* text = std::get_if<std::string>(&setting.value);
    std::istringstream words(text ? *text : std::string());
    std::string file, samplesWord, extra;
    words >> file >> samplesWord >> extra;
    int samples = kDefaultCurveSamples;
    if (!samplesWord.empty()) {
        char* stop = nullptr;
        double d = std::strtod(samplesWord.c_str(), &stop);
        if (*stop || d != std::floor(d) || d < 2 || d > 1e6) file.clear();
        samples = static_cast<int>(d);
    }
    if (file.empty() || !extra.empty()) {
        diagnostics.error(setting.location,
                          "'curve:' expects a curve file and optionally a number of samples "
                          "(at least 2), e.g. 'curve: stem.crv 100', found '" +
                              (text ? *text : std::string()) + "'");
        return;
    }
    const std::filesystem::path path = settingFilePath(setting, file);
    const std::optional<std::string> bytes = readSettingFile(setting, path, "curve", diagnostics);
    if (!bytes) return;
    try {
        lsystem.curves.push_back(parseCurveFile(*bytes, path.string(), samples));
    } catch (const Error& e) {
        for (const auto& d : e.diagnostics()) diagnostics.add(d);
    }
}

}  // namespace graftal

// Reading the curve a view file names (see curve_setting.hpp).
#include "curve_setting.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "graftal/curve_xyz.hpp"
#include "graftal/file_reading.hpp"

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
    std::filesystem::path path(file);
    if (path.is_relative())
        path = std::filesystem::path(setting.location.file).parent_path() / path;
    std::string problem;
    const std::optional<std::string> bytes = readUserFile(path, problem);
    if (!bytes) {
        diagnostics.error(setting.location, "the curve file '" + path.string() + "' " + problem);
        return;
    }
    try {
        lsystem.curves.push_back(parseCurveFile(*bytes, path.string(), samples));
    } catch (const Error& e) {
        for (const auto& d : e.diagnostics()) diagnostics.add(d);
    }
}

}  // namespace graftal

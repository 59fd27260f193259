// The official Khronos glTF validator, run with Node (tests/tools/validate_gltf.mjs, which
// `make test-tools` sets up in the build folder).
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

namespace graftal::testing {

inline const std::filesystem::path kToolsDir = GRAFTAL_TOOLS_DIR;
inline const std::filesystem::path kValidatorScript =
    std::filesystem::path(GRAFTAL_TESTS_DIR) / "tools" / "validate_gltf.mjs";

inline bool validatorInstalled() {
    return std::filesystem::is_directory(kToolsDir / "node_modules" / "gltf-validator");
}

inline std::string shellQuoted(const std::filesystem::path& p) {
    std::string s = "'";
    for (char c : p.string()) s += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return s + "'";
}

struct Validation {
    int status = -1;
    std::string output;
    nlohmann::json report;
};

inline Validation validate(const std::filesystem::path& file) {
    Validation v;
    const std::string command = "node " + shellQuoted(kValidatorScript) + " " + shellQuoted(file) +
                                " " + shellQuoted(kToolsDir) + " 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) return v;
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
        v.output.append(buffer, n);
    const int raw = ::pclose(pipe);
    v.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    // The report is the last line.
    std::string last = v.output;
    while (!last.empty() && last.back() == '\n') last.pop_back();
    if (const auto nl = last.rfind('\n'); nl != std::string::npos) last = last.substr(nl + 1);
    if (!last.empty()) v.report = nlohmann::json::parse(last, nullptr, false);
    return v;
}

}  // namespace graftal::testing

// Fails the test (never skips it) when the validator is missing.
#define EXPECT_VALID_GLTF(file)                                                           \
    do {                                                                                  \
        ASSERT_TRUE(graftal::testing::validatorInstalled())                               \
            << "the glTF validator is not installed in "                                  \
            << graftal::testing::kToolsDir / "node_modules"                               \
            << ": run `make test-tools` (`make test` installs it)";                       \
        const graftal::testing::Validation validation = graftal::testing::validate(file); \
        EXPECT_EQ(validation.status, 0) << validation.output;                             \
        ASSERT_TRUE(validation.report.is_object()) << validation.output;                  \
        EXPECT_EQ(validation.report.value("numErrors", -1), 0) << validation.output;      \
        std::cout << "validator: " << validation.output;                                  \
    } while (false)

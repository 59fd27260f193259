// Small helpers shared by the tests: parse text, derive, print.
#pragma once

#include <filesystem>
#include <string>

#include "graftal/graftal.hpp"

namespace graftal::testing {

inline LSystem parse(const std::string& text, const std::string& name = "test.l") {
    ParseOptions o;
    o.fileName = name;
    return parseLSystem(text, o);
}

// The grammar and the view, for tests that draw.
inline Model parseModel(const std::string& text, const std::string& name = "test.l") {
    ParseOptions o;
    o.fileName = name;
    return graftal::parse(text, o).orThrow();
}

inline Model loadExample(const std::filesystem::path& path, ParseOptions options = {}) {
    return loadModel(path, std::move(options)).orThrow();
}

inline std::string derived(const LSystem& ls, int steps) {
    return deriveWithQueries(ls, steps).toString(ls.symbols);
}

inline std::string derived(const std::string& text, int steps) {
    LSystem ls = parse(text);
    return derived(ls, steps);
}

// The first error message a parse produces, or "" when it parses.
inline std::string parseError(const std::string& text) {
    try {
        parse(text);
    } catch (const Error& e) {
        return e.diagnostics().front().toString();
    }
    return "";
}

// A streamed derivation's modules, kept as a string to compare with a held one.
class ModuleCollector : public ModuleSink {
  public:
    ModuleString s;
    void module(Symbol sym, std::span<const double> p) override { s.push(sym, p); }
};

}  // namespace graftal::testing

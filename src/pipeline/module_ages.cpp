// Fractional ages between derivation steps (see module_ages.hpp).
#include "module_ages.hpp"

#include <array>
#include <cstdint>

namespace graftal {

std::vector<ModuleAge> moduleAges(const Model& model) {
    return model.lsystem.ages;
}

ModuleString agedString(const ModuleString& modules, const std::vector<ModuleAge>& ages,
                        double fraction) {
    ModuleString aged = modules;
    if (ages.empty() || !aged.hasParameters() || fraction == 0) return aged;
    // Per symbol: the age parameter + 1 and the parameter count (0: no age).
    std::array<std::uint32_t, kMaxSymbols> ageOf{}, countOf{};
    for (const ModuleAge& a : ages) {
        ageOf[a.symbol] = a.parameter + 1;
        countOf[a.symbol] = a.parameterCount;
    }
    const auto& starts = aged.paramStarts();
    for (std::size_t i = 0; i < aged.size(); ++i) {
        const Symbol s = aged.symbol(i);
        if (!ageOf[s] || starts[i + 1] - starts[i] != countOf[s]) continue;
        // setParam stores into the string's own precision (floats or doubles).
        const std::size_t k = ageOf[s] - 1;
        aged.setParam(starts[i] + k, aged.params(i)[k] + fraction);
    }
    return aged;
}

}  // namespace graftal

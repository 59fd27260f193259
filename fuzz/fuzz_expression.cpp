// Fuzz target: one expression of the .l language, compiled and evaluated.
#include <cstddef>
#include <cstdint>

#include "fuzz_api.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    graftal_fuzz::compileAndEvaluate(graftal_fuzz::asText(data, size));
    return 0;
}

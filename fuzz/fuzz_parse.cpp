// Fuzz target: .l text -> model or diagnostics (the parser and the model printer).
#include <cstddef>
#include <cstdint>

#include "fuzz_api.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    graftal_fuzz::parseAndPrint(graftal_fuzz::asText(data, size));
    return 0;
}

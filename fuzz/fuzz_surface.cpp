// Fuzz target: the text of a cpfg surface file (.s) -> Bézier patches -> mesh.
#include <cstddef>
#include <cstdint>

#include "fuzz_api.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    graftal_fuzz::parseSurfaceFile(graftal_fuzz::asText(data, size));
    return 0;
}

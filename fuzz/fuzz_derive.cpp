// Fuzz target: .l text -> derivation (few steps, small memory and module caps, a time
// budget) -> homomorphism -> turtle -> SVG, PNG and mesh; a streamed derivation must give
// the stored string, and an exact growth prediction its length.
#include <cstddef>
#include <cstdint>

#include "fuzz_api.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    graftal_fuzz::deriveAndDraw(graftal_fuzz::asText(data, size));
    return 0;
}

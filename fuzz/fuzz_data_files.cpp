// Fuzz target: the files a cpfg model names besides its .l (view, contour, function,
// function set, material and colour map files); the first byte picks which.
#include <cstddef>
#include <cstdint>

#include "fuzz_api.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    graftal_fuzz::readDataFile(data, size);
    return 0;
}

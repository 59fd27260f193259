// A ZIP archive of a few files stored uncompressed: how the studio hands over an OBJ with
// its material library (.mtl) as one download that Blender's importer finds side by side
// once unpacked.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace graftal::studio {

// The archive's bytes: each (name, bytes) stored as it is (method 0), with its CRC-32.
std::string storedZip(const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace graftal::studio

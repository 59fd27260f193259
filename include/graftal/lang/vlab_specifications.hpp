// vlab's `specifications` file: the menu of a model folder, whose commands say how cpfg is
// run on the folder (`cpfg -M plant.mat plant.l plant.v plant.a`). graftal reads the first
// cpfg command of it to know which of the folder's files make the model when it is given
// the folder alone (`graftal derive FOLDER`).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace graftal {

struct VlabCommand {
    std::string lFile;        // the L-system, cpfg's first file argument
    std::string viewFile;     // the view file (empty: none named)
    std::string colorMap;     // -m FILE (or -m1 FILE)
    std::string materials;    // -M FILE
    std::string environment;  // -e FILE (an environmental program's file)
};

// The first cpfg command of a specifications text, or nothing when it has none. The file
// names are as written, relative to the model's folder.
std::optional<VlabCommand> cpfgCommandOf(std::string_view specifications);

}  // namespace graftal

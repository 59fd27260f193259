// `graftal studio` as the program has it in a shared build: the server is in its plugin
// (studio_plugin.hpp), loaded when the command runs.
#include "studio_plugin.hpp"

namespace graftal::cli {

int runStudio(const StudioCommandOptions& options) {
    return plugins::plugin<plugins::StudioPlugin>("studio", "graftal studio (cpp-httplib)")
        .runStudio(options);
}

}  // namespace graftal::cli

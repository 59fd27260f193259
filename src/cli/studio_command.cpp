// `graftal studio [PATH] [--port N] [--no-open]`: the live editor in the browser. Its options;
// the server is run by studio_run.cpp (a plugin of its own in a shared build, so that the
// other commands do not load cpp-httplib and OpenSSL).
#include <CLI/CLI.hpp>

#include "studio_command.hpp"

namespace graftal::cli {

void addStudioCommand(CLI::App& app, StudioCommandOptions& options) {
    options.command = app.add_subcommand(
        "studio", "edit an L-system in the browser and watch it grow, live (docs/studio.md)");
    options.command->add_option("path", options.path, "a folder or a .l file (default: .)");
    options.command->add_option("--port", options.port, "port on 127.0.0.1 (default: a free one)")
        ->check(CLI::Range(0, 65535));
    options.command->add_flag("--no-open", options.noOpen, "do not open the browser");
    options.command->add_flag("--no-token", options.noToken,
                              "answer requests without this run's secret token (any program "
                              "or user of this machine can then read and write the models)");
}

}  // namespace graftal::cli

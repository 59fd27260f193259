// The studio subcommand's options and runner (main.cpp registers it).
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace graftal::cli {

struct StudioCommandOptions {
    CLI::App* command = nullptr;
    std::string path;
    int port = 0;
    bool noOpen = false;
    bool noToken = false;
};

void addStudioCommand(CLI::App& app, StudioCommandOptions& options);
int runStudio(const StudioCommandOptions& options);

}  // namespace graftal::cli

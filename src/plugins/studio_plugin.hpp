// The table of `graftal studio`'s plugin (plugin_loader.hpp): the server and the HTTP,
// OpenSSL, zlib and Brotli libraries under it are loaded only when the studio runs.
#pragma once

#include <cstdint>

#include "../cli/studio_command.hpp"
#include "plugin_loader.hpp"

namespace graftal::plugins {

// cpp-httplib (graftal_plugin_studio.so): the studio's server (src/cli/studio_run.cpp).
struct StudioPlugin {
    std::uint32_t abi = kPluginAbi;
    int (*runStudio)(const cli::StudioCommandOptions&);
};

}  // namespace graftal::plugins

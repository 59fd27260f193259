// Plugins: the writers whose native libraries are heavy (Cairo, Embree, giflib and libwebp,
// FFmpeg, libsmf, FluidSynth) live in shared libraries of their own, opened with dlopen the
// first time a file needs one, as Mitsuba loads its plugins: a command that writes no PNG
// never maps Cairo. Each plugin exports one C function, graftal_plugin_<name>, returning its
// table of entry points (output_plugins.hpp, music_plugins.hpp); the layers' own definitions
// of those functions forward to the table (output_forwarders.cpp, music_forwarders.cpp).
// Static builds link the writers into the layers instead and have no plugins.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>

namespace graftal::plugins {

// Raised when a table changes shape, so that a plugin of another build is refused rather
// than called through the wrong entries.
inline constexpr std::uint32_t kPluginAbi = 1;

// The folder holding the plugins: GRAFTAL_PLUGIN_DIR when set, else graftal-plugins/ beside
// the library this function is in (the build tree's folder, or the installed libdir).
std::filesystem::path pluginFolder();

// The table of plugin `name` (graftal_plugin_<name>.so), loaded on first use and kept for
// the life of the process. `what` names what the caller was making ("a PNG picture") in the
// Error thrown when the plugin is missing, cannot be loaded or is of another build.
const void* pluginTable(std::string_view name, std::string_view what);

// The table as its type: every table starts with its ABI number.
template <typename Table>
const Table& plugin(std::string_view name, std::string_view what) {
    return *static_cast<const Table*>(pluginTable(name, what));
}

}  // namespace graftal::plugins

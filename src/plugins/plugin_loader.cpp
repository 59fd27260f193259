// Finding and opening the writers' plugins (plugin_loader.hpp).
#include "plugin_loader.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <map>
#include <mutex>
#include <string>

#include "graftal/core/diagnostics.hpp"

namespace graftal::plugins {

namespace {

Error pluginError(std::string_view what, const std::string& problem) {
    return Error(SourceLocation{"graftal", 0, 0}, std::string(what) + " needs " + problem);
}

// The folder of the library (or program) holding this code.
std::filesystem::path ownFolder() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&pluginFolder), &info) == 0 || !info.dli_fname)
        return {};
    std::error_code ec;
    std::filesystem::path file = std::filesystem::canonical(info.dli_fname, ec);
    return (ec ? std::filesystem::path(info.dli_fname) : file).parent_path();
}

struct Loaded {
    void* handle = nullptr;
    const void* table = nullptr;
};

}  // namespace

std::filesystem::path pluginFolder() {
    if (const char* dir = std::getenv("GRAFTAL_PLUGIN_DIR"); dir && *dir) return dir;
    return ownFolder() / "graftal-plugins";
}

const void* pluginTable(std::string_view name, std::string_view what) {
    static std::mutex mutex;
    static std::map<std::string, Loaded, std::less<>> loaded;
    const std::lock_guard lock(mutex);
    if (auto it = loaded.find(name); it != loaded.end()) return it->second.table;

    const std::string entry = "graftal_plugin_" + std::string(name);
    const std::filesystem::path file = pluginFolder() / (entry + ".so");
    std::error_code ec;
    if (!std::filesystem::exists(file, ec))
        throw pluginError(what, "the plugin " + file.string() +
                                    ", which is missing (graftal's plugins are installed "
                                    "beside its libraries; GRAFTAL_PLUGIN_DIR names another "
                                    "folder)");
    // RTLD_LOCAL: a plugin's libraries stay out of the program's symbol lookup.
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = dlerror();
        throw pluginError(what, "the plugin " + file.string() + ", which cannot be loaded: " +
                                    (why ? why : "unknown error"));
    }
    using Entry = const void* (*)();
    auto function = reinterpret_cast<Entry>(dlsym(handle, entry.c_str()));
    const void* table = function ? function() : nullptr;
    if (!table || *static_cast<const std::uint32_t*>(table) != kPluginAbi) {
        dlclose(handle);
        throw pluginError(what, "the plugin " + file.string() + ", which " +
                                    (function ? "is of another graftal version"
                                              : "has no " + entry + " function"));
    }
    // Never closed: objects the plugin made (encoders, pictures) may outlive any caller.
    loaded.emplace(std::string(name), Loaded{handle, table});
    return table;
}

}  // namespace graftal::plugins

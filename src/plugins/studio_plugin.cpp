// graftal_plugin_studio.so: `graftal studio`'s server (studio_plugin.hpp).
#include "studio_plugin.hpp"

namespace graftal::plugins {
namespace {
const StudioPlugin kTable{
    .runStudio = &cli::runStudio,
};
}  // namespace
}  // namespace graftal::plugins

extern "C" __attribute__((visibility("default"))) const void* graftal_plugin_studio() {
    return &graftal::plugins::kTable;
}

// graftal_plugin_raytrace.so: the ray tracer built on Embree (output_plugins.hpp).
#include "output_plugins.hpp"

namespace graftal::plugins {
namespace {
const RaytracePlugin kTable{
    .renderMesh = &renderRaytraced,
    .meshPixels = &renderRaytracedPixels,
    .renderScene = &renderRaytraced,
    .scenePixels = &renderRaytracedPixels,
};
}  // namespace
}  // namespace graftal::plugins

extern "C" __attribute__((visibility("default"))) const void* graftal_plugin_raytrace() {
    return &graftal::plugins::kTable;
}

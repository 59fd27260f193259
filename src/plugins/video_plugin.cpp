// graftal_plugin_video.so: the MP4 (H.264) encoder built on FFmpeg (output_plugins.hpp).
#include "output_plugins.hpp"

namespace graftal::plugins {
namespace {
const VideoPlugin kTable{
    .openMp4Encoder = &openMp4Encoder,
};
}  // namespace
}  // namespace graftal::plugins

extern "C" __attribute__((visibility("default"))) const void* graftal_plugin_video() {
    return &graftal::plugins::kTable;
}

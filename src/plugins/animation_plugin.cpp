// graftal_plugin_animation.so: the animated GIF (giflib) and WebP (libwebp) encoders
// (output_plugins.hpp).
#include "output_plugins.hpp"

namespace graftal::plugins {
namespace {
const AnimationPlugin kTable{
    .openGifEncoder = &openGifEncoder,
    .openWebPEncoder = &openWebPEncoder,
};
}  // namespace
}  // namespace graftal::plugins

extern "C" __attribute__((visibility("default"))) const void* graftal_plugin_animation() {
    return &graftal::plugins::kTable;
}

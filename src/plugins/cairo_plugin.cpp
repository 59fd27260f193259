// graftal_plugin_cairo.so: the writers built on Cairo (output_plugins.hpp).
#include "output_plugins.hpp"

namespace graftal::plugins {
namespace {
const CairoPlugin kTable{
    .writePngFile = &writePng,
    .writePdfFile = &writePdf,
    .writePngStream = &writePng,
    .writePdfStream = &writePdf,
    .drawLineArt = &drawLineArt,
    .openStreamedPng = &openStreamedPng,
    .drawDerivationDiagram = &drawDerivationDiagram,
    .writeDerivationDiagramPng = &writeDerivationDiagramPng,
    .writeDerivationDiagramPdf = &writeDerivationDiagramPdf,
    .openPngFramesEncoder = &openPngFramesEncoder,
    .writeRgbaPng = &writeRgbaPng,
};
}  // namespace
}  // namespace graftal::plugins

extern "C" __attribute__((visibility("default"))) const void* graftal_plugin_cairo() {
    return &graftal::plugins::kTable;
}

// The tables of the output layer's plugins (plugin_loader.hpp): each holds the entry points
// of the writers built on one native library. A plugin fills its table from its own
// definitions of the layer's functions; output_forwarders.cpp defines the same functions in
// libgraftal_output by calling through the table.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <ostream>
#include <vector>

#include "../output/diagram_style.hpp"
#include "../output/streamed_png.hpp"
#include "graftal/output/animation_file.hpp"
#include "graftal/output/derivation_diagram.hpp"
#include "graftal/output/framed_picture.hpp"
#include "graftal/output/output.hpp"
#include "graftal/output/render3d.hpp"
#include "plugin_loader.hpp"

namespace graftal::plugins {

// Cairo (graftal_plugin_cairo.so): PNG and PDF pictures, pixels of line art and diagrams.
struct CairoPlugin {
    std::uint32_t abi = kPluginAbi;
    void (*writePngFile)(const Scene&, const RenderOptions&, const std::filesystem::path&);
    void (*writePdfFile)(const Scene&, const RenderOptions&, const std::filesystem::path&);
    void (*writePngStream)(const Scene&, const RenderOptions&, std::ostream&,
                           const std::filesystem::path&);
    void (*writePdfStream)(const Scene&, const RenderOptions&, std::ostream&,
                           const std::filesystem::path&);
    RgbaImage (*drawLineArt)(const Scene&, const RenderOptions&, const Bounds&);
    std::unique_ptr<StreamedPng::Impl> (*openStreamedPng)(const RenderOptions&, const Bounds&,
                                                          double, bool, float, std::vector<Rgb>,
                                                          Destination);
    RgbaImage (*drawDerivationDiagram)(const DerivationDiagram&);
    void (*writeDerivationDiagramPng)(const DerivationDiagram&, const std::filesystem::path&);
    void (*writeDerivationDiagramPdf)(const DerivationDiagram&, const std::filesystem::path&);
    std::unique_ptr<AnimationEncoder> (*openPngFramesEncoder)(const std::filesystem::path&,
                                                              const AnimationEncoding&);
    void (*writeRgbaPng)(const RgbaImage&, const Destination&);
};

// Embree (graftal_plugin_raytrace.so): ray-traced pictures of 3D scenes.
struct RaytracePlugin {
    std::uint32_t abi = kPluginAbi;
    void (*renderMesh)(const Mesh&, const RaytraceOptions&, const std::filesystem::path&);
    std::vector<unsigned char> (*meshPixels)(const Mesh&, const RaytraceOptions&);
    void (*renderScene)(const MeshScene&, const RaytraceOptions&, const std::filesystem::path&);
    std::vector<unsigned char> (*scenePixels)(const MeshScene&, const RaytraceOptions&);
};

// giflib and libwebp (graftal_plugin_animation.so): animated GIF and WebP.
struct AnimationPlugin {
    std::uint32_t abi = kPluginAbi;
    std::unique_ptr<AnimationEncoder> (*openGifEncoder)(const std::filesystem::path&,
                                                        const AnimationEncoding&);
    std::unique_ptr<AnimationEncoder> (*openWebPEncoder)(const std::filesystem::path&,
                                                         const AnimationEncoding&);
};

// FFmpeg (graftal_plugin_video.so): H.264 video in MP4.
struct VideoPlugin {
    std::uint32_t abi = kPluginAbi;
    std::unique_ptr<AnimationEncoder> (*openMp4Encoder)(const std::filesystem::path&,
                                                        const AnimationEncoding&);
};

}  // namespace graftal::plugins

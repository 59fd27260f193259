// The entry points of the writers and tools that need a native library, as the web build
// has them (cmake/web.cmake): each throws an Error that names what is missing, so the export
// registry's rows for PNG, PDF, ray tracing, animations, MIDI, audio and engraved scores stay
// in its one table and answer with a message instead of a file. Their real definitions are
// in the sources the web build leaves out (cairo_writer, raytrace_*, streamed_*, the
// animation encoders and animation.cpp, derivation_diagram_writer, the music writers).
#include <filesystem>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "graftal/core/destination.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/music/music.hpp"
#include "graftal/output/derivation_diagram.hpp"
#include "graftal/output/framed_picture.hpp"
#include "graftal/output/output.hpp"
#include "graftal/output/render3d.hpp"
#include "graftal/output/streamed_picture.hpp"
#include "graftal/pipeline/animation.hpp"
#include "graftal/turtle/subtree_summaries.hpp"

namespace graftal {

namespace {

[[noreturn]] void unavailable(const std::string& what) {
    throw Error(SourceLocation{"graftal", 0, 0},
                what + " needs the graftal command: the library it is made with is not part of "
                       "the web build, which writes SVG, OBJ, PLY, glTF and MusicXML");
}

}  // namespace

// Cairo: PNG and PDF pictures, pixels of line art and of derivation diagrams.
void writePng(const Scene&, const RenderOptions&, const std::filesystem::path&) {
    unavailable("a PNG picture");
}
void writePdf(const Scene&, const RenderOptions&, const std::filesystem::path&) {
    unavailable("a PDF picture");
}
void writePng(const Scene&, const RenderOptions&, std::ostream&, const std::filesystem::path&) {
    unavailable("a PNG picture");
}
void writePdf(const Scene&, const RenderOptions&, std::ostream&, const std::filesystem::path&) {
    unavailable("a PDF picture");
}
RgbaImage drawLineArt(const Scene&, const RenderOptions&, const Bounds&) {
    unavailable("a picture in pixels");
}
void writeRgbaPng(const RgbaImage&, const std::filesystem::path&) { unavailable("a PNG picture"); }
void writeRgbaPng(const RgbaImage&, const Destination&) { unavailable("a PNG picture"); }
void writeDerivationDiagramSvg(const DerivationDiagram&, std::ostream&) {
    unavailable("a derivation diagram");
}
RgbaImage drawDerivationDiagram(const DerivationDiagram&) { unavailable("a derivation diagram"); }
void writeDerivationDiagram(const DerivationDiagram&, const std::filesystem::path&) {
    unavailable("a derivation diagram");
}
void writeDerivationDiagram(const std::vector<ModuleString>&, const SymbolTable&,
                            const RenderOptions&, const std::filesystem::path&) {
    unavailable("a derivation diagram");
}
void writeDerivationDiagram(const DerivationDiagram&, ImageFormat, const Destination&) {
    unavailable("a derivation diagram");
}
void writeDerivationDiagram(const std::vector<ModuleString>&, const SymbolTable&,
                            const RenderOptions&, ImageFormat, const Destination&) {
    unavailable("a derivation diagram");
}

// Streamed and summarised PNGs (Cairo): the web build never streams a picture.
bool streamedPictureIsSummarised(const Model&, int, std::size_t, const RenderOptions&) {
    return false;
}
void renderStreamedPng(const Model&, int, const DerivationOptions&, const RenderOptions&,
                       const Destination&) {
    unavailable("a picture of a string too large to hold");
}
void renderSummarisedPng(const Model&, const SubtreeSummaries&, const RenderOptions&,
                         const Destination&, double, double) {
    unavailable("a picture of a string too large to hold");
}

// Embree: ray-traced pictures.
void renderRaytraced(const Mesh&, const RaytraceOptions&, const std::filesystem::path&) {
    unavailable("a ray-traced picture");
}
std::vector<unsigned char> renderRaytracedPixels(const Mesh&, const RaytraceOptions&) {
    unavailable("a ray-traced picture");
}
void renderRaytraced(const MeshScene&, const RaytraceOptions&, const std::filesystem::path&) {
    unavailable("a ray-traced picture");
}
std::vector<unsigned char> renderRaytracedPixels(const MeshScene&, const RaytraceOptions&) {
    unavailable("a ray-traced picture");
}
Camera framedCamera(const Camera&, const MeshScene&, int, int) {
    unavailable("a ray-traced picture");
}
Camera framedCamera(const Camera&, std::span<const MeshScene* const>, int, int) {
    unavailable("a ray-traced picture");
}
Camera framedCamera(const Camera&, const Bounds&, int, int) {
    unavailable("a ray-traced picture");
}

// giflib, libwebp, FFmpeg: animations.
void checkAnimationRequest(const AnimationRequest&) { unavailable("an animation"); }
AnimationResult writeAnimationFile(const Model&, const AnimationRequest&) {
    unavailable("an animation");
}
AnimationResult writeAnimationTo(const Model&, const AnimationRequest&, AnimationFormat,
                                 const Destination&) {
    unavailable("an animation");
}

// libsmf, FluidSynth, LilyPond: music files but MusicXML.
void writeScore(const Score& score, const std::filesystem::path& path, const AudioOptions&) {
    if (path.extension() == ".musicxml") return writeMusicXml(score, path);
    unavailable("a " + path.extension().string() + " score");
}
void writeScore(const Score& score, MusicFormat format, const Destination& destination,
                const AudioOptions&) {
    if (format == MusicFormat::MusicXml) return writeMusicXml(score, destination);
    unavailable("a score other than MusicXML");
}

}  // namespace graftal

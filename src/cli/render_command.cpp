// graftal render: the options become a RenderRequest, and the library's render() decides
// the rest (streaming, line art or ray tracing, surfaces, camera).
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "graftal/core/file_format.hpp"
#include "graftal/pipeline/export.hpp"
#include "graftal/pipeline/pipeline.hpp"
#include "standard_streams.hpp"

namespace graftal::cli {

namespace {

Error usageError(const std::string& message) {
    return Error(SourceLocation{"graftal", 0, 0}, message);
}

}  // namespace

// The format written to standard output by -o -: --format's, else SVG. Binary formats are
// refused when standard output is a terminal.
FileFormat standardOutputFormat(const std::string& outputFormat) {
    const std::string name = outputFormat.empty() ? "svg" : outputFormat;
    const std::optional<FileFormat> format = fileFormatFor("out." + name);
    if (!format)
        throw usageError("--format " + name + ": unknown format (use " +
                         extensionList(std::nullopt, ", ", " or ") + " without the dot)");
    const bool text = *format == FileFormat::Svg || *format == FileFormat::Obj;
    if (!text && ::isatty(1))
        throw usageError("-o -: " + std::string(fileFormatInfo(*format).name) +
                         " is binary and standard output is a terminal; redirect it "
                         "(> file) or pipe it, or name a file with -o");
    return *format;
}

ViewDirection parseViewOption(const std::string& name) {
    const std::optional<ViewDirection> view = viewDirectionFromName(name);
    if (!view) throw usageError("--view '" + name + "': expected front, back, side or top");
    return *view;
}

void applyMeshQuality(RenderRequest& request, const std::string& quality,
                      std::optional<int> tubeSides) {
    if (!quality.empty()) {
        const std::optional<MeshResolution> resolution = meshResolutionFor(quality);
        if (!resolution)
            throw usageError("--quality '" + quality +
                             "': expected low, medium, high or a number from 3 to 64");
        request.tubeSides = resolution->tubeSides;
        request.surfaceDivisions = resolution->surfaceDivisions;
    }
    if (tubeSides) request.tubeSides = *tubeSides;
}

// The export request of render's options, and where it goes: a file, or standard output
// for -o - (its format from --format).
ExportRequest renderRequest(const InputOptions& in, const RenderCommandOptions& out) {
    ExportRequest request;
    static_cast<DeriveRequest&>(request) = deriveRequest(in);
    if (out.output == "-") {
        request.format = fileFormatInfo(standardOutputFormat(out.outputFormat)).extension;
        request.output = "out" + request.format;  // the checks below read its extension
    } else {
        if (!out.outputFormat.empty())
            throw usageError("--format applies to -o - (standard output); the extension of " +
                             out.output + " names its format");
        request.output = out.output;
    }
    // A model folder's files are beside its .l, the model's own file.
    request.sourceFile =
        in.file == "-" || std::filesystem::is_directory(in.file) ? std::string() : in.file;
    request.picture = out.render;
    if (out.backgroundGiven) request.background = out.render.background;
    if (!out.view.empty()) request.view = parseViewOption(out.view);
    request.viewpoint = out.viewpoint;
    request.target = out.target;
    request.up = out.up;
    request.light = out.light;
    request.fieldOfView = out.fieldOfView;
    request.samplesPerPixel = out.samplesPerPixel;
    applyMeshQuality(request, out.quality, out.tubeSides);
    request.ground = out.ground;
    request.spline = out.spline;
    if (out.splinePath) request.splinePath = true;
    request.kolamDots = out.kolamDots;
    request.derivationDiagram = out.derivation;
    request.glb.instancing = !out.noInstancing;
    request.glb.compression = out.compress;
    return request;
}

Destination renderDestination(const RenderCommandOptions& out) {
    return out.output == "-" ? Destination::stream(std::cout, "<stdout>")
                             : Destination::file(out.output);
}

int runRender(const InputOptions& in, const RenderCommandOptions& out) {
    ExportRequest request = renderRequest(in, out);
    checkRenderRequest(request);  // option errors before the file is read

    Loaded l = loadInput(in);
    request.steps = l.steps;
    exportModel(l.model, renderDestination(out), request);
    endProgressLine();
    return 0;
}

}  // namespace graftal::cli

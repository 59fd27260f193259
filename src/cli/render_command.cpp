// graftal render: the options become a RenderRequest, and the library's render() decides
// the rest (streaming, line art or ray tracing, surfaces, camera).
#include <unistd.h>

#include <filesystem>
#include <optional>

#include "commands.hpp"
#include "graftal/file_format.hpp"
#include "graftal/pipeline.hpp"
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

int runRender(const InputOptions& in, const RenderCommandOptions& out) {
    RenderRequest request;
    static_cast<DeriveRequest&>(request) = deriveRequest(in);
    std::optional<ScratchFile> scratch;
    if (out.output == "-") {
        const FileFormat format = standardOutputFormat(out.outputFormat);
        scratch.emplace("out" + std::string(fileFormatInfo(format).extension));
        request.output = scratch->path();
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
    if (!out.view.empty()) {
        request.view = viewDirectionFromName(out.view);
        if (!request.view)
            throw Error(SourceLocation{"graftal", 0, 0},
                        "--view '" + out.view + "': expected front, back, side or top");
    }
    request.viewpoint = out.viewpoint;
    request.target = out.target;
    request.up = out.up;
    request.light = out.light;
    request.fieldOfView = out.fieldOfView;
    request.samplesPerPixel = out.samplesPerPixel;
    if (!out.quality.empty()) {
        const std::optional<MeshResolution> resolution = meshResolutionFor(out.quality);
        if (!resolution)
            throw Error(SourceLocation{"graftal", 0, 0},
                        "--quality '" + out.quality +
                            "': expected low, medium, high or a number from 3 to 64");
        request.tubeSides = resolution->tubeSides;
        request.surfaceDivisions = resolution->surfaceDivisions;
    }
    if (out.tubeSides) request.tubeSides = *out.tubeSides;
    request.ground = out.ground;
    request.spline = out.spline;
    if (out.splinePath) request.splinePath = true;
    request.kolamDots = out.kolamDots;
    request.derivationDiagram = out.derivation;
    request.glb.instancing = !out.noInstancing;
    request.glb.compression = out.compress;
    checkRenderRequest(request);  // option errors before the file is read

    Loaded l = loadInput(in);
    request.steps = l.steps;
    render(l.model, request);
    endProgressLine();
    if (scratch && !copyToStandardOutput(request.output)) return 1;
    return 0;
}

}  // namespace graftal::cli

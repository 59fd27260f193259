// graftal render: the options become a RenderRequest, and the library's render() decides
// the rest (streaming, line art or ray tracing, surfaces, camera).
#include "commands.hpp"
#include "graftal/pipeline.hpp"

namespace graftal::cli {

int runRender(const InputOptions& in, const RenderCommandOptions& out) {
    RenderRequest request;
    static_cast<DeriveRequest&>(request) = deriveRequest(in);
    request.output = out.output;
    request.sourceFile = in.file;
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
    request.tubeSides = out.tubeSides;
    request.spline = out.spline;
    if (out.splinePath) request.splinePath = true;
    request.kolamDots = out.kolamDots;
    request.derivationDiagram = out.derivation;
    checkRenderRequest(request);  // option errors before the file is read

    Loaded l = loadInput(in);
    request.steps = l.steps;
    render(l.model, request);
    endProgressLine();
    return 0;
}

}  // namespace graftal::cli

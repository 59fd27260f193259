// What render() decides between a model and a picture, shared with the animations so that a
// frame looks like `graftal render` of the same step.
#pragma once

#include <filesystem>

#include "graftal/geometry/surface.hpp"
#include "graftal/lang/model.hpp"
#include "graftal/output/render3d.hpp"
#include "graftal/pipeline/pipeline.hpp"

namespace graftal {

// The folder surfaces and colour maps are read from: the request's source file's, else the
// model's own file's.
std::filesystem::path sourceFolder(const Model& model, const RenderRequest& request);
// The file's surfaces (relative to `dir`) over the built-in ones.
SurfaceLibrary surfacesFor(const ViewSettings& view, const std::filesystem::path& dir);
// The file's camera and light with the request's overrides.
RaytraceOptions raytraceOptions(const ViewSettings& v, const RenderRequest& request);
// The mesh widths a picture with these options needs: stems at least half a pixel thick,
// and those under about two pixels across left as curves for the ray tracer.
void setPictureRadii(MeshOptions& mo, const Bounds& bounds, const RaytraceOptions& options);
// Line art's options: pfg's scale factor and the background.
RenderOptions lineArtOptions(const Model& model, const RenderRequest& request);

}  // namespace graftal

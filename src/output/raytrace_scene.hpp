// The ray tracer's scene in Embree: the mesh's triangles, each prototype once as a scene of
// its own placed by instances (one per placement, with the placement's transform), and the
// thin stems as round curves. Answers what a ray hits, in world terms.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "raytrace_camera.hpp"
#include "traced_scene.hpp"

namespace graftal {

// What a ray met: where along it, which way the surface faces and its colour index.
struct SurfaceHit {
    double distance = 0;   // along the ray, in units of its direction's length
    Vec3 geometricNormal;  // unit; facing either way
    Vec3 shadingNormal;    // unit; on the same side as geometricNormal
    std::uint16_t color = 0;
};

// Throws Error when Embree could not trace the scene safely: a vertex index out of range,
// colours and triangles that do not pair up, a placement of a missing prototype, a curve
// with a negative radius.
void checkScene(const TracedScene& scene);

class EmbreeScene {
  public:
    // Curves are drawn at least `minimumCurvePixels` pixels wide as `view` sees them, so
    // that a stem thinner than a pixel does not vanish between the rays. Throws Error
    // (bad indices, a placement of a missing prototype, Embree failing).
    EmbreeScene(const TracedScene& scene, const View& view, double minimumCurvePixels);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // The nearest hit of the ray from `origin` along `direction` before `far` (in units of
    // the direction's length); false when it hits nothing.
    bool intersect(const Vec3& origin, const Vec3& direction, double far, SurfaceHit& hit) const;
    // Whether anything lies on the ray before `far`.
    bool occluded(const Vec3& origin, const Vec3& direction, double far) const;
    // Throws Error when Embree reported a failure (e.g. while tracing).
    void check(const char* doing) const;

  private:
    struct Log {
        std::mutex mutex;
        std::string firstMessage;
    };

    void addTriangles(RTCScene scene, const Mesh& mesh, unsigned id);
    void addCurves(const View& view, double minimumCurvePixels);
    void addInstances();
    SurfaceHit describe(const RTCRayHit& rayHit) const;
    void release();

    TracedScene scene_;
    mutable Log log_;
    RTCDevice device_ = nullptr;
    RTCScene top_ = nullptr;
    std::vector<RTCScene> prototypeScenes_;  // null for an empty prototype
    // Positions copied where a mesh's vector had no room for the padding Embree reads.
    std::vector<std::unique_ptr<std::vector<Vec3f>>> paddedPositions_;
};

}  // namespace graftal

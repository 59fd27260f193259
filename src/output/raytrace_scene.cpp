// Embree's view of a MeshScene. The top-level scene holds the mesh's triangles (geometry 0),
// the curves (geometry 1) and one instance per placement (geometry 2 + placement index),
// each instance pointing at its prototype's own committed scene: a leaf repeated 50,000
// times is stored and indexed once. Buffers are shared with the MeshScene where Embree can
// read them in place, so the mesh is not copied.
#include "raytrace_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "graftal/core/diagnostics.hpp"
#include "raytrace_camera.hpp"

namespace graftal {

namespace {

constexpr unsigned kMeshGeometry = 0;
constexpr unsigned kCurveGeometry = 1;
constexpr unsigned kFirstInstance = 2;

static_assert(sizeof(Vec3f) == 3 * sizeof(float), "Embree reads positions as packed float3");
static_assert(sizeof(Affine3f) == 12 * sizeof(float),
              "Embree reads a transform as 12 floats, column by column");

Error renderError(const std::string& message) {
    return Error(SourceLocation{}, message);
}

const char* embreeErrorName(RTCError code) {
    switch (code) {
        case RTC_ERROR_NONE:
            return "no error";
        case RTC_ERROR_INVALID_ARGUMENT:
            return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION:
            return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY:
            return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU:
            return "unsupported CPU";
        case RTC_ERROR_CANCELLED:
            return "cancelled";
        default:
            return "unknown error";
    }
}

// Embree reads indices unchecked, so a bad one would read outside the position array.
void checkMesh(const Mesh& mesh, const char* what) {
    if (mesh.indices.size() % 3 != 0)
        throw renderError(std::string(what) + " has " + std::to_string(mesh.indices.size()) +
                          " vertex indices, expected a multiple of 3");
    if (mesh.triangleColor.size() != mesh.indices.size() / 3)
        throw renderError(std::string(what) + " has " + std::to_string(mesh.indices.size() / 3) +
                          " triangles but " + std::to_string(mesh.triangleColor.size()) +
                          " triangle colours");
    const std::size_t n = mesh.positions.size();
    for (std::uint32_t i : mesh.indices)
        if (i >= n)
            throw renderError(std::string(what) + " vertex index " + std::to_string(i) +
                              " is out of range (" + std::to_string(n) + " positions)");
}

void setRay(RTCRay& ray, const Vec3& origin, const Vec3& direction, double far) {
    ray.org_x = static_cast<float>(origin.x);
    ray.org_y = static_cast<float>(origin.y);
    ray.org_z = static_cast<float>(origin.z);
    ray.dir_x = static_cast<float>(direction.x);
    ray.dir_y = static_cast<float>(direction.y);
    ray.dir_z = static_cast<float>(direction.z);
    ray.tnear = 0;
    ray.tfar =
        std::isfinite(far) ? static_cast<float>(far) : std::numeric_limits<float>::infinity();
    ray.time = 0;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
}

// The triangle's normal by the mesh's own rule (counter-clockwise = front), so the
// front/back decision does not depend on Embree's winding convention, and the vertex
// normals interpolated at (u, v) when the mesh has them.
void triangleNormals(const Mesh& mesh, unsigned prim, float u, float v, Vec3& geometric,
                     Vec3& shading) {
    const std::uint32_t* tri = mesh.indices.data() + 3 * static_cast<std::size_t>(prim);
    const Vec3 p0 = toVec3(mesh.positions[tri[0]]);
    const Vec3 p1 = toVec3(mesh.positions[tri[1]]);
    const Vec3 p2 = toVec3(mesh.positions[tri[2]]);
    geometric = unitOrZero(cross(p1 - p0, p2 - p0));
    shading = geometric;
    if (mesh.normals.size() == mesh.positions.size()) {
        const Vec3 smooth =
            unitOrZero(toVec3(mesh.normals[tri[0]]) * (1.0 - u - v) +
                       toVec3(mesh.normals[tri[1]]) * u + toVec3(mesh.normals[tri[2]]) * v);
        if (isFinite(smooth) && length(smooth) > 0.5) shading = smooth;
    }
}

Vec3 transformedNormal(const Affine3f& t, const Vec3& n) {
    return unitOrZero(toVec3(t.normal(toVec3f(n))));
}

}  // namespace

void checkScene(const TracedScene& scene) {
    checkMesh(*scene.mesh, "mesh");
    for (std::size_t k = 0; k < scene.prototypes.size(); ++k)
        checkMesh(scene.prototypes[k], ("prototype " + std::to_string(k)).c_str());
    for (const MeshPlacement& p : scene.placements)
        if (p.prototype >= scene.prototypes.size())
            throw renderError("a placement refers to prototype " + std::to_string(p.prototype) +
                              " of " + std::to_string(scene.prototypes.size()));
    for (const CurveSegment& c : scene.curves)
        if (!(c.radiusA >= 0) || !(c.radiusB >= 0))
            throw renderError("a curve has a negative or undefined radius");
}

EmbreeScene::EmbreeScene(const TracedScene& scene, const View& view, double minimumCurvePixels)
    : scene_(scene) {
    checkScene(scene);
    // Embree's own threads build the BVH. Its size is not limited by the render's thread
    // count: the BVH, and with it the picture, then never depends on it.
    device_ = rtcNewDevice("verbose=0");
    if (!device_)
        throw renderError(std::string("ray tracer (Embree) failed to start: ") +
                          embreeErrorName(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(
        device_,
        [](void* user, RTCError code, const char* message) {
            auto* log = static_cast<Log*>(user);
            std::lock_guard<std::mutex> lock(log->mutex);
            if (log->firstMessage.empty())
                log->firstMessage = std::string(embreeErrorName(code)) + (message ? ": " : "") +
                                    (message ? message : "");
        },
        &log_);
    try {
        top_ = rtcNewScene(device_);
        check("to create a scene");
        addTriangles(top_, *scene.mesh, kMeshGeometry);
        addCurves(view, minimumCurvePixels);
        addInstances();
        check("to take the scene");
        rtcCommitScene(top_);
        check("to build the acceleration structure");
    } catch (...) {
        release();
        throw;
    }
}

EmbreeScene::~EmbreeScene() {
    release();
}

void EmbreeScene::release() {
    if (top_) rtcReleaseScene(top_);
    top_ = nullptr;
    for (RTCScene s : prototypeScenes_)
        if (s) rtcReleaseScene(s);
    prototypeScenes_.clear();
    if (device_) rtcReleaseDevice(device_);
    device_ = nullptr;
}

void EmbreeScene::check(const char* doing) const {
    const RTCError code = rtcGetDeviceError(device_);
    std::lock_guard<std::mutex> lock(log_.mutex);
    if (code == RTC_ERROR_NONE && log_.firstMessage.empty()) return;
    throw renderError(std::string("ray tracer (Embree) failed ") + doing + ": " +
                      (log_.firstMessage.empty() ? embreeErrorName(code) : log_.firstMessage));
}

// A triangle mesh for Embree that shares the mesh's arrays. Embree loads every vertex with
// a 16-byte SSE load, so the last one needs 4 readable bytes after it; when the vector's
// allocation has no spare room the positions are copied once into a padded array.
void EmbreeScene::addTriangles(RTCScene scene, const Mesh& mesh, unsigned id) {
    if (mesh.triangleCount() == 0) return;
    const Vec3f* positions = mesh.positions.data();
    if (mesh.positions.capacity() == mesh.positions.size()) {
        auto padded = std::make_unique<std::vector<Vec3f>>();
        padded->reserve(mesh.positions.size() + 1);
        padded->assign(mesh.positions.begin(), mesh.positions.end());
        padded->push_back(Vec3f{});
        positions = padded->data();
        paddedPositions_.push_back(std::move(padded));
    }
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!geometry) return;  // check() reports why
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, positions, 0,
                               sizeof(Vec3f), mesh.positions.size());
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                               mesh.indices.data(), 0, 3 * sizeof(std::uint32_t),
                               mesh.triangleCount());
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(scene, geometry, id);
    rtcReleaseGeometry(geometry);  // the scene holds its own reference
}

// Round linear curves: a cone between two balls per segment. A segment that starts where
// the previous one ended (an axis drawn on) shares its vertex and is flagged as its
// neighbour, so the joint is smooth and the vertex stored once.
void EmbreeScene::addCurves(const View& view, double minimumCurvePixels) {
    const auto curves = scene_.curves;
    if (curves.empty()) return;
    auto continues = [&](std::size_t k) {
        return k > 0 && curves[k].a == curves[k - 1].b &&
               curves[k].radiusA == curves[k - 1].radiusB;
    };
    std::size_t vertices = 0;
    for (std::size_t k = 0; k < curves.size(); ++k) vertices += continues(k) ? 1 : 2;
    if (vertices > std::numeric_limits<std::uint32_t>::max())
        throw renderError("too many curve vertices for 32-bit indices");

    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE);
    if (!geometry) return;
    auto* vertex = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), vertices));
    auto* index = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(std::uint32_t), curves.size()));
    auto* flags = static_cast<unsigned char*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, 1, curves.size()));
    if (!vertex || !index || !flags) {
        rtcReleaseGeometry(geometry);
        return;
    }
    const double halfWidth = 0.5 * minimumCurvePixels;
    auto put = [&](std::size_t at, const Vec3f& p, float r) {
        const float least = static_cast<float>(halfWidth * view.pixelSizeAt(toVec3(p)));
        vertex[4 * at] = p.x;
        vertex[4 * at + 1] = p.y;
        vertex[4 * at + 2] = p.z;
        vertex[4 * at + 3] = std::max(r, least);
    };
    std::size_t next = 0;
    for (std::size_t k = 0; k < curves.size(); ++k) {
        const CurveSegment& c = curves[k];
        flags[k] = 0;
        if (continues(k)) {
            flags[k - 1] |= RTC_CURVE_FLAG_NEIGHBOR_RIGHT;
            flags[k] = RTC_CURVE_FLAG_NEIGHBOR_LEFT;
            index[k] = static_cast<std::uint32_t>(next - 1);
        } else {
            index[k] = static_cast<std::uint32_t>(next);
            put(next++, c.a, c.radiusA);
        }
        put(next++, c.b, c.radiusB);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(top_, geometry, kCurveGeometry);
    rtcReleaseGeometry(geometry);
}

void EmbreeScene::addInstances() {
    if (scene_.placements.empty()) return;
    prototypeScenes_.assign(scene_.prototypes.size(), nullptr);
    for (std::size_t k = 0; k < scene_.prototypes.size(); ++k) {
        if (scene_.prototypes[k].triangleCount() == 0) continue;
        prototypeScenes_[k] = rtcNewScene(device_);
        if (!prototypeScenes_[k]) return;
        addTriangles(prototypeScenes_[k], scene_.prototypes[k], kMeshGeometry);
        rtcCommitScene(prototypeScenes_[k]);
    }
    for (std::size_t k = 0; k < scene_.placements.size(); ++k) {
        const MeshPlacement& p = scene_.placements[k];
        if (!prototypeScenes_[p.prototype]) continue;
        RTCGeometry instance = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        if (!instance) return;
        rtcSetGeometryInstancedScene(instance, prototypeScenes_[p.prototype]);
        rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR,
                                &p.transform.columns[0].x);
        rtcCommitGeometry(instance);
        rtcAttachGeometryByID(top_, instance, kFirstInstance + static_cast<unsigned>(k));
        rtcReleaseGeometry(instance);
    }
}

bool EmbreeScene::intersect(const Vec3& origin, const Vec3& direction, double far,
                            SurfaceHit& hit) const {
    if (!embreeCanTrace(origin, direction)) return false;  // nothing met out there
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    setRay(rh.ray, origin, direction, far);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(top_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit = describe(rh);
    return true;
}

bool EmbreeScene::occluded(const Vec3& origin, const Vec3& direction, double far) const {
    if (!embreeCanTrace(origin, direction)) return false;  // nothing shades it out there
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    setRay(ray, origin, direction, far);
    rtcOccluded1(top_, &context, &ray);
    return ray.tfar < 0;  // Embree marks an occluded ray with tfar = -inf
}

SurfaceHit EmbreeScene::describe(const RTCRayHit& rh) const {
    SurfaceHit hit;
    hit.distance = rh.ray.tfar;
    if (rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID) {
        // Embree reports the prototype's triangle in the prototype's own coordinates.
        const MeshPlacement& p = scene_.placements[rh.hit.instID[0] - kFirstInstance];
        const Mesh& prototype = scene_.prototypes[p.prototype];
        Vec3 geometric, shading;
        triangleNormals(prototype, rh.hit.primID, rh.hit.u, rh.hit.v, geometric, shading);
        hit.geometricNormal = transformedNormal(p.transform, geometric);
        hit.shadingNormal = transformedNormal(p.transform, shading);
        hit.color = prototype.triangleColor[rh.hit.primID];
    } else if (rh.hit.geomID == kMeshGeometry) {
        triangleNormals(*scene_.mesh, rh.hit.primID, rh.hit.u, rh.hit.v, hit.geometricNormal,
                        hit.shadingNormal);
        hit.color = scene_.mesh->triangleColor[rh.hit.primID];
    } else {
        // A round curve: Embree's normal is the surface's own.
        hit.geometricNormal = unitOrZero(Vec3{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
        hit.shadingNormal = hit.geometricNormal;
        hit.color = scene_.curves[rh.hit.primID].color;
    }
    return hit;
}

}  // namespace graftal

// The headless 3D renderer. Embree finds what each camera ray hits; the hit is shaded with
// Lambert's law under a directional sun (tested for shadow with a second ray) and a sky
// hemisphere. Everything a pixel gets is a pure function of the pixel, so the image is the
// same for any number of threads. The PNG goes through Cairo's writer, atomically, as the
// 2D pictures do.
#include <embree3/rtcore.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "core/random_stream.hpp"
#include "graftal/animation_file.hpp"
#include "graftal/diagnostics.hpp"
#include "graftal/framed_picture.hpp"
#include "graftal/output.hpp"
#include "graftal/render3d.hpp"

namespace graftal {

namespace {

namespace fs = std::filesystem;

// Cairo's image surfaces are limited to 32767 pixels a side; the in-memory image keeps the
// same limit so that the two entry points accept the same options.
constexpr int kMaxPixelSize = 32767;
constexpr int kMaxSamplesPerPixel = 1024;
// Auto-framing: the outline of the bounding sphere spans this fraction of the picture's
// narrower side, leaving at least 5% of that side free on every edge as the 2D pictures do.
// The camera is raised this far above the horizontal: a plant is seen slightly from above,
// as one stands before it.
constexpr double kFrameFill = 0.9;
constexpr double kFrameElevationDegrees = 20;
// Square tiles are handed to threads one at a time: small enough to balance two cores
// when the plant covers only part of the picture, large enough that the atomic counter
// costs nothing.
constexpr int kTileSize = 16;
// Shadow rays start this far (relative to the scene's size) off the surface, so that the
// rounding of the hit point cannot put them behind their own triangle.
constexpr double kShadowOffset = 1e-5;
// Hemispherical sky light: light from straight above has the sky's colour, from straight
// below the ground's (a dim, warm bounce); in between they mix by the normal's height.
constexpr double kSkyColor[3] = {0.95, 0.97, 1.0};
constexpr double kGroundColor[3] = {0.30, 0.28, 0.25};
// A triangle whose colour index finds no palette (the palette is empty) is drawn grey.
constexpr double kFallbackColor = 0.5;

static_assert(sizeof(Vec3f) == 3 * sizeof(float), "Embree reads positions as packed float3");

// ---- errors ------------------------------------------------------------------------------

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

// Embree reports through a callback, possibly from its own build threads; the first
// message is kept for the Error, since it names the cause and later ones are consequences.
struct EmbreeLog {
    std::mutex mutex;
    std::string firstMessage;
};

void onEmbreeError(void* user, RTCError code, const char* message) {
    auto* log = static_cast<EmbreeLog*>(user);
    std::lock_guard<std::mutex> lock(log->mutex);
    if (log->firstMessage.empty())
        log->firstMessage =
            std::string(embreeErrorName(code)) + (message ? ": " : "") + (message ? message : "");
}

using DevicePtr = std::unique_ptr<RTCDeviceTy, decltype(&rtcReleaseDevice)>;
using ScenePtr = std::unique_ptr<RTCSceneTy, decltype(&rtcReleaseScene)>;

void checkEmbree(RTCDevice device, EmbreeLog& log, const char* doing) {
    const RTCError code = rtcGetDeviceError(device);
    std::lock_guard<std::mutex> lock(log.mutex);
    if (code == RTC_ERROR_NONE && log.firstMessage.empty()) return;
    throw renderError(std::string("ray tracer (Embree) failed ") + doing + ": " +
                      (log.firstMessage.empty() ? embreeErrorName(code) : log.firstMessage));
}

// ---- input checks ------------------------------------------------------------------------

void checkOptions(const RaytraceOptions& o) {
    if (o.width <= 0 || o.height <= 0 || o.width > kMaxPixelSize || o.height > kMaxPixelSize)
        throw renderError("image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                          " is out of range (1 to " + std::to_string(kMaxPixelSize) + " per side)");
    if (o.samplesPerPixel < 1 || o.samplesPerPixel > kMaxSamplesPerPixel)
        throw renderError("samples per pixel " + std::to_string(o.samplesPerPixel) +
                          " is out of range (1 to " + std::to_string(kMaxSamplesPerPixel) + ")");
    const Camera& c = o.camera;
    if (!(c.fieldOfView > 0 && c.fieldOfView < 180))
        throw renderError("field of view must be between 0 and 180 degrees (exclusive)");
    if (!isFinite(c.up) || length(c.up) == 0)
        throw renderError("the camera's up vector must be a finite, non-zero vector");
    if ((c.viewpoint && !isFinite(*c.viewpoint)) || (c.target && !isFinite(*c.target)))
        throw renderError("the camera's viewpoint and target must be finite points");
    const Lighting& l = o.lighting;
    if (!isFinite(l.sunDirection) || !std::isfinite(l.sunIntensity) ||
        !std::isfinite(l.skyIntensity) || l.sunIntensity < 0 || l.skyIntensity < 0)
        throw renderError("light direction and intensities must be finite, intensities >= 0");
}

// Embree reads indices unchecked, so a bad one would read outside the position array.
void checkMesh(const Mesh& mesh) {
    if (mesh.indices.size() % 3 != 0)
        throw renderError("mesh has " + std::to_string(mesh.indices.size()) +
                          " vertex indices, expected a multiple of 3");
    if (mesh.triangleColor.size() != mesh.indices.size() / 3)
        throw renderError("mesh has " + std::to_string(mesh.indices.size() / 3) +
                          " triangles but " + std::to_string(mesh.triangleColor.size()) +
                          " triangle colours");
    const std::size_t n = mesh.positions.size();
    for (std::uint32_t i : mesh.indices)
        if (i >= n)
            throw renderError("mesh vertex index " + std::to_string(i) + " is out of range (" +
                              std::to_string(n) + " positions)");
}

// ---- camera ------------------------------------------------------------------------------

// Box of the finite positions. Mesh::bounds lives with the mesh builder; computing it here
// keeps the renderer independent of that file and skips non-finite points, which Embree
// drops anyway but which would otherwise throw the framing off to infinity.
Bounds meshBounds(const Mesh& mesh) {
    Bounds b;
    for (const Vec3f& p : mesh.positions)
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
            b.extend(Vec3{p.x, p.y, p.z});
    return b;
}

// Where rays come from. For a perspective camera every ray starts at `eye` and goes through
// forward + u * right + v * up, u and v in [-1, 1] across the picture; an orthographic
// camera moves the start instead and keeps the direction `forward`.
struct View {
    Vec3 eye, forward, right, up;
    bool orthographic = false;
};

// A unit vector perpendicular to `up` pointing out of the picture towards the viewer: +z
// when up is the default +y. A z-up world has no +z front, so -y serves there.
Vec3 frontDirection(Vec3 up) {
    Vec3 front = Vec3{0, 0, 1} - up * up.z;
    if (length(front) < 1e-6) front = Vec3{0, -1, 0} - up * (-up.y);
    return unitOrZero(front);
}

}  // namespace

Camera framedCamera(const Camera& c, const Bounds& bounds, int width, int height) {
    const Vec3 worldUp = unitOrZero(c.up);
    const double aspect = static_cast<double>(width) / height;
    const double tanHalfV = std::tan(c.fieldOfView * std::numbers::pi / 360);

    Vec3 lo{0, 0, 0}, hi{0, 0, 0};
    if (!bounds.empty()) {
        lo = bounds.min;
        hi = bounds.max;
    }
    Camera framed = c;
    const Vec3 target = c.target ? *c.target : (lo + hi) * 0.5;
    framed.target = target;
    if (!c.viewpoint) {
        // The sphere around the target that holds the whole box (the box's own bounding
        // sphere when the target is its centre) is framed: seen from distance d it spans
        // the half-angle asin(r / d), whose tangent is its outline's radius in the picture
        // plane at distance 1, to be kFrameFill of the narrower half-side.
        double radius = 0;
        for (int k = 0; k < 8; ++k) {
            const Vec3 corner{k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z};
            radius = std::max(radius, length(corner - target));
        }
        if (!(radius > 0)) radius = 1;  // a single point: any distance shows it
        const double elevation = kFrameElevationDegrees * std::numbers::pi / 180;
        const Vec3 direction =
            frontDirection(worldUp) * std::cos(elevation) + worldUp * std::sin(elevation);
        const double halfAngle = std::atan(kFrameFill * tanHalfV * std::min(1.0, aspect));
        framed.viewpoint = target + direction * (radius / std::sin(halfAngle));
    }
    return framed;
}

namespace {

View makeView(const Camera& camera, const Bounds& bounds, int width, int height) {
    const Camera c = framedCamera(camera, bounds, width, height);
    const Vec3 worldUp = unitOrZero(c.up);
    const double aspect = static_cast<double>(width) / height;
    const double tanHalfV = std::tan(c.fieldOfView * std::numbers::pi / 360);
    const Vec3 target = *c.target;
    const Vec3 eye = *c.viewpoint;

    const Vec3 toTarget = target - eye;
    const double distance = length(toTarget);
    if (!(distance > 0)) throw renderError("the camera's viewpoint and target are the same point");
    View view;
    view.orthographic = c.orthographic;
    view.eye = eye;
    view.forward = toTarget * (1 / distance);
    Vec3 right = cross(view.forward, worldUp);
    if (length(right) < 1e-9) {
        // Looking straight along the up vector: any horizontal direction is as good.
        const Vec3 axis = std::abs(view.forward.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
        right = cross(view.forward, cross(axis, view.forward));
    }
    right = unitOrZero(right);
    const Vec3 up = cross(right, view.forward);
    // The orthographic window is what the perspective camera shows in the target's plane,
    // so switching projections keeps the plant the same size there.
    const double scale = c.orthographic ? distance : 1.0;
    view.right = right * (tanHalfV * aspect * scale);
    view.up = up * (tanHalfV * scale);
    return view;
}

// ---- sampling ----------------------------------------------------------------------------

// Stratification: the pixel is cut into a grid of exactly samplesPerPixel cells (as square
// as the count allows, so no part of the pixel goes unsampled) and each sample is jittered
// inside its own cell: edges get smoother than from purely random positions, without the
// regular stair pattern of a fixed grid.
struct SampleGrid {
    int count = 1, columns = 1, rows = 1;

    explicit SampleGrid(int n) : count(n) {
        for (int c = 1; c * c <= n; ++c)
            if (n % c == 0) columns = c;
        rows = n / columns;
    }

    // Offset of sample s inside pixel (x, y), each coordinate in [0, 1).
    void offset(int x, int y, int s, double& ox, double& oy) const {
        if (count == 1) {
            ox = oy = 0.5;  // one sample: the pixel centre, as a rasteriser would take
            return;
        }
        const std::uint64_t key =
            (static_cast<std::uint64_t>(static_cast<std::uint32_t>(y)) << 32) |
            static_cast<std::uint32_t>(x);
        const std::uint64_t h = mix64(key ^ mix64(static_cast<std::uint64_t>(s) + 1));
        ox = ((s % columns) + unitDouble(h)) / columns;
        oy = ((s / columns) + unitDouble(mix64(h))) / rows;
    }
};

// ---- colour ------------------------------------------------------------------------------

// Palette and background are sRGB values; light adds up linearly, so shading and the
// averaging of samples happen in linear light and only the final pixel is encoded again.
double srgbToLinear(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

unsigned char linearToSrgbByte(double c) {
    c = std::clamp(c, 0.0, 1.0);
    const double s = c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
    return static_cast<unsigned char>(std::lround(s * 255));
}

unsigned char srgbByte(float c) {
    return static_cast<unsigned char>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255));
}

struct Color {
    double r = 0, g = 0, b = 0;
};

// ---- the renderer ------------------------------------------------------------------------

class Tracer {
  public:
    Tracer(const Mesh& mesh, const RaytraceOptions& options, RTCScene scene, const View& view,
           const Bounds& bounds)
        : mesh_(mesh),
          options_(options),
          scene_(scene),
          view_(view),
          grid_(options.samplesPerPixel) {
        sun_ = unitOrZero(options.lighting.sunDirection);
        skyUp_ = unitOrZero(options.camera.up);
        background_ = {srgbToLinear(options.background.r), srgbToLinear(options.background.g),
                       srgbToLinear(options.background.b)};
        backgroundBytes_[0] = srgbByte(options.background.r);
        backgroundBytes_[1] = srgbByte(options.background.g);
        backgroundBytes_[2] = srgbByte(options.background.b);
        for (const Rgb& c : mesh.palette)
            palette_.push_back({srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)});
        double size = 1;
        if (!bounds.empty())
            for (const Vec3& p : {bounds.min, bounds.max})
                size = std::max({size, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        shadowOffset_ = kShadowOffset * size;
    }

    // Renders the pixels of [x0, x1) x [y0, y1) into the RGB8 image `out`.
    void renderTile(int x0, int y0, int x1, int y1, unsigned char* out) const {
        const int width = options_.width;
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                Color sum;
                int hits = 0;
                for (int s = 0; s < grid_.count; ++s) {
                    double ox, oy;
                    grid_.offset(x, y, s, ox, oy);
                    Color c;
                    if (traceSample(x + ox, y + oy, c)) ++hits;
                    sum.r += c.r;
                    sum.g += c.g;
                    sum.b += c.b;
                }
                unsigned char* px = out + (static_cast<std::size_t>(y) * width + x) * 3;
                if (hits == 0) {
                    // Exactly the requested background: an encode of its decode could be
                    // off by one.
                    std::memcpy(px, backgroundBytes_, 3);
                } else {
                    const double n = grid_.count;
                    px[0] = linearToSrgbByte(sum.r / n);
                    px[1] = linearToSrgbByte(sum.g / n);
                    px[2] = linearToSrgbByte(sum.b / n);
                }
            }
        }
    }

  private:
    // One camera ray through image point (sx, sy); false (and the background) on a miss.
    bool traceSample(double sx, double sy, Color& out) const {
        const double u = 2 * sx / options_.width - 1;
        const double v = 1 - 2 * sy / options_.height;
        const Vec3 offset = view_.right * u + view_.up * v;
        const Vec3 origin = view_.orthographic ? view_.eye + offset : view_.eye;
        const Vec3 direction = view_.orthographic ? view_.forward : view_.forward + offset;

        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh;
        setRay(rh.ray, origin, direction);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
            out = background_;
            return false;
        }
        const Vec3 point = origin + direction * rh.ray.tfar;
        out = shade(rh.hit.primID, rh.hit.u, rh.hit.v, point, unitOrZero(direction));
        return true;
    }

    static void setRay(RTCRay& ray, Vec3 origin, Vec3 direction) {
        ray.org_x = static_cast<float>(origin.x);
        ray.org_y = static_cast<float>(origin.y);
        ray.org_z = static_cast<float>(origin.z);
        ray.dir_x = static_cast<float>(direction.x);
        ray.dir_y = static_cast<float>(direction.y);
        ray.dir_z = static_cast<float>(direction.z);
        ray.tnear = 0;
        ray.tfar = std::numeric_limits<float>::infinity();
        ray.time = 0;
        ray.mask = 0xFFFFFFFFu;
        ray.id = 0;
        ray.flags = 0;
    }

    Color shade(unsigned prim, float u, float v, Vec3 point, Vec3 direction) const {
        const std::uint32_t* tri = mesh_.indices.data() + 3 * static_cast<std::size_t>(prim);
        const Vec3 p0 = toVec3(mesh_.positions[tri[0]]);
        const Vec3 p1 = toVec3(mesh_.positions[tri[1]]);
        const Vec3 p2 = toVec3(mesh_.positions[tri[2]]);
        // The geometric normal by the mesh's own rule (counter-clockwise = front), so the
        // front/back decision does not depend on Embree's winding convention.
        Vec3 ng = unitOrZero(cross(p1 - p0, p2 - p0));
        Vec3 n = ng;
        if (mesh_.normals.size() == mesh_.positions.size()) {
            const Vec3 smooth =
                unitOrZero(toVec3(mesh_.normals[tri[0]]) * (1.0 - u - v) +
                           toVec3(mesh_.normals[tri[1]]) * u + toVec3(mesh_.normals[tri[2]]) * v);
            if (isFinite(smooth) && length(smooth) > 0.5) n = smooth;
        }
        // Two-sided: a leaf seen from below shows its underside, lit as a surface facing
        // the viewer.
        if (dot(ng, direction) > 0) {
            ng = ng * -1;
            n = n * -1;
        }

        double light = 0;
        const double facing = dot(n, sun_);
        // A sun behind the face as seen (by the true geometry) cannot light it, whatever
        // the interpolated normal says.
        if (options_.lighting.sunIntensity > 0 && facing > 0 && dot(ng, sun_) > 0 &&
            !inShadow(point + ng * shadowOffset_))
            light = options_.lighting.sunIntensity * facing;

        const double height = 0.5 + 0.5 * std::clamp(dot(n, skyUp_), -1.0, 1.0);
        const double sky = options_.lighting.skyIntensity;
        const Color albedo = colorOf(mesh_.triangleColor[prim]);
        Color c;
        c.r = albedo.r *
              (light + sky * (kGroundColor[0] + (kSkyColor[0] - kGroundColor[0]) * height));
        c.g = albedo.g *
              (light + sky * (kGroundColor[1] + (kSkyColor[1] - kGroundColor[1]) * height));
        c.b = albedo.b *
              (light + sky * (kGroundColor[2] + (kSkyColor[2] - kGroundColor[2]) * height));
        // Clamped per sample, not per pixel: a bright sample must not brighten its
        // neighbours past white when averaged with them on an edge.
        c.r = std::min(c.r, 1.0);
        c.g = std::min(c.g, 1.0);
        c.b = std::min(c.b, 1.0);
        return c;
    }

    bool inShadow(Vec3 origin) const {
        if (!options_.lighting.shadows) return false;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRay ray;
        setRay(ray, origin, sun_);
        rtcOccluded1(scene_, &context, &ray);
        return ray.tfar < 0;  // Embree marks an occluded ray with tfar = -inf
    }

    Color colorOf(std::uint16_t index) const {
        if (palette_.empty()) return {kFallbackColor, kFallbackColor, kFallbackColor};
        return palette_[index % palette_.size()];  // indices past the end wrap, as in Scene
    }

    const Mesh& mesh_;
    const RaytraceOptions& options_;
    RTCScene scene_;
    View view_;
    SampleGrid grid_;
    Vec3 sun_, skyUp_;
    Color background_;
    unsigned char backgroundBytes_[3] = {0, 0, 0};
    std::vector<Color> palette_;
    double shadowOffset_ = 0;
};

unsigned threadCount(unsigned requested, std::size_t tiles) {
    unsigned n = requested != 0 ? requested : std::thread::hardware_concurrency();
    if (n == 0) n = 1;
    return static_cast<unsigned>(std::min<std::size_t>(n, std::max<std::size_t>(tiles, 1)));
}

// Hands out tiles from a shared counter until none are left. Which thread takes which tile
// varies from run to run; what a tile contains does not.
void renderTiles(const Tracer& tracer, const RaytraceOptions& o, unsigned char* out) {
    const int tilesX = (o.width + kTileSize - 1) / kTileSize;
    const int tilesY = (o.height + kTileSize - 1) / kTileSize;
    const std::size_t tiles = static_cast<std::size_t>(tilesX) * tilesY;
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex failureMutex;

    auto work = [&] {
        try {
            for (std::size_t t = next++; t < tiles; t = next++) {
                const int tx = static_cast<int>(t % tilesX), ty = static_cast<int>(t / tilesX);
                const int x0 = tx * kTileSize, y0 = ty * kTileSize;
                tracer.renderTile(x0, y0, std::min(x0 + kTileSize, o.width),
                                  std::min(y0 + kTileSize, o.height), out);
            }
        } catch (...) {
            next = tiles;  // the others stop at their next tile
            std::lock_guard<std::mutex> lock(failureMutex);
            if (!failure) failure = std::current_exception();
        }
    };

    const unsigned n = threadCount(o.threads, tiles);
    std::vector<std::thread> helpers;
    helpers.reserve(n - 1);
    try {
        for (unsigned i = 1; i < n; ++i) helpers.emplace_back(work);
    } catch (...) {
        // Could not start a thread: the ones that did start (and this one) do the work.
    }
    work();
    for (std::thread& t : helpers) t.join();
    if (failure) std::rethrow_exception(failure);
}

// A triangle mesh for Embree that shares the mesh's arrays. Embree loads every vertex with
// a 16-byte SSE load, so the last one needs 4 readable bytes after it; when the vector's
// allocation has no spare room the positions are copied once into a padded array.
struct SharedGeometry {
    std::vector<Vec3f> paddedPositions;

    void attach(RTCDevice device, RTCScene scene, const Mesh& mesh) {
        const Vec3f* positions = mesh.positions.data();
        if (mesh.positions.capacity() == mesh.positions.size()) {
            paddedPositions.reserve(mesh.positions.size() + 1);
            paddedPositions.assign(mesh.positions.begin(), mesh.positions.end());
            paddedPositions.push_back(Vec3f{});
            positions = paddedPositions.data();
        }
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        if (!geometry) return;  // the caller's error check reports why
        rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                   positions, 0, sizeof(Vec3f), mesh.positions.size());
        rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                   mesh.indices.data(), 0, 3 * sizeof(std::uint32_t),
                                   mesh.indices.size() / 3);
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene, geometry);
        rtcReleaseGeometry(geometry);  // the scene holds its own reference
    }
};

void fillBackground(std::vector<unsigned char>& pixels, const Rgb& background) {
    const unsigned char bytes[3] = {srgbByte(background.r), srgbByte(background.g),
                                    srgbByte(background.b)};
    for (std::size_t i = 0; i < pixels.size(); i += 3) std::memcpy(&pixels[i], bytes, 3);
}

}  // namespace

std::vector<unsigned char> renderRaytracedPixels(const Mesh& mesh, const RaytraceOptions& options) {
    checkOptions(options);
    checkMesh(mesh);
    std::vector<unsigned char> pixels(static_cast<std::size_t>(options.width) * options.height * 3);
    if (mesh.triangleCount() == 0) {
        // Nothing to see is a picture too (a plant that has not sprouted yet).
        fillBackground(pixels, options.background);
        return pixels;
    }

    const Bounds bounds = meshBounds(mesh);
    const View view = makeView(options.camera, bounds, options.width, options.height);

    EmbreeLog log;
    // Embree's own threads build the BVH. Its size is not limited by `threads`: the BVH,
    // and with it the picture, then never depends on the thread count.
    DevicePtr device(rtcNewDevice("verbose=0"), &rtcReleaseDevice);
    if (!device)
        throw renderError(std::string("ray tracer (Embree) failed to start: ") +
                          embreeErrorName(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(device.get(), &onEmbreeError, &log);

    ScenePtr scene(rtcNewScene(device.get()), &rtcReleaseScene);
    checkEmbree(device.get(), log, "to create a scene");
    SharedGeometry geometry;
    geometry.attach(device.get(), scene.get(), mesh);
    checkEmbree(device.get(), log, "to take the mesh");
    rtcCommitScene(scene.get());
    checkEmbree(device.get(), log, "to build the acceleration structure");

    const Tracer tracer(mesh, options, scene.get(), view, bounds);
    renderTiles(tracer, options, pixels.data());
    checkEmbree(device.get(), log, "while tracing");
    return pixels;
}

void renderRaytraced(const Mesh& mesh, const RaytraceOptions& options, const fs::path& path) {
    // Checked before the render: a wrong directory should not cost a minute of tracing.
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw fileError(path,
                        "cannot write image: '" + dir.string() +
                            (fs::exists(dir, ec) ? "' is not a directory" : "' does not exist"));

    std::vector<unsigned char> pixels;
    try {
        pixels = renderRaytracedPixels(mesh, options);
    } catch (const Error& e) {
        throw fileError(path, e.messages());
    }

    writeRgbaPng(RgbaImage::fromRgb(pixels, options.width, options.height), path);
}

// Instances are not kept yet: the ray tracer is given the flattened mesh.
void renderRaytraced(const MeshScene& scene, const RaytraceOptions& options,
                     const std::filesystem::path& path) {
    renderRaytraced(scene.flattened(), options, path);
}

std::vector<unsigned char> renderRaytracedPixels(const MeshScene& scene,
                                                 const RaytraceOptions& options) {
    return renderRaytracedPixels(scene.flattened(), options);
}

}  // namespace graftal

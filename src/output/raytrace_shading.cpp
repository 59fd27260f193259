// The ray tracer's light. A hit is shaded with Lambert's law under two lights: the sun, a
// small disc sampled at a different point by each of a pixel's samples (so shadow edges
// are soft), and the sky, looked for by a few cosine-weighted rays per hit (ambient
// occlusion: where the plant hides the sky, it shades itself). Every random number is a
// hash of the pixel, the sample and what it is for, so the picture is the same for any
// number of threads. Light adds up linearly: shading and the averaging of samples happen
// in linear light and only the final pixel is encoded as sRGB.
#include "raytrace_shading.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <mutex>
#include <numbers>
#include <optional>
#include <thread>

#include "graftal/core/random_stream.hpp"

namespace graftal {

namespace {

// Square tiles are handed to threads one at a time: small enough to balance two cores
// when the plant covers only part of the picture, large enough that the atomic counter
// costs nothing.
constexpr int kTileSize = 16;
// Secondary rays start this far (relative to the scene's size) off the surface, so that
// the rounding of the hit point cannot put them behind their own surface.
constexpr double kRayOffset = 1e-5;
// Light from the sky hemisphere has the sky's colour; light from below the horizon the
// ground's (a dim, warm bounce).
constexpr double kSkyColor[3] = {0.95, 0.97, 1.0};
constexpr double kGroundBounce[3] = {0.30, 0.28, 0.25};
// The floor's own colour (linear): a light, warm grey on which shadows read well.
constexpr double kFloorAlbedo[3] = {0.62, 0.60, 0.56};
// A triangle whose colour index finds no palette (the palette is empty) is drawn grey.
constexpr double kFallbackColor = 0.5;
// What a random draw is for: each purpose gets its own stream per pixel.
enum Purpose : std::uint64_t { kPixelPosition = 1, kSunPoint, kSkyDirection, kRotation };

struct Color {
    double r = 0, g = 0, b = 0;
};

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

// Random numbers in [0, 1) that depend only on the pixel, the purpose and the index.
struct PixelRandom {
    std::uint64_t pixel;

    PixelRandom(int x, int y)
        : pixel((static_cast<std::uint64_t>(static_cast<std::uint32_t>(y)) << 32) |
                static_cast<std::uint32_t>(x)) {}

    std::uint64_t bits(Purpose purpose, std::uint64_t index) const {
        return mix64(pixel ^ mix64(purpose * 0x9e3779b97f4a7c15ULL + index + 1));
    }
    double unit(Purpose purpose, std::uint64_t index, int draw) const {
        std::uint64_t h = bits(purpose, index);
        for (int k = 0; k < draw; ++k) h = mix64(h);
        return unitDouble(h);
    }
};

// Stratification: the unit square is cut into a grid of exactly `count` cells (as square
// as the count allows, so no part goes unsampled) and each draw is jittered inside its own
// cell: smoother than purely random points, without a fixed grid's regular pattern.
struct Strata {
    int count = 1, columns = 1, rows = 1;

    explicit Strata(int n) : count(std::max(n, 1)) {
        for (int c = 1; c * c <= count; ++c)
            if (count % c == 0) columns = c;
        rows = count / columns;
    }

    // Point of cell `cell` jittered by the random (ju, jv), each coordinate in [0, 1).
    void point(int cell, double ju, double jv, double& u, double& v) const {
        u = ((cell % columns) + ju) / columns;
        v = ((cell / columns) + jv) / rows;
    }
};

// An orthonormal frame around the unit vector n.
struct Frame {
    Vec3 s, t, n;

    explicit Frame(const Vec3& normal) : n(normal) {
        s = anyPerpendicular(n);
        t = cross(n, s);
    }
    Vec3 toWorld(double x, double y, double z) const { return s * x + t * y + n * z; }
};

class Tracer {
  public:
    Tracer(const EmbreeScene& scene, const std::vector<Rgb>& palette, const View& view,
           const Bounds& bounds, const RaytraceOptions& options)
        : scene_(scene),
          view_(view),
          options_(options),
          pixelStrata_(options.samplesPerPixel),
          sunStrata_(options.samplesPerPixel),
          skyStrata_(options.samplesPerPixel * std::max(options.lighting.skyRays, 1)) {
        sun_ = unitOrZero(options.lighting.sunDirection);
        sunCosRadius_ = std::cos(radians(options.lighting.sunDiameterDegrees / 2));
        up_ = unitOrZero(options.camera.up);
        background_ = {srgbToLinear(options.background.r), srgbToLinear(options.background.g),
                       srgbToLinear(options.background.b)};
        backgroundBytes_[0] = srgbByte(options.background.r);
        backgroundBytes_[1] = srgbByte(options.background.g);
        backgroundBytes_[2] = srgbByte(options.background.b);
        for (const Rgb& c : palette)
            palette_.push_back({srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)});
        double size = 1;
        if (!bounds.empty()) {
            for (const Vec3& p : {bounds.min, bounds.max})
                size = std::max({size, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
            skyReach_ = 2 * length(bounds.max - bounds.min);
        }
        offset_ = kRayOffset * size;
        if (options.ground && !bounds.empty()) ground_ = groundUnder(bounds, up_);
    }

    // Renders the pixels of [x0, x1) x [y0, y1) into the RGB8 image `out`.
    void renderTile(int x0, int y0, int x1, int y1, unsigned char* out) const {
        const int width = options_.width;
        const int n = pixelStrata_.count;
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                const PixelRandom random(x, y);
                Color sum;
                int hits = 0;
                for (int s = 0; s < n; ++s) {
                    double ox = 0.5, oy = 0.5;  // one sample: the pixel centre
                    if (n > 1)
                        pixelStrata_.point(s, random.unit(kPixelPosition, s, 0),
                                           random.unit(kPixelPosition, s, 1), ox, oy);
                    Color c;
                    if (traceSample(x + ox, y + oy, random, s, c)) ++hits;
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
                    px[0] = linearToSrgbByte(sum.r / n);
                    px[1] = linearToSrgbByte(sum.g / n);
                    px[2] = linearToSrgbByte(sum.b / n);
                }
            }
        }
    }

  private:
    // One camera ray through image point (sx, sy); false (and the background) on a miss.
    bool traceSample(double sx, double sy, const PixelRandom& random, int sample,
                     Color& out) const {
        Vec3 origin, direction;
        view_.ray(2 * sx / options_.width - 1, 1 - 2 * sy / options_.height, origin, direction);
        SurfaceHit hit;
        const bool onScene = scene_.intersect(origin, direction, INFINITY, hit);
        double groundAt = INFINITY;
        if (ground_) {
            const double rate = dot(direction, up_);
            const double t = (ground_->height - dot(origin, up_)) / rate;
            if (rate < 0 && t > 0 && (!onScene || t < hit.distance)) groundAt = t;
        }
        if (std::isfinite(groundAt)) {
            out = shadeGround(origin + direction * groundAt, random, sample);
            return true;
        }
        if (!onScene) {
            out = background_;
            return false;
        }
        const Vec3 point = origin + direction * hit.distance;
        Vec3 ng = hit.geometricNormal, n = hit.shadingNormal;
        // Two-sided: a leaf seen from below shows its underside, lit as a surface facing
        // the viewer.
        if (dot(ng, direction) > 0) {
            ng = -ng;
            n = -n;
        }
        out = shade(point, ng, n, colorOf(hit.color), random, sample);
        return true;
    }

    Color shade(const Vec3& point, const Vec3& ng, const Vec3& n, const Color& albedo,
                const PixelRandom& random, int sample) const {
        const Vec3 origin = point + ng * offset_;
        double light[3] = {0, 0, 0};
        const double sun = sunLight(origin, ng, n, random, sample);
        skyLight(origin, ng, n, random, sample, light);
        Color c;
        // Clamped per sample, not per pixel: a bright sample must not brighten its
        // neighbours past white when averaged with them on an edge.
        c.r = std::min(albedo.r * (sun + light[0]), 1.0);
        c.g = std::min(albedo.g * (sun + light[1]), 1.0);
        c.b = std::min(albedo.b * (sun + light[2]), 1.0);
        return c;
    }

    // The floor: lit like the plant, then faded into the background away from the plant.
    Color shadeGround(const Vec3& point, const PixelRandom& random, int sample) const {
        const Color floor = shade(
            point, up_, up_, {kFloorAlbedo[0], kFloorAlbedo[1], kFloorAlbedo[2]}, random, sample);
        const Vec3 across = point - ground_->centre;
        const double distance = length(across - up_ * dot(across, up_));
        double w = std::clamp(
            (distance - ground_->fadeStart) / (ground_->fadeEnd - ground_->fadeStart), 0.0, 1.0);
        w = w * w * (3 - 2 * w);  // smoothstep: no visible rim where the fade starts or ends
        return {floor.r + (background_.r - floor.r) * w, floor.g + (background_.g - floor.g) * w,
                floor.b + (background_.b - floor.b) * w};
    }

    // The sun: one point of its disc per sample, stratified over the pixel's samples.
    double sunLight(const Vec3& origin, const Vec3& ng, const Vec3& n, const PixelRandom& random,
                    int sample) const {
        const double intensity = options_.lighting.sunIntensity;
        if (!(intensity > 0)) return 0;
        Vec3 towards = sun_;
        if (sunCosRadius_ < 1) {
            const int rotation = static_cast<int>(random.bits(kRotation, 0) % sunStrata_.count);
            double u, v;
            sunStrata_.point((sample + rotation) % sunStrata_.count,
                             random.unit(kSunPoint, sample, 0), random.unit(kSunPoint, sample, 1),
                             u, v);
            // Uniform over the cone of directions the disc fills.
            const double cosTheta = 1 - u * (1 - sunCosRadius_);
            const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
            const double phi = 2 * std::numbers::pi * v;
            towards =
                Frame(sun_).toWorld(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
        }
        const double facing = dot(n, towards);
        // A sun behind the face as seen (by the true geometry) cannot light it, whatever
        // the interpolated normal says.
        if (facing <= 0 || dot(ng, towards) <= 0) return 0;
        if (options_.lighting.shadows && scene_.occluded(origin, towards, INFINITY)) return 0;
        return intensity * facing;
    }

    // The sky: cosine-weighted directions about the normal, stratified over all the pixel's
    // sky rays; each one that escapes brings the sky's (or, below the horizon, the
    // ground's) light. Without sky rays, the sky is taken as seen whole.
    void skyLight(const Vec3& origin, const Vec3& ng, const Vec3& n, const PixelRandom& random,
                  int sample, double light[3]) const {
        const double intensity = options_.lighting.skyIntensity;
        if (!(intensity > 0)) return;
        const int rays = options_.lighting.skyRays;
        if (rays <= 0) {
            const double h = 0.5 + 0.5 * std::clamp(dot(n, up_), -1.0, 1.0);
            for (int k = 0; k < 3; ++k)
                light[k] = intensity * (kGroundBounce[k] + (kSkyColor[k] - kGroundBounce[k]) * h);
            return;
        }
        const Frame frame(n);
        const int rotation = static_cast<int>(random.bits(kRotation, 1) % skyStrata_.count);
        double seen[3] = {0, 0, 0};
        for (int i = 0; i < rays; ++i) {
            const int index = sample * rays + i;
            double u, v;
            skyStrata_.point((index + rotation) % skyStrata_.count,
                             random.unit(kSkyDirection, index, 0),
                             random.unit(kSkyDirection, index, 1), u, v);
            const double r = std::sqrt(u), phi = 2 * std::numbers::pi * v;
            const Vec3 d = frame.toWorld(r * std::cos(phi), r * std::sin(phi),
                                         std::sqrt(std::max(0.0, 1 - u)));
            if (dot(d, ng) <= 0) continue;  // into the surface itself
            if (scene_.occluded(origin, d, skyReach_)) continue;
            const double* c = dot(d, up_) >= 0 ? kSkyColor : kGroundBounce;
            for (int k = 0; k < 3; ++k) seen[k] += c[k];
        }
        for (int k = 0; k < 3; ++k) light[k] = intensity * seen[k] / rays;
    }

    Color colorOf(std::uint16_t index) const {
        if (palette_.empty()) return {kFallbackColor, kFallbackColor, kFallbackColor};
        return palette_[index % palette_.size()];  // indices past the end wrap, as in Scene
    }

    const EmbreeScene& scene_;
    View view_;
    const RaytraceOptions& options_;
    Strata pixelStrata_, sunStrata_, skyStrata_;
    Vec3 sun_, up_;
    double sunCosRadius_ = 1;
    Color background_;
    unsigned char backgroundBytes_[3] = {0, 0, 0};
    std::vector<Color> palette_;
    double offset_ = 0;
    double skyReach_ = INFINITY;
    std::optional<Ground> ground_;
};

unsigned threadCount(unsigned requested, std::size_t tiles) {
    unsigned n = requested != 0 ? requested : std::thread::hardware_concurrency();
    if (n == 0) n = 1;
    return static_cast<unsigned>(std::min<std::size_t>(n, std::max<std::size_t>(tiles, 1)));
}

}  // namespace

Ground groundUnder(const Bounds& bounds, const Vec3& up) {
    Ground g;
    double lowest = INFINITY;
    for (int k = 0; k < 8; ++k) {
        const Vec3 corner{k & 1 ? bounds.max.x : bounds.min.x, k & 2 ? bounds.max.y : bounds.min.y,
                          k & 4 ? bounds.max.z : bounds.min.z};
        lowest = std::min(lowest, dot(corner, up));
    }
    g.height = lowest;
    const Vec3 centre = (bounds.min + bounds.max) * 0.5;
    g.centre = centre - up * (dot(centre, up) - lowest);
    // Far enough that the shadow of a tree with the sun half way up the sky still lands on
    // the floor before it fades.
    const double size = std::max(length(bounds.max - bounds.min), 1e-9);
    g.fadeStart = 0.5 * size;
    g.fadeEnd = 1.2 * size;
    return g;
}

void renderPixels(const EmbreeScene& scene, const std::vector<Rgb>& palette, const View& view,
                  const Bounds& bounds, const RaytraceOptions& o, unsigned char* out) {
    const Tracer tracer(scene, palette, view, bounds, o);
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

void fillBackground(std::vector<unsigned char>& pixels, const Rgb& background) {
    const unsigned char bytes[3] = {srgbByte(background.r), srgbByte(background.g),
                                    srgbByte(background.b)};
    for (std::size_t i = 0; i < pixels.size(); i += 3) std::memcpy(&pixels[i], bytes, 3);
}

}  // namespace graftal

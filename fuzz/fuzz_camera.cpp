// Fuzz target: the camera and render options of the ray tracer (viewpoint, target, up, field
// of view, projection, size, samples, lighting) as the command line, a view file or the
// studio may set them, from raw doubles (NaN, infinities and 1e308 included), over a small
// fixed scene. A value no picture can be made from must be an Error, never an abort in
// Embree (its ray.valid() assertion) or a picture of a size not asked for.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz_api.hpp"

namespace {

// A unit box standing on the origin: two triangles a face.
graftal::Mesh box() {
    graftal::Mesh m;
    const float c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                           {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (const auto& p : c) {
        m.positions.push_back({p[0], p[1], p[2]});
        const float n = 0.57735f;
        m.normals.push_back({p[0] * 2 * n - n, p[1] * 2 * n - n, p[2] * 2 * n - n});
    }
    const std::uint32_t faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7},
                                        {0, 1, 5}, {0, 5, 4}, {3, 7, 6}, {3, 6, 2},
                                        {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
    for (const auto& f : faces) {
        m.indices.insert(m.indices.end(), {f[0], f[1], f[2]});
        m.triangleColor.push_back(0);
    }
    m.palette.push_back({0.2f, 0.6f, 0.2f});
    return m;
}

// Reads doubles from the input in turn (zeros when it runs out).
struct Reader {
    const std::uint8_t* data;
    std::size_t size, at = 0;
    double next() {
        double v = 0;
        if (at + sizeof v <= size) std::memcpy(&v, data + at, sizeof v);
        at += sizeof v;
        return v;
    }
    graftal::Vec3 vec() {
        const double x = next(), y = next();
        return {x, y, next()};
    }
    std::uint8_t byte() { return at < size ? data[at++] : 0; }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const graftal::Mesh scene = box();
    Reader in{data, size};
    const std::uint8_t flags = in.byte();
    graftal::RaytraceOptions o;
    o.width = 1 + in.byte() % 24;
    o.height = 1 + in.byte() % 24;
    o.samplesPerPixel = 1 + in.byte() % 2;
    o.threads = 1;
    o.ground = flags & 16;
    o.lighting.skyRays = in.byte() % 3;
    o.lighting.shadows = flags & 32;
    if (flags & 1) o.camera.viewpoint = in.vec();
    if (flags & 2) o.camera.target = in.vec();
    if (flags & 4) o.camera.up = in.vec();
    if (flags & 8) o.camera.fieldOfView = in.next();
    o.camera.orthographic = flags & 64;
    o.camera.fitWindow = flags & 128;
    o.lighting.sunDirection = in.vec();
    o.minimumCurvePixels = in.next();
    try {
        const std::vector<unsigned char> pixels = graftal::renderRaytracedPixels(scene, o);
        if (pixels.size() != static_cast<std::size_t>(o.width) * o.height * 3)
            graftal_fuzz::finding("a picture of another size than asked for");
    } catch (const graftal::Error& e) {
        graftal_fuzz::checkRejection(e, "camera");
    }
    return 0;
}

// What a StreamedPng draws with (output.hpp): the Cairo picture of streamed_png.cpp, behind
// an interface so that StreamedPng itself needs no Cairo (the picture may live in a plugin).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "graftal/core/destination.hpp"
#include "graftal/output/output.hpp"

namespace graftal {

struct StreamedPng::Impl {
    virtual ~Impl() = default;
    virtual void segment(const Segment& s) = 0;
    virtual void polygon(std::span<const Vec3> vertices, std::uint16_t color) = 0;
    virtual void finish() = 0;
};

// The picture StreamedPng's constructor describes. Throws Error for a size out of range.
std::unique_ptr<StreamedPng::Impl> openStreamedPng(const RenderOptions& o, const Bounds& bounds,
                                                   double ink, bool anySegments, float baseWidth,
                                                   std::vector<Rgb> palette,
                                                   Destination destination);

}  // namespace graftal

// The container side of a .glb: the JSON document, the binary chunk its buffer views point
// into, and the EXT_meshopt_compression layer over them. Views are added as plain data;
// with compression on, each is stored meshopt-encoded in the binary chunk and points at a
// placeholder "fallback" buffer that has a length but no data (so the extension is
// required: a viewer without it could not read the file at all, rather than read it wrong).
// A view the codec would not make smaller is stored as it is.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <ostream>
#include <set>
#include <span>
#include <string>
#include <vector>

namespace graftal::glb {

// glTF's numbers for what the writer stores.
inline constexpr int kFloat = 5126;
inline constexpr int kByte = 5120;
inline constexpr int kUnsignedShort = 5123;
inline constexpr int kUnsignedInt = 5125;
inline constexpr int kArrayBuffer = 34962;
inline constexpr int kElementArrayBuffer = 34963;

inline constexpr const char* kMeshoptCompression = "EXT_meshopt_compression";
inline constexpr const char* kGpuInstancing = "EXT_mesh_gpu_instancing";
inline constexpr const char* kMeshQuantization = "KHR_mesh_quantization";

// EXT_meshopt_compression's filters: a transform applied after decoding. The data given to
// addAttributeView is then the filter's encoded form (meshopt_encodeFilterExp, ...Oct).
enum class Filter { None, Exponential, Octahedral };

class Builder {
  public:
#ifdef GRAFTAL_NO_MESHOPTIMIZER
    // Without meshoptimizer (the web build) the buffers are stored plain: a valid glTF,
    // only larger.
    explicit Builder(bool) : compress_(false) {}
#else
    explicit Builder(bool compress) : compress_(compress) {}
#endif

    // Per-element data (vertex attributes, instance transforms): `count` elements of
    // `stride` bytes, a multiple of 4. `target` is a glTF buffer target, 0 for none. A
    // filter other than None needs compression on. With `declareStride` the view states its
    // stride (needed when elements are padded). Returns the view's index.
    int addAttributeView(std::span<const unsigned char> bytes, std::size_t count,
                         std::size_t stride, int target, Filter filter = Filter::None,
                         bool declareStride = false);
    bool compressing() const { return compress_; }
    // A triangle list's indices, stored as 16-bit values when `shortIndices`.
    int addTriangleView(std::span<const std::uint32_t> indices, bool shortIndices);

    // An accessor over a whole view; returns its index.
    int addAccessor(int view, int componentType, const char* type, std::size_t count);

    // Used (and, for EXT_meshopt_compression and EXT_mesh_gpu_instancing, required).
    void requireExtension(const std::string& name) { required_.insert(name); }

    nlohmann::json& document() { return document_; }
    // The bytes the binary chunk holds so far.
    std::size_t binarySize() const { return binary_.size(); }
    void reserve(std::size_t bytes) { binary_.reserve(bytes); }

    // The .glb: header, JSON chunk, binary chunk (when not empty). Fills in the buffers
    // and the extension lists first. False (and nothing written) when the file would be
    // larger than the 4 GB a .glb's 32-bit lengths allow.
    bool write(std::ostream& out);

  private:
    int addView(std::span<const unsigned char> plain, std::span<const unsigned char> stored,
                std::size_t count, std::size_t stride, const char* mode, int target, Filter filter);
    std::size_t appendBinary(std::span<const unsigned char> bytes);

    bool compress_;
    nlohmann::json document_ = nlohmann::json::object();
    std::vector<unsigned char> binary_;
    std::size_t fallbackBytes_ = 0;  // the uncompressed layout's length (compression only)
    std::set<std::string> required_;
};

}  // namespace graftal::glb

// The .glb container and meshoptimizer's codecs for EXT_meshopt_compression.
#include "glb_builder.hpp"

#ifndef GRAFTAL_NO_MESHOPTIMIZER
#include <meshoptimizer.h>
#endif

#include <array>
#include <bit>
#include <cstring>
#include <limits>

namespace graftal::glb {

namespace {

static_assert(std::endian::native == std::endian::little,
              "glTF buffers are little-endian and are copied from memory as they are");

constexpr std::uint32_t kMagic = 0x46546C67;        // "glTF"
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;    // "JSON"
constexpr std::uint32_t kBinaryChunk = 0x004E4942;  // "BIN\0"

std::size_t paddedTo4(std::size_t n) {
    return (n + 3) & ~std::size_t{3};
}

void putWord(std::ostream& out, std::uint32_t v) {
    std::array<char, 4> bytes;
    std::memcpy(bytes.data(), &v, 4);
    out.write(bytes.data(), 4);
}

}  // namespace

std::size_t Builder::appendBinary(std::span<const unsigned char> bytes) {
    // Every view starts on a 4-byte boundary, as float and uint32 accessors need.
    const std::size_t offset = paddedTo4(binary_.size());
    binary_.resize(offset + bytes.size());
    if (!bytes.empty()) std::memcpy(binary_.data() + offset, bytes.data(), bytes.size());
    return offset;
}

int Builder::addView(std::span<const unsigned char> plain, std::span<const unsigned char> stored,
                     std::size_t count, std::size_t stride, const char* mode, int target,
                     Filter filter) {
    nlohmann::json view = nlohmann::json::object();
    // Data the codec cannot shrink (a few hundred random rotations) is kept as it is; a
    // filtered view is not plain data and is always decoded.
    const bool asIs = !compress_ || (filter == Filter::None && stored.size() >= plain.size());
    if (asIs) {
        view["buffer"] = 0;
        view["byteOffset"] = appendBinary(plain);
        view["byteLength"] = plain.size();
    } else {
        // The view describes the data as it is once decoded, in the placeholder buffer 1;
        // the extension says where its encoded bytes are, in the binary chunk (buffer 0).
        const std::size_t fallbackOffset = paddedTo4(fallbackBytes_);
        fallbackBytes_ = fallbackOffset + plain.size();
        view["buffer"] = 1;
        view["byteOffset"] = fallbackOffset;
        view["byteLength"] = plain.size();
        nlohmann::json meshopt = {{"buffer", 0},
                                  {"byteOffset", appendBinary(stored)},
                                  {"byteLength", stored.size()},
                                  {"byteStride", stride},
                                  {"mode", mode},
                                  {"count", count}};
        if (filter == Filter::Exponential) meshopt["filter"] = "EXPONENTIAL";
        if (filter == Filter::Octahedral) meshopt["filter"] = "OCTAHEDRAL";
        view["extensions"][kMeshoptCompression] = std::move(meshopt);
        required_.insert(kMeshoptCompression);
    }
    if (target != 0) view["target"] = target;
    nlohmann::json& views = document_["bufferViews"];
    views.push_back(std::move(view));
    return static_cast<int>(views.size() - 1);
}

int Builder::addAttributeView(std::span<const unsigned char> bytes, std::size_t count,
                              std::size_t stride, int target, Filter filter, bool declareStride) {
    std::vector<unsigned char> encoded;
#ifndef GRAFTAL_NO_MESHOPTIMIZER
    if (compress_) {
        encoded.resize(meshopt_encodeVertexBufferBound(count, stride));
        encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), bytes.data(),
                                                  count, stride));
    }
#endif
    const int view = addView(bytes, encoded, count, stride, "ATTRIBUTES", target,
                             compress_ ? filter : Filter::None);
    if (declareStride) document_["bufferViews"][view]["byteStride"] = stride;
    return view;
}

int Builder::addTriangleView(std::span<const std::uint32_t> indices, bool shortIndices) {
    std::vector<unsigned char> plain(indices.size() * (shortIndices ? 2 : 4));
    if (shortIndices) {
        for (std::size_t i = 0; i < indices.size(); ++i) {
            const auto v = static_cast<std::uint16_t>(indices[i]);
            std::memcpy(plain.data() + 2 * i, &v, 2);
        }
    } else if (!indices.empty()) {
        std::memcpy(plain.data(), indices.data(), plain.size());
    }
    std::vector<unsigned char> encoded;
#ifndef GRAFTAL_NO_MESHOPTIMIZER
    if (compress_) {
        std::uint32_t vertices = 0;
        for (std::uint32_t v : indices) vertices = std::max(vertices, v + 1);
        encoded.resize(meshopt_encodeIndexBufferBound(indices.size(), vertices));
        encoded.resize(meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices.data(),
                                                 indices.size()));
    }
#endif
    return addView(plain, encoded, indices.size(), shortIndices ? 2 : 4, "TRIANGLES",
                   kElementArrayBuffer, Filter::None);
}

int Builder::addAccessor(int view, int componentType, const char* type, std::size_t count) {
    nlohmann::json& accessors = document_["accessors"];
    accessors.push_back(
        {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
    return static_cast<int>(accessors.size() - 1);
}

bool Builder::write(std::ostream& out) {
    // glTF requires every buffer to hold at least one byte, so an empty file has none.
    if (!binary_.empty()) {
        document_["buffers"] = nlohmann::json::array({{{"byteLength", binary_.size()}}});
        if (fallbackBytes_ > 0)
            document_["buffers"].push_back(
                {{"byteLength", fallbackBytes_},
                 {"extensions", {{kMeshoptCompression, {{"fallback", true}}}}}});
    }
    if (!required_.empty()) {
        document_["extensionsUsed"] = required_;
        document_["extensionsRequired"] = required_;
    }
    std::string json = document_.dump();
    json.resize(paddedTo4(json.size()), ' ');
    const std::size_t binaryChunk = binary_.empty() ? 0 : 8 + paddedTo4(binary_.size());
    const std::size_t total = 12 + 8 + json.size() + binaryChunk;
    if (total > std::numeric_limits<std::uint32_t>::max()) return false;

    putWord(out, kMagic);
    putWord(out, 2);
    putWord(out, static_cast<std::uint32_t>(total));
    putWord(out, static_cast<std::uint32_t>(json.size()));
    putWord(out, kJsonChunk);
    out.write(json.data(), static_cast<std::streamsize>(json.size()));
    if (binaryChunk != 0) {
        putWord(out, static_cast<std::uint32_t>(binaryChunk - 8));
        putWord(out, kBinaryChunk);
        out.write(reinterpret_cast<const char*>(binary_.data()),
                  static_cast<std::streamsize>(binary_.size()));
        const char zeros[4] = {0, 0, 0, 0};
        out.write(zeros, static_cast<std::streamsize>(binaryChunk - 8 - binary_.size()));
    }
    return true;
}

}  // namespace graftal::glb

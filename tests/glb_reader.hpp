// A .glb read back the way a viewer draws it, independently of the writer: its JSON, its
// binary chunk, buffer views decoded through meshoptimizer when they carry
// EXT_meshopt_compression, and every triangle as drawn (instance transforms of
// EXT_mesh_gpu_instancing applied: translation * rotation * scale).
#pragma once

#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "graftal/geometry/mesh.hpp"
#include "process.hpp"

namespace graftal::testing {

struct GlbFile {
    nlohmann::json json;
    std::string binary;
    std::size_t fileSize = 0;

    static GlbFile read(const std::filesystem::path& path) {
        const std::string bytes = readFile(path);
        auto word = [&](std::size_t at) {
            std::uint32_t v;
            std::memcpy(&v, bytes.data() + at, 4);
            return v;
        };
        if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0 || word(4) != 2 ||
            word(8) != bytes.size())
            throw std::runtime_error("not a GLB: " + path.string());
        GlbFile f;
        f.fileSize = bytes.size();
        const std::uint32_t jsonLength = word(12);
        if (word(16) != 0x4E4F534A) throw std::runtime_error("first chunk is not JSON");
        f.json = nlohmann::json::parse(bytes.substr(20, jsonLength));
        const std::size_t at = 20 + jsonLength;
        if (at < bytes.size()) {
            if (word(at + 4) != 0x004E4942) throw std::runtime_error("second chunk is not BIN");
            f.binary = bytes.substr(at + 8, word(at));
        }
        return f;
    }

    bool uses(const std::string& extension) const {
        return json.contains("extensionsUsed") &&
               std::find(json["extensionsUsed"].begin(), json["extensionsUsed"].end(), extension) !=
                   json["extensionsUsed"].end();
    }

    // A buffer view's bytes as a viewer gets them: decoded (and unfiltered) when compressed.
    std::string view(int index) const {
        const nlohmann::json& v = json.at("bufferViews").at(index);
        const std::size_t length = v.at("byteLength");
        if (!v.contains("extensions") || !v["extensions"].contains("EXT_meshopt_compression")) {
            if (v.at("buffer") != 0) throw std::runtime_error("view outside the GLB chunk");
            return binary.substr(v.value("byteOffset", 0), length);
        }
        const nlohmann::json& m = v["extensions"]["EXT_meshopt_compression"];
        if (m.at("buffer") != 0) throw std::runtime_error("compressed data outside the GLB chunk");
        const auto* source =
            reinterpret_cast<const unsigned char*>(binary.data()) + m.value("byteOffset", 0);
        const std::size_t sourceLength = m.at("byteLength"), count = m.at("count"),
                          stride = m.at("byteStride");
        if (count * stride != length) throw std::runtime_error("count * byteStride != byteLength");
        std::string out(length, '\0');
        const std::string mode = m.at("mode");
        int status = -1;
        if (mode == "ATTRIBUTES")
            status = meshopt_decodeVertexBuffer(out.data(), count, stride, source, sourceLength);
        else if (mode == "TRIANGLES")
            status = meshopt_decodeIndexBuffer(out.data(), count, stride, source, sourceLength);
        else if (mode == "INDICES")
            status = meshopt_decodeIndexSequence(out.data(), count, stride, source, sourceLength);
        if (status != 0) throw std::runtime_error("meshopt decoding failed: mode " + mode);
        const std::string filter = m.value("filter", "NONE");
        if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), count, stride);
        if (filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), count, stride);
        if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), count, stride);
        return out;
    }

    // An accessor's values as numbers: floats, indices, normalized bytes dequantized.
    std::vector<double> values(int accessor) const {
        const nlohmann::json& a = json.at("accessors").at(accessor);
        const std::string bytes = view(a.at("bufferView"));
        const std::string type = a.at("type");
        const std::size_t components = type == "SCALAR" ? 1 : type == "VEC3" ? 3 : 4;
        const std::size_t count = a.at("count");
        const int componentType = a.at("componentType");
        std::vector<double> out;
        out.reserve(count * components);
        const std::size_t size = componentType == 5123 ? 2 : componentType == 5120 ? 1 : 4;
        const nlohmann::json& view = json.at("bufferViews").at(a.at("bufferView").get<int>());
        const std::size_t stride = view.value("byteStride", size * components);
        for (std::size_t i = 0; i < count * components; ++i) {
            const char* at = bytes.data() + a.value("byteOffset", 0) + (i / components) * stride +
                             (i % components) * size;
            if (componentType == 5126) {
                float f;
                std::memcpy(&f, at, 4);
                out.push_back(f);
            } else if (componentType == 5125) {
                std::uint32_t u;
                std::memcpy(&u, at, 4);
                out.push_back(u);
            } else if (componentType == 5123) {
                std::uint16_t u;
                std::memcpy(&u, at, 2);
                out.push_back(u);
            } else if (componentType == 5120 && a.value("normalized", false)) {
                out.push_back(std::max(static_cast<signed char>(*at) / 127.0, -1.0));
            } else {
                throw std::runtime_error("unexpected component type");
            }
        }
        return out;
    }
};

// A drawn triangle: three corners in world coordinates, and its material's name.
struct DrawnTriangle {
    std::array<Vec3, 3> corners;
    std::string material;
};

// The affine maps of a node's instances (translation * rotation * scale), or the identity
// once for a node without EXT_mesh_gpu_instancing.
struct InstanceMap {
    double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    Vec3 apply(const Vec3& p) const {
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
    }
    double determinant() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
};

inline std::vector<InstanceMap> instancesOf(const GlbFile& f, const nlohmann::json& node) {
    if (!node.contains("extensions") || !node["extensions"].contains("EXT_mesh_gpu_instancing"))
        return {InstanceMap{}};
    const nlohmann::json& attributes = node["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
    std::vector<double> t, r, s;
    if (attributes.contains("TRANSLATION")) t = f.values(attributes["TRANSLATION"]);
    if (attributes.contains("ROTATION")) r = f.values(attributes["ROTATION"]);
    if (attributes.contains("SCALE")) s = f.values(attributes["SCALE"]);
    const std::size_t n = !t.empty() ? t.size() / 3 : !r.empty() ? r.size() / 4 : s.size() / 3;
    std::vector<InstanceMap> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double x = r.empty() ? 0 : r[4 * i], y = r.empty() ? 0 : r[4 * i + 1],
                     z = r.empty() ? 0 : r[4 * i + 2], w = r.empty() ? 1 : r[4 * i + 3];
        const double rot[3][3] = {
            {1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
        for (int row = 0; row < 3; ++row) {
            for (int col = 0; col < 3; ++col)
                out[i].m[row][col] = rot[row][col] * (s.empty() ? 1 : s[3 * i + col]);
            out[i].m[row][3] = t.empty() ? 0 : t[3 * i + row];
        }
    }
    return out;
}

// Every triangle of the default scene as drawn. Nodes must not carry transforms of their
// own (the writer never gives them any).
inline std::vector<DrawnTriangle> drawnTriangles(const GlbFile& f) {
    std::vector<DrawnTriangle> out;
    std::vector<int> pending = f.json.at("scenes").at(f.json.value("scene", 0)).at("nodes");
    while (!pending.empty()) {
        const nlohmann::json& node = f.json.at("nodes").at(pending.back());
        pending.pop_back();
        for (const char* key : {"matrix", "translation", "rotation", "scale"})
            if (node.contains(key)) throw std::runtime_error("node transforms are not read");
        if (node.contains("children"))
            for (int c : node["children"]) pending.push_back(c);
        if (!node.contains("mesh")) continue;
        const std::vector<InstanceMap> instances = instancesOf(f, node);
        for (const nlohmann::json& p :
             f.json.at("meshes").at(node["mesh"].get<int>())["primitives"]) {
            const std::vector<double> positions = f.values(p.at("attributes").at("POSITION"));
            const std::vector<double> indices = f.values(p.at("indices"));
            const std::string material =
                f.json.at("materials").at(p.at("material").get<int>()).value("name", "");
            for (const InstanceMap& map : instances)
                for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
                    DrawnTriangle tri{{}, material};
                    for (int k = 0; k < 3; ++k) {
                        const auto v = static_cast<std::size_t>(indices[t + k]);
                        tri.corners[k] = map.apply({positions.at(3 * v), positions.at(3 * v + 1),
                                                    positions.at(3 * v + 2)});
                    }
                    out.push_back(tri);
                }
        }
    }
    return out;
}

}  // namespace graftal::testing

// Wavefront OBJ: positions, normals and faces as text, with a .mtl beside it holding one
// material per colour (its diffuse colour from the palette).
#include <charconv>
#include <string>

#include "graftal/core/number_chars.hpp"
#include "graftal/geometry/mesh.hpp"
#include "graftal/output/output.hpp"
#include "mesh_file.hpp"

namespace graftal {

namespace {

// Formatting millions of numbers through iostreams would dominate the time to write a big
// plant; to_chars gives the shortest text that reads back as the same float.
class TextBuffer {
  public:
    explicit TextBuffer(std::ostream& out) : out_(out) { text_.reserve(kFlushAt + 256); }

    TextBuffer& operator<<(const std::string& s) {
        text_ += s;
        return flushIfFull();
    }
    TextBuffer& operator<<(const char* s) {
        text_ += s;
        return flushIfFull();
    }
    TextBuffer& operator<<(char c) {
        text_ += c;
        return flushIfFull();
    }
    template <class Number>
    TextBuffer& number(Number v) {
        char digits[32];
        const auto r = numberToChars(digits, digits + sizeof digits, v);
        text_.append(digits, r.ptr);
        return flushIfFull();
    }
    void flush() {
        out_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
        text_.clear();
    }

  private:
    static constexpr std::size_t kFlushAt = 1 << 20;

    TextBuffer& flushIfFull() {
        if (text_.size() >= kFlushAt) flush();
        return *this;
    }

    std::ostream& out_;
    std::string text_;
};

void writeVectors(TextBuffer& out, const char* tag, const std::vector<Vec3f>& vectors) {
    for (const Vec3f& v : vectors) {
        out << tag << ' ';
        out.number(v.x) << ' ';
        out.number(v.y) << ' ';
        out.number(v.z) << '\n';
    }
}

}  // namespace

void writeObj(const Mesh& mesh, const std::filesystem::path& path) {
    std::filesystem::path mtlPath = path;
    mtlPath.replace_extension(".mtl");
    if (mtlPath == path)
        throw fileError(path, "cannot write " + std::string(fileFormatInfo(FileFormat::Obj).name) +
                                  ": the materials go to '" + mtlPath.string() +
                                  "'; use the extension " +
                                  std::string(fileFormatInfo(FileFormat::Obj).extension));
    writeObj(mesh, Destination::file(path), Destination::file(mtlPath));
}

void writeObj(const Mesh& mesh, const Destination& objDestination,
              const Destination& mtlDestination) {
    const std::string format(fileFormatInfo(FileFormat::Obj).name);
    const std::filesystem::path& path = objDestination.path();
    const std::filesystem::path mtlPath = mtlDestination.path();
    mesh_file::checkMesh(mesh, path, format);
    // Both files are complete before either is renamed into place, the materials first so
    // that a reader of the new OBJ never finds the old .mtl: the materials are written and
    // renamed while the OBJ is still a temporary.
    const std::vector<mesh_file::ColorGroup> groups = mesh_file::groupByColor(mesh);
    auto writeMaterials = [&](std::ostream& mtlFile) {
        TextBuffer mtl(mtlFile);
        mtl << "# graftal palette: one material per colour\n";
        for (const mesh_file::ColorGroup& g : groups) {
            const Rgb c = mesh_file::paletteColor(mesh, g.color);
            mtl << "\nnewmtl " << mesh_file::materialName(g.color) << "\nKd ";
            mtl.number(c.r) << ' ';
            mtl.number(c.g) << ' ';
            mtl.number(c.b) << "\nKa 0 0 0\nKs 0 0 0\nd 1\nillum 1\n";
        }
        mtl.flush();
    };
    auto writeGeometry = [&](std::ostream& objFile) {
        TextBuffer obj(objFile);
        obj << "# graftal mesh: ";
        obj.number(mesh.positions.size()) << " vertices, ";
        obj.number(mesh.triangleCount())
            << " triangles\nmtllib " << mtlPath.filename().string() << '\n';
        writeVectors(obj, "v", mesh.positions);
        writeVectors(obj, "vn", mesh.normals);
        for (const mesh_file::ColorGroup& g : groups) {
            obj << "usemtl " << mesh_file::materialName(g.color) << '\n';
            for (std::uint32_t t : g.triangles) {
                obj << 'f';
                for (int k = 0; k < 3; ++k) {
                    // OBJ counts from 1; each vertex has the normal of the same number.
                    const std::uint64_t v =
                        mesh.indices[3 * static_cast<std::size_t>(t) + k] + 1ull;
                    obj << ' ';
                    obj.number(v) << "//";
                    obj.number(v);
                }
                obj << '\n';
            }
        }
        obj.flush();
        mtlDestination.write("MTL", writeMaterials);
    };
    objDestination.write(format, writeGeometry);
}

}  // namespace graftal

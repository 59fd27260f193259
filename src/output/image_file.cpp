// writeImage: picks the writer by extension and makes the write atomic (atomic_file.hpp), so
// a reader never sees half a PNG and a failed render never destroys the previous picture.
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>

#include "graftal/atomic_file.hpp"
#include "graftal/diagnostics.hpp"
#include "graftal/output.hpp"

namespace graftal {

namespace {

namespace fs = std::filesystem;

void writeSvgFile(const Scene& scene, const RenderOptions& o, const fs::path& path) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw fileError(path, std::string("cannot create file: ") + std::strerror(errno));
    writeSvg(scene, o, out);
    out.close();
    if (!out)
        throw fileError(path, "cannot write " + std::string(fileFormatInfo(FileFormat::Svg).name) +
                                  ": write failed (disk full?)");
}

void writeByFormat(ImageFormat format, const Scene& scene, const RenderOptions& o,
                   const fs::path& path) {
    switch (format) {
        case ImageFormat::Svg:
            writeSvgFile(scene, o, path);
            return;
        case ImageFormat::Png:
            writePng(scene, o, path);
            return;
        case ImageFormat::Pdf:
            writePdf(scene, o, path);
            return;
        default:
            break;
    }
}

}  // namespace

void writeImage(const Scene& scene, const RenderOptions& o, const fs::path& path) {
    const std::optional<ImageFormat> format = imageFormatFor(path);
    if (!format) {
        const std::string ext = path.extension().string();
        throw fileError(path, (ext.empty() ? std::string("no image file extension")
                                           : "unknown image file extension '" + ext + "'") +
                                  "; use " + extensionList(FormatKind::Picture));
    }
    writeFileAtomically(
        path, [&](const fs::path& temporary) { writeByFormat(*format, scene, o, temporary); });
}

}  // namespace graftal

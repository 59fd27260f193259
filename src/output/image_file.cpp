// writeImage: picks the picture writer by format and writes to a destination; a file is
// written atomically (atomic_file.hpp), so a reader never sees half a PNG and a failed
// render never destroys the previous picture.
#include <string>

#include "graftal/core/destination.hpp"
#include "graftal/core/diagnostics.hpp"
#include "graftal/output/output.hpp"

namespace graftal {

namespace fs = std::filesystem;

void writeImage(const Scene& scene, const RenderOptions& o, ImageFormat format,
                const Destination& destination) {
    const std::string what(fileFormatInfo(format).name);
    destination.write(what, [&](std::ostream& out) {
        switch (format) {
            case ImageFormat::Svg:
                writeSvg(scene, o, out);
                return;
            case ImageFormat::Png:
                writePng(scene, o, out, destination.path());
                return;
            case ImageFormat::Pdf:
                writePdf(scene, o, out, destination.path());
                return;
            default:
                throw fileError(destination.path(), what + " is not a picture format");
        }
    });
}

void writeImage(const Scene& scene, const RenderOptions& o, const fs::path& path) {
    const std::optional<ImageFormat> format = imageFormatFor(path);
    if (!format) {
        const std::string ext = path.extension().string();
        throw fileError(path, (ext.empty() ? std::string("no image file extension")
                                           : "unknown image file extension '" + ext + "'") +
                                  "; use " + extensionList(FormatKind::Picture));
    }
    writeImage(scene, o, *format, Destination::file(path));
}

}  // namespace graftal

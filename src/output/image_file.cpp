// writeImage: picks the writer by extension and makes the write atomic. The picture goes to
// a hidden temporary file in the target's own directory (rename is only atomic within one
// file system) and is renamed over the target when complete, so a reader never sees half a
// PNG and a failed render never destroys the previous picture.
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include "graftal/diagnostics.hpp"
#include "graftal/output.hpp"

namespace graftal {

namespace {

namespace fs = std::filesystem;

Error fileError(const fs::path& path, const std::string& message) {
    return Error(SourceLocation{path.string(), 0, 0}, message);
}

void writeSvgFile(const Scene& scene, const RenderOptions& o, const fs::path& path) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw fileError(path, std::string("cannot create file: ") + std::strerror(errno));
    writeSvg(scene, o, out);
    out.close();
    if (!out) throw fileError(path, "cannot write SVG: write failed (disk full?)");
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
    }
}

}  // namespace

void writeImage(const Scene& scene, const RenderOptions& o, const fs::path& path) {
    const std::optional<ImageFormat> format = imageFormatFor(path);
    if (!format) {
        const std::string ext = path.extension().string();
        throw fileError(path, (ext.empty() ? std::string("no image file extension")
                                           : "unknown image file extension '" + ext + "'") +
                                  "; use .svg, .png or .pdf");
    }
    writeFileAtomically(
        path, [&](const fs::path& temporary) { writeByFormat(*format, scene, o, temporary); });
}

fs::path temporaryPathBeside(const fs::path& target) {
    static std::atomic<unsigned> counter{0};
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "." + std::string.
    std::string name = ".";
    name += target.filename().string();
    name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    return target.parent_path() / name;
}

void writeFileAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw fileError(path,
                        "cannot write image: '" + dir.string() +
                            (fs::exists(dir, ec) ? "' is not a directory" : "' does not exist"));

    const fs::path temporary = temporaryPathBeside(path);
    try {
        write(temporary);
        fs::rename(temporary, path, ec);
        if (ec) throw fileError(path, "cannot write image: " + ec.message());
    } catch (const Error& e) {
        fs::remove(temporary, ec);
        if (!e.diagnostics().empty() && e.diagnostics().front().location.file == path.string())
            throw;
        throw fileError(path, e.messages());
    } catch (...) {
        fs::remove(temporary, ec);
        throw;
    }
}

}  // namespace graftal

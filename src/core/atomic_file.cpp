// The one atomic file writer (see atomic_file.hpp).
#include "graftal/core/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

namespace graftal {

namespace fs = std::filesystem;

Error fileError(const fs::path& path, const std::string& message) {
    return Error(SourceLocation{path.string(), 0, 0}, message);
}

fs::path temporaryPathBeside(const fs::path& target) {
    static std::atomic<unsigned> counter{0};
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "." + std::string.
    std::string name = ".";
    name += target.filename().string();
    name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    return target.parent_path() / name;
}

void writeFileAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write,
                         const std::string& what) {
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw fileError(path,
                        "cannot write " + what + ": '" + dir.string() +
                            (fs::exists(dir, ec) ? "' is not a directory" : "' does not exist"));

    const fs::path temporary = temporaryPathBeside(path);
    try {
        write(temporary);
        fs::rename(temporary, path, ec);
        if (ec) throw fileError(path, "cannot write " + what + ": " + ec.message());
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

void writeStreamAtomically(const fs::path& path, const std::function<void(std::ostream&)>& write,
                           const std::string& what) {
    writeFileAtomically(
        path,
        [&](const fs::path& temporary) {
            std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
            if (!out) {
                const fs::path dir =
                    path.parent_path().empty() ? fs::path(".") : path.parent_path();
                throw fileError(path, "cannot write " + what + ": cannot create a file in '" +
                                          dir.string() + "': " + std::strerror(errno));
            }
            write(out);
            out.close();
            if (!out) throw fileError(path, "cannot write " + what + ": write failed (disk full?)");
        },
        what);
}

}  // namespace graftal

// Path checks for the studio: a browser page names files by relative paths, and the
// server must never read or write outside the folder it was started on.
#include "graftal/studio/studio_root.hpp"

#include <algorithm>
#include <system_error>

namespace graftal::studio {

namespace fs = std::filesystem;

PathRefused::PathRefused(const std::string& message)
    : Error(SourceLocation{"studio", 0, 0}, message) {}

namespace {

bool isModelFile(const fs::path& p) {
    const std::string ext = p.extension().string();
    return ext == ".l" || ext == ".v";
}

// Whether `p` (canonical) is `root` or below it.
bool inside(const fs::path& root, const fs::path& p) {
    const fs::path rel = p.lexically_relative(root);
    if (rel.empty()) return false;
    const auto first = rel.begin();
    return first == rel.end() || *first != "..";
}

bool skippedFolder(const fs::path& name) {
    const std::string n = name.string();
    return n.empty() || n[0] == '.' || n == "node_modules" || n == "build" ||
           n.rfind("build-", 0) == 0;
}

}  // namespace

std::int64_t modificationTime(const fs::path& path) {
    std::error_code ec;
    const auto t = fs::last_write_time(path, ec);
    if (ec) return 0;
    const auto system = std::chrono::file_clock::to_sys(t);
    return std::chrono::duration_cast<std::chrono::microseconds>(system.time_since_epoch()).count();
}

StudioRoot::StudioRoot(const fs::path& path) {
    std::error_code ec;
    const fs::path canonical = fs::canonical(path, ec);
    if (ec) throw Error(SourceLocation{path.string(), 0, 0}, "no such file or folder");
    if (fs::is_directory(canonical)) {
        folder_ = canonical;
    } else {
        if (!isModelFile(canonical))
            throw Error(SourceLocation{path.string(), 0, 0},
                        "the studio opens a folder or a .l file");
        folder_ = canonical.parent_path();
        onlyFile_ = canonical.filename().string();
    }
}

fs::path StudioRoot::resolve(std::string_view relative, bool mustExist) const {
    const std::string text(relative);
    if (text.empty()) throw PathRefused("no path given");
    if (text.find('\0') != std::string::npos) throw PathRefused("a path may not hold NUL");
    const fs::path rel(text);
    if (rel.is_absolute() || rel.has_root_name() || text[0] == '/' || text[0] == '\\')
        throw PathRefused("'" + text + "': absolute paths are refused");
    for (const auto& part : rel)
        if (part == "..") throw PathRefused("'" + text + "': '..' is refused");
    if (!isModelFile(rel))
        throw PathRefused("'" + text + "': the studio reads and writes only .l and .v files");
    // Started on one file: that file, and its view file (the same name, .v).
    const std::string normal = rel.lexically_normal().string();
    if (!onlyFile_.empty() && normal != onlyFile_ &&
        normal != fs::path(onlyFile_).replace_extension(".v").string())
        throw PathRefused("'" + text + "': the studio was started on " + onlyFile_ + " alone");

    const fs::path joined = folder_ / rel;
    std::error_code ec;
    if (fs::exists(fs::symlink_status(joined, ec)) || fs::exists(joined, ec)) {
        const fs::path real = fs::canonical(joined, ec);
        if (ec) throw PathRefused("'" + text + "': cannot be resolved (a broken link?)");
        if (!inside(folder_, real)) throw PathRefused("'" + text + "' leads outside the root");
        if (!fs::is_regular_file(real)) throw PathRefused("'" + text + "' is not a file");
        return real;
    }
    if (mustExist) throw PathRefused("'" + text + "': no such file");
    const fs::path parent = fs::canonical(joined.parent_path(), ec);
    if (ec) throw PathRefused("'" + text + "': its folder does not exist");
    if (!inside(folder_, parent) && parent != folder_)
        throw PathRefused("'" + text + "' leads outside the root");
    return parent / joined.filename();
}

std::vector<ListedFile> StudioRoot::list(std::size_t limit) const {
    std::vector<ListedFile> files;
    auto add = [&](const fs::path& p) {
        std::error_code ec;
        ListedFile f;
        f.path = p.lexically_relative(folder_).generic_string();
        f.size = fs::file_size(p, ec);
        f.mtime = modificationTime(p);
        files.push_back(std::move(f));
    };
    if (!onlyFile_.empty()) {
        add(folder_ / onlyFile_);
        return files;
    }
    std::error_code ec;
    fs::recursive_directory_iterator it(folder_, fs::directory_options::skip_permission_denied, ec);
    for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        const fs::directory_entry& e = *it;
        if (e.is_directory(ec)) {
            // Links to folders are not followed (they may lead anywhere).
            if (e.is_symlink(ec) || skippedFolder(e.path().filename()) || it.depth() >= 5)
                it.disable_recursion_pending();
            continue;
        }
        if (e.path().extension() != ".l" || !e.is_regular_file(ec)) continue;
        const fs::path real = fs::canonical(e.path(), ec);
        if (ec || !inside(folder_, real)) {
            ec.clear();
            continue;
        }
        add(e.path());
        if (files.size() >= limit) break;
    }
    std::sort(files.begin(), files.end(),
              [](const ListedFile& a, const ListedFile& b) { return a.path < b.path; });
    return files;
}

}  // namespace graftal::studio

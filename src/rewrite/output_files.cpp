#include "output_files.hpp"

#include <cmath>

#include "graftal/core/module_string.hpp"

namespace graftal {

namespace {

// Whether `path` lies inside `folder` (both made absolute, `..` resolved).
bool inside(const std::filesystem::path& path, const std::filesystem::path& folder) {
    std::error_code ec;
    auto p = std::filesystem::weakly_canonical(path, ec);
    if (ec) return false;
    auto f = std::filesystem::weakly_canonical(folder, ec);
    if (ec) return false;
    auto rel = p.lexically_relative(f);
    return !rel.empty() && *rel.begin() != ".." && rel != ".";
}

}  // namespace

ModelOutputFiles::ModelOutputFiles(std::filesystem::path modelFolder)
    : folder_(modelFolder.empty() ? std::filesystem::path(".") : std::move(modelFolder)) {}

double ModelOutputFiles::open(const std::string& name, bool append, const SourceLocation& where) {
    std::filesystem::path p(name);
    if (p.is_relative()) p = folder_ / p;
    std::error_code ec;
    auto cwd = std::filesystem::current_path(ec);
    if (name.empty() || !(inside(p, folder_) || (!ec && inside(p, cwd))))
        throw Error(where, "fopen(\"" + name +
                               "\"): a model may only write files inside its own folder or "
                               "the working directory");
    auto out = std::make_unique<std::ofstream>(
        p, std::ios::binary | (append ? std::ios::app : std::ios::trunc));
    if (!*out)
        throw Error(where, "fopen(\"" + name + "\"): cannot open " + p.string() + " for writing");
    files_.push_back(std::move(out));
    return static_cast<double>(files_.size());
}

std::ofstream& ModelOutputFiles::file(double handle, const SourceLocation& where) {
    double k = std::floor(handle);
    if (!(k >= 1 && k <= static_cast<double>(files_.size())) ||
        !files_[static_cast<std::size_t>(k) - 1])
        throw Error(where, "no open file has the handle " + formatNumber(handle) +
                               " (a value fopen() gave and fclose() did not close)");
    return *files_[static_cast<std::size_t>(k) - 1];
}

void ModelOutputFiles::write(double handle, std::string_view text, const SourceLocation& where) {
    std::ofstream& f = file(handle, where);
    f.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!f) throw Error(where, "writing a file failed (disk full?)");
}

void ModelOutputFiles::flush(double handle, const SourceLocation& where) {
    file(handle, where).flush();
}

void ModelOutputFiles::close(double handle, const SourceLocation& where) {
    file(handle, where);  // checks the handle
    files_[static_cast<std::size_t>(std::floor(handle)) - 1].reset();
}

}  // namespace graftal

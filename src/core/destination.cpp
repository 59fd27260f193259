// Destinations of written bytes (destination.hpp).
#include "graftal/core/destination.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>

#include "graftal/core/atomic_file.hpp"

namespace graftal {

namespace fs = std::filesystem;

Destination Destination::file(fs::path path) {
    return Destination(Kind::File, std::move(path));
}

Destination Destination::stream(std::ostream& out, std::string name) {
    Destination d(Kind::Stream, std::move(name));
    d.stream_ = &out;
    return d;
}

Destination Destination::memory(std::string& bytes, std::string name) {
    Destination d(Kind::Memory, std::move(name));
    d.bytes_ = &bytes;
    return d;
}

void Destination::write(const std::string& what,
                        const std::function<void(std::ostream&)>& write) const {
    switch (kind_) {
        case Kind::File:
            writeStreamAtomically(path_, write, what);
            return;
        case Kind::Stream:
            write(*stream_);
            stream_->flush();
            if (!*stream_) throw fileError(path_, "cannot write " + what + ": write failed");
            return;
        case Kind::Memory: {
            // Written aside first: a writer that fails half-way leaves the bytes unchanged.
            std::ostringstream out(std::ios::binary);
            write(out);
            bytes_->append(std::move(out).str());
            return;
        }
    }
}

namespace {

// A private file in the system's temporary folder, removed when this goes.
class TemporaryFile {
  public:
    explicit TemporaryFile(const std::string& extension) {
        static std::atomic<unsigned> counter{0};
        std::error_code ec;
        fs::path dir = fs::temp_directory_path(ec);
        if (ec) dir = "/tmp";
        path_ = dir / ("graftal-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) +
                       extension);
    }
    ~TemporaryFile() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

}  // namespace

void Destination::writeThroughFile(const std::string& what, const std::string& extension,
                                   const std::function<void(const fs::path&)>& write) const {
    if (kind_ == Kind::File) {
        // The writer picks its format by the name's extension: the temporary keeps it.
        writeFileAtomically(
            path_,
            [&](const fs::path& temporary) {
                const fs::path named = temporary.string() + extension;
                write(named);
                std::error_code ec;
                fs::rename(named, temporary, ec);
                if (ec) {
                    fs::remove_all(named, ec);
                    throw fileError(path_, "cannot write " + what + ": the writer left no file");
                }
            },
            what);
        return;
    }
    TemporaryFile temporary(extension);
    try {
        write(temporary.path());
    } catch (const Error& e) {
        throw fileError(path_, e.messages());
    }
    std::ifstream in(temporary.path(), std::ios::binary);
    if (!in) throw fileError(path_, "cannot write " + what + ": the writer left no file");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    this->write(what, [&](std::ostream& out) {
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    });
}

}  // namespace graftal

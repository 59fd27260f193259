// Destinations of written bytes (destination.hpp).
#include "graftal/core/destination.hpp"

#ifndef __EMSCRIPTEN__
#include <sys/mman.h>
#endif
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
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

// An anonymous file in memory (memfd), named by /proc/self/fd/N for the libraries that open
// a path: nothing is created in any folder, and it goes when closed.
class MemoryFile {
  public:
    explicit MemoryFile(const fs::path& destination) {
#ifdef __EMSCRIPTEN__
        // The WebAssembly build's files are all in memory (MEMFS): a file there is one.
        static std::atomic<unsigned> counter{0};
        path_ = "/tmp/graftal-output-" + std::to_string(counter++);
        (void)destination;
#else
        fd_ = ::memfd_create("graftal-output", MFD_CLOEXEC);
        if (fd_ < 0)
            throw fileError(destination,
                            std::string("cannot write: no memory file (") + std::strerror(errno) +
                                ")");
        path_ = "/proc/self/fd/" + std::to_string(fd_);
#endif
    }
    ~MemoryFile() {
#ifdef __EMSCRIPTEN__
        std::error_code ec;
        fs::remove(path_, ec);
#else
        ::close(fd_);
#endif
    }
    MemoryFile(const MemoryFile&) = delete;
    MemoryFile& operator=(const MemoryFile&) = delete;
    const fs::path& path() const { return path_; }

    // What the writer left in it (it may have replaced the file through its path: read
    // through the path, not the descriptor).
    bool read(std::string& bytes) const {
        std::ifstream in(path_, std::ios::binary);
        if (!in) return false;
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        return true;
    }

  private:
#ifndef __EMSCRIPTEN__
    int fd_ = -1;
#endif
    fs::path path_;
};

}  // namespace

void Destination::writeThroughFile(const std::string& what,
                                   const std::function<void(const fs::path&)>& write) const {
    if (kind_ == Kind::File) {
        writeFileAtomically(path_, write, what);
        return;
    }
    const MemoryFile file(path_);
    try {
        write(file.path());
    } catch (const Error& e) {
        throw fileError(path_, e.messages());
    }
    std::string bytes;
    if (!file.read(bytes))
        throw fileError(path_, "cannot write " + what + ": the writer left no file");
    this->write(what, [&](std::ostream& out) {
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    });
}

}  // namespace graftal

// Where a writer's bytes go: a file (written atomically, so that a failure leaves nothing
// half-written), a stream the caller owns (standard output), or a string in memory (the
// studio's downloads, a Python caller's bytes). Every writer of the export registry
// (export.hpp) writes to a Destination, so that `-o -` and in-memory exports need no file.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace graftal {

class Destination {
  public:
    enum class Kind { File, Stream, Memory };

    // A file, written through a temporary beside it and renamed into place when complete.
    static Destination file(std::filesystem::path path);
    // A stream the caller owns; `name` is how messages call it ("<stdout>").
    static Destination stream(std::ostream& out, std::string name = "<stdout>");
    // The bytes appended to `bytes`; `name` is how messages call it and gives the format
    // when none is named ("tree.png").
    static Destination memory(std::string& bytes, std::string name = "<memory>");

    Kind kind() const { return kind_; }
    // The file's path, or the name given to a stream or to memory.
    const std::filesystem::path& path() const { return path_; }
    std::string name() const { return path_.string(); }

    // Hands `write` a stream that ends up at the destination. A file is written
    // atomically; `what` names the content in errors ("cannot write PNG: ...").
    void write(const std::string& what, const std::function<void(std::ostream&)>& write) const;

    // For libraries that can only write a named file (libsmf, giflib, FFmpeg's MP4 muxer,
    // Cairo's PDF surface): `write` gets a path to write to, whatever its name (it has no
    // extension: the writer is told its format). A file destination is written atomically
    // through a temporary beside it; a stream or memory through an anonymous file in memory
    // (/proc/self/fd/N), whose bytes are then copied there: no file is made in any folder.
    void writeThroughFile(const std::string& what,
                          const std::function<void(const std::filesystem::path&)>& write) const;

  private:
    Destination(Kind kind, std::filesystem::path path) : kind_(kind), path_(std::move(path)) {}
    Kind kind_;
    std::filesystem::path path_;
    std::ostream* stream_ = nullptr;
    std::string* bytes_ = nullptr;
};

}  // namespace graftal

// Errors are values carrying a source location; the library never prints or exits.
#pragma once

#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace graftal {

struct SourceLocation {
    std::string file;  // empty when the text did not come from a file
    int line = 0;      // 1-based; 0 means "no position in the text"
    int column = 0;    // 1-based, counted in bytes
    // Where the offending text ends: the line and the column just past its last byte
    // (0 when unknown). toString() prints only the start.
    int endLine = 0;
    int endColumn = 0;

    std::string toString() const;
};

enum class Severity { Error, Warning, Note };

// What the caller can change to get past a problem, in terms of its request (DeriveRequest's
// fields). The library words them by those fields; a front end words them in its own terms
// (the graftal command names its flags: -n, --memory-limit, --stream, --stream-limit).
enum class Remedy {
    LowerSteps,        // DeriveRequest::steps
    RaiseMemoryLimit,  // DeriveRequest::memoryLimit
    Stream,            // DeriveRequest::stream = StreamPolicy::Always
    RaiseStreamLimit,  // DeriveRequest::streamLimit
};

// "lower steps", "raise memoryLimit", "set stream to StreamPolicy::Always", "raise
// streamLimit".
std::string requestRemedyText(Remedy r);

struct Diagnostic {
    Severity severity = Severity::Error;
    SourceLocation location;
    std::string message;
    // The request's fields the message is about ("viewpoint", "samplesPerPixel"), listed
    // after it: "...: viewpoint, samplesPerPixel".
    std::vector<std::string> fields;
    // Advice appended to the message: "; lower steps or raise memoryLimit".
    std::vector<Remedy> remedies;

    // "file:line:column: error: message", the form compilers and editors understand.
    std::string toString() const;
    // The same with the fields and remedies worded by a front end (e.g. as its flags).
    std::string toString(const std::function<std::string(Remedy)>& remedy,
                         const std::function<std::string(const std::string&)>& field) const;
};

std::ostream& operator<<(std::ostream& os, const SourceLocation& loc);
std::ostream& operator<<(std::ostream& os, const Diagnostic& d);

// Collects diagnostics so that a parser can report several problems in one pass.
class DiagnosticList {
  public:
    void error(SourceLocation loc, std::string message);
    void warning(SourceLocation loc, std::string message);
    void add(Diagnostic d) { items_.push_back(std::move(d)); }

    bool hasErrors() const;
    const std::vector<Diagnostic>& items() const { return items_; }
    std::string toString() const;

  private:
    std::vector<Diagnostic> items_;
};

// The one exception family of the library. It carries every diagnostic that led to it.
class Error : public std::runtime_error {
  public:
    explicit Error(Diagnostic d);
    explicit Error(std::vector<Diagnostic> ds);
    Error(SourceLocation loc, const std::string& message);

    const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
    // The messages alone, without locations, joined by "; " (for re-raising an error under
    // another location, e.g. a file's real name instead of its temporary's).
    std::string messages() const;

  private:
    std::vector<Diagnostic> diagnostics_;
};

}  // namespace graftal

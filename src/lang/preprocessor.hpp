// The C preprocessor every .l file goes through before it is parsed, as cpfg runs its
// files through cpp: #define (object- and function-like), #undef, #if/#ifdef/#ifndef/#elif/
// #else/#endif, #include "file" relative to the including file, #error, and -D from the
// command line. The work is done by mcpp (used as a library); this file prepares its input
// and maps every line of its output back to the user's file and line.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <string_view>

#include "graftal/core/diagnostics.hpp"
#include "graftal/lang/source_text.hpp"

namespace graftal {

struct PreprocessOptions {
    std::string fileName;  // the model's path as the user named it; #include is relative to it
    // -D NAME=VALUE. A command-line value wins over the file's own #define of NAME (the
    // file's #define and #undef lines of NAME are skipped), so that a slider or `-D` can
    // change a model's constant; cpfg would keep the file's definition.
    std::map<std::string, std::string> defines;
    // Upper bound of the preprocessed text in bytes; 0 picks the default, 16 times the
    // input plus 256 KiB and at most 64 MiB (see kDefaultPreprocessedLimit in the .cpp).
    std::size_t maxOutputBytes = 0;
};

// True when `text` needs the preprocessor: a line starting with '#' or a -D value. Files
// without either come out of cpp unchanged, and are parsed without it.
bool needsPreprocessing(std::string_view text, const PreprocessOptions& options);

// Runs the preprocessor on `text` (the contents of options.fileName, or text that came
// from no file). On success `out` holds the preprocessed lines, each with the file and line
// it came from (SourceLine::spans), and the object-like macros defined at the end
// (SourceText::defines). Returns false with diagnostics at the user's file:line otherwise.
//
// mcpp keeps its state in globals: calls are serialised by a mutex inside, so this function
// may be called from any thread; it never runs two preprocessings at once.
bool preprocessSource(std::string_view text, const PreprocessOptions& options, SourceText& out,
                      DiagnosticList& diags);

// True once libmcpp's name comparisons go through a comparison that stops at the first
// difference (installed by the first preprocessSource): its macro lookup then reads no
// stored name past its end.
bool mcppComparesWithinNames();

}  // namespace graftal

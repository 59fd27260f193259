// A preprocessor that needs no mcpp, for the web build (WebAssembly has no processes to run
// mcpp in, and Debian's libmcpp is a native library). It does what the book's models and
// cpfg's use: #define of object-like and function-like macros (no # or ## operators),
// #undef, #if/#ifdef/#ifndef/#elif/#else/#endif with integer expressions and `defined`,
// #error, and -D values that win over the file's own. A function-like call must close on
// its line, and #include is an error (a model on the web is one text). Its lines map back
// to the user's file and line as preprocessSource's do; the tests hold it to mcpp's output
// on the examples. Built with GRAFTAL_NO_MCPP, it is preprocessSource().
#pragma once

#include <string_view>

#include "graftal/core/diagnostics.hpp"
#include "graftal/lang/source_text.hpp"
#include "preprocessor.hpp"

namespace graftal {

bool preprocessLimited(std::string_view text, const PreprocessOptions& options, SourceText& out,
                       DiagnosticList& diags);

}  // namespace graftal

// What a parse produces: the grammar (LSystem) and how it is drawn (ViewSettings), and the
// entry points that return it with every diagnostic instead of throwing.
#pragma once

#include <filesystem>
#include <ostream>
#include <string_view>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/lang/lsystem.hpp"
#include "graftal/lang/view_settings.hpp"

namespace graftal {

// An L-system model as a file describes it: the grammar the derivation engine runs and the
// view the turtle draws it with. Rewriting needs only `lsystem`; drawing needs both.
struct Model {
    LSystem lsystem;
    ViewSettings view;
};

// Prints the model back in the .l language (the grammar with its view settings).
std::ostream& operator<<(std::ostream& os, const Model& model);

// The outcome of a parse: the model as far as the parser got (complete when ok()), and
// every diagnostic (errors, warnings, notes) in the order the parser found them.
struct ParseResult {
    Model model;
    std::vector<Diagnostic> diagnostics;

    bool ok() const;  // no diagnostic is an error
    std::vector<Diagnostic> errors() const;
    std::vector<Diagnostic> warnings() const;
    // The model; throws Error carrying every error when the parse failed.
    Model& orThrow() &;
    Model orThrow() &&;
};

// Parses .l text (cpfg L-system files and pfg data files). Never throws for bad input.
ParseResult parse(std::string_view text, const ParseOptions& options);

// Parses .l text, then the text of the cpfg view file read with it (its settings win, as in
// loadModel). `viewFileName` names the view file in diagnostics and finds the files it names.
// The view file's problems are warnings (cpfg forgives its view files): a value that cannot
// be used leaves its setting as it was; only the .l text's errors make the result fail.
ParseResult parse(std::string_view text, std::string_view viewText, const std::string& viewFileName,
                  const ParseOptions& options);

// Reads and parses a file (ParseOptions::fileName defaults to the path), then the view file
// ParseOptions::viewFile names, if any. `path` may be a model folder as vlab lays them out:
// its one .l file is read, with its one .v file unless a view file is named. A file that
// cannot be read is a diagnostic at line 0, not an exception.
ParseResult loadModel(const std::filesystem::path& path, ParseOptions options = {});

}  // namespace graftal

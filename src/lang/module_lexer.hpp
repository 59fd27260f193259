// Splits module text (an axiom, a successor, a context) into modules and their
// parenthesised argument texts. Declared multi-letter names are tried longest first.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "graftal/core/diagnostics.hpp"
#include "graftal/core/module_string.hpp"

namespace graftal {

struct ArgumentText {
    std::string text;
    int column = 0;  // where the argument starts, 1-based
};

struct ModuleToken {
    Symbol symbol = 0;
    int column = 0;  // 1-based column of the module name
    bool hasParens = false;
    std::vector<ArgumentText> args;  // one per comma-separated argument
};

// `startColumn` is the column of text[0] on line `loc.line`. Returns false and reports
// to `diags` when the text is malformed. `~` is a module of its own, as in cpfg; a
// surface name of two or more characters after it is one module, declared in `symbols`
// on first use (matched only after ~ unless `module` declares it), except that after a
// letter of `oneLetterSurfaces` (the surfaces declared with one-letter names) ~ takes that
// one letter, as cpfg does, unless the whole run is a declared name.
bool tokenizeModules(std::string_view text, const SourceLocation& loc, int startColumn,
                     SymbolTable& symbols, std::vector<ModuleToken>& out, DiagnosticList& diags,
                     std::string_view oneLetterSurfaces = {});

}  // namespace graftal

#include "module_lexer.hpp"

#include <cctype>

namespace graftal {

namespace {

std::string describeByte(std::string_view text, std::size_t i) {
    auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x80) {
        std::size_t n = (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : 4;
        return "'" + std::string(text.substr(i, n)) + "'";
    }
    return "'" + std::string(1, static_cast<char>(c)) + "'";
}

}  // namespace

bool tokenizeModules(std::string_view text, const SourceLocation& loc, int startColumn,
                     SymbolTable& symbols, std::vector<ModuleToken>& out, DiagnosticList& diags,
                     std::string_view oneLetterSurfaces) {
    auto where = [&](std::size_t i) {
        SourceLocation l = loc;
        l.column = startColumn + static_cast<int>(i);
        return l;
    };
    std::size_t i = 0;
    while (i < text.size()) {
        char c = text[i];
        if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
            continue;
        }
        if (c == '(') {
            if (out.empty() || out.back().hasParens) {
                diags.error(where(i), "'(' must follow a module name, as in F(1)");
                return false;
            }
            // Arguments belong to the module just read; split at top-level commas.
            ModuleToken& m = out.back();
            m.hasParens = true;
            int depth = 0;
            std::size_t argStart = i + 1;
            std::size_t j = i + 1;
            for (; j < text.size(); ++j) {
                char d = text[j];
                if (d == '"') {  // a label's text: its commas and parentheses are not ours
                    std::size_t close = text.find('"', j + 1);
                    if (close == std::string_view::npos) break;
                    j = close;
                    continue;
                }
                if (d == '(') {
                    ++depth;
                } else if (d == ')') {
                    if (depth == 0) break;
                    --depth;
                } else if (d == ',' && depth == 0) {
                    m.args.push_back({std::string(text.substr(argStart, j - argStart)),
                                      startColumn + static_cast<int>(argStart)});
                    argStart = j + 1;
                }
            }
            if (j >= text.size()) {
                diags.error(where(i), "unclosed '(': expected ')' to end the parameter list");
                return false;
            }
            std::string last(text.substr(argStart, j - argStart));
            bool blank = last.find_first_not_of(" \t") == std::string::npos;
            if (!(blank && m.args.empty()))
                m.args.push_back({std::move(last), startColumn + static_cast<int>(argStart)});
            // cpfg's label @L("format", values...): its text is drawn, never computed with.
            // graftal draws no labels, so the text is dropped and the values stay.
            const bool label =
                m.symbol == 'L' && out.size() >= 2 && out[out.size() - 2].symbol == '@';
            std::erase_if(m.args, [&](const ArgumentText& a) {
                std::size_t k = a.text.find_first_not_of(" \t");
                return label && k != std::string::npos && a.text[k] == '"';
            });
            for (const auto& a : m.args) {
                if (a.text.find_first_not_of(" \t") == std::string::npos) {
                    diags.error(where(static_cast<std::size_t>(a.column - startColumn)),
                                "empty parameter: expected an expression between the commas");
                    return false;
                }
            }
            i = j + 1;
            continue;
        }
        if (c == ')') {
            diags.error(where(i), "unmatched ')'");
            return false;
        }
        if (static_cast<unsigned char>(c) >= 0x80) {
            diags.error(where(i), "unexpected character " + describeByte(text, i) +
                                      ": module names are ASCII (declare long names with "
                                      "`module name;`)");
            return false;
        }
        ModuleToken tok;
        tok.column = startColumn + static_cast<int>(i);
        std::size_t len = 1;
        // cpfg's ~ is a module of its own, followed by the module that names the surface
        // (`~l(0.5,t)` is `~` and `l(0.5,t)`, which productions rewrite like any other).
        // graftal's surfaces may have long names: a run of two or more letters, digits
        // or _ after ~ is one module (`~leaf` is `~` and `leaf`), whether declared or not.
        // Such a name is matched in the text only after ~ unless `module` declares it.
        if (c == '~') {
            tok.symbol = static_cast<Symbol>('~');
            out.push_back(std::move(tok));
            std::size_t e = i + 1;
            while (e < text.size() &&
                   (std::isalnum(static_cast<unsigned char>(text[e])) || text[e] == '_'))
                ++e;
            std::string_view name = text.substr(i + 1, e - i - 1);
            // cpfg reads one character after ~: with surface L declared in the view file,
            // `~LF` is the surface L, then F. A run that names no declared module then starts
            // with that surface's letter.
            const bool oneLetter = !name.empty() &&
                                   oneLetterSurfaces.find(name[0]) != std::string_view::npos &&
                                   symbols.find(name) < 0;
            if (e - i <= 2 || oneLetter) {  // nothing or one character: read as any module
                ++i;
                continue;
            }
            if (symbols.size() >= kMaxSymbols && symbols.find(name) < 0) {
                diags.error(where(i), "too many module names: at most " +
                                          std::to_string(kMaxSymbols - kFirstDeclaredSymbol) +
                                          " multi-letter names (and ~surfaces) per file");
                return false;
            }
            ModuleToken surface;
            surface.column = startColumn + static_cast<int>(i + 1);
            surface.symbol = symbols.declare(name, SymbolTable::Matching::AfterTildeOnly);
            out.push_back(std::move(surface));
            i = e;
            continue;
        }
        if (std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == '?') {
            for (Symbol s : symbols.namesLongestFirst()) {
                const std::string& n = symbols.name(s);
                if (text.compare(i, n.size(), n) == 0) {
                    tok.symbol = s;
                    len = n.size();
                    break;
                }
            }
        }
        if (len == 1) tok.symbol = static_cast<Symbol>(static_cast<unsigned char>(c));
        out.push_back(std::move(tok));
        i += len;
    }
    return true;
}

}  // namespace graftal

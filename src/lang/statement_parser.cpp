// Statement blocks: a small recursive-descent reader of cpfg's C-like statements. The
// expressions inside are handed to the expression compiler.
#include "statement_parser.hpp"

#include "graftal/lang/source_text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace graftal::parsing {

std::size_t matchingBrace(std::string_view text, std::size_t open) {
    int depth = 0;
    for (std::size_t i = open; i < text.size(); ++i) {
        i = skipStringLiteral(text, i);
        if (i >= text.size()) break;
        char c = text[i];
        if (c == '"')
            continue;
        else if (c == '{')
            ++depth;
        else if (c == '}' && --depth == 0)
            return i;
    }
    return std::string_view::npos;
}

namespace {

bool isNameStart(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool isNameChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

class StatementParser {
  public:
    StatementParser(std::string_view text, const std::function<SourceLocation(std::size_t)>& locate,
                    BlockScope& scope, DiagnosticList& diags)
        : text_(text), locate_(locate), scope_(scope), diags_(diags) {}

    bool parseAll(Block& out) {
        while (!failed_) {
            skipSpace();
            if (pos_ >= text_.size()) break;
            parseStatement(out);
        }
        return !failed_;
    }

  private:
    // A backslash is blank here too: cpfg's lexer drops a character no rule of an
    // expression matches, so the `\` a macro continued with (`#define w(x) \\`) and one
    // continuing a line of a block are passed over.
    void skipSpace() {
        while (pos_ < text_.size() &&
               (std::isspace(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '\\'))
            ++pos_;
    }

    void fail(std::size_t at, const std::string& message) {
        if (!failed_)
            diags_.error(locate_(std::min(at, text_.size() ? text_.size() - 1 : 0)), message);
        failed_ = true;
    }

    // The word at pos_ (without moving), empty when none.
    std::string_view peekWord() const {
        std::size_t e = pos_;
        if (e >= text_.size() || !isNameStart(text_[e])) return {};
        while (e < text_.size() && isNameChar(text_[e])) ++e;
        return text_.substr(pos_, e - pos_);
    }

    // Index of the first `stop` at depth 0 (outside parentheses and strings) from `from`.
    std::size_t findTopLevel(std::size_t from, char stop) const {
        int depth = 0;
        for (std::size_t i = from; i < text_.size(); ++i) {
            if (text_[i] == stop && depth == 0) return i;
            i = skipStringLiteral(text_, i);
            if (i >= text_.size()) break;
            char c = text_[i];
            if (c == '"')
                continue;
            else if (c == '(' || c == '[')
                ++depth;
            else if (c == ')' || c == ']')
                --depth;
            if (depth < 0) return std::string_view::npos;
        }
        return std::string_view::npos;
    }

    Expression compile(std::size_t from, std::size_t to) {
        std::string_view part = text_.substr(from, to - from);
        std::size_t lead = part.find_first_not_of(" \t\r\n");
        if (lead == std::string_view::npos) {
            fail(from, "expected an expression");
            return {};
        }
        ExpressionScope es;
        if (scope_.formals) es.variables = *scope_.formals;
        es.defines = scope_.defines;
        es.state = scope_.state;
        es.arrays = scope_.arrays;
        std::size_t end = part.find_last_not_of(" \t\r\n");
        Expression e =
            compileExpression(part.substr(lead, end - lead + 1), locate_(from + lead), es, diags_);
        if (e.empty()) failed_ = true;
        return e;
    }

    // `( expression )` at pos_.
    bool parenthesised(Expression& out, const char* what) {
        skipSpace();
        if (pos_ >= text_.size() || text_[pos_] != '(') {
            fail(pos_, std::string("expected '(' after '") + what + "'");
            return false;
        }
        std::size_t close = findTopLevel(pos_ + 1, ')');
        if (close == std::string_view::npos) {
            fail(pos_, "expected ')' to close the condition");
            return false;
        }
        out = compile(pos_ + 1, close);
        pos_ = close + 1;
        return !failed_;
    }

    void expectSemicolon() {
        skipSpace();
        if (pos_ < text_.size() && text_[pos_] == ';')
            ++pos_;
        else
            fail(pos_, "expected ';' after the statement");
    }

    void parseStatement(Block& out) {
        skipSpace();
        if (pos_ >= text_.size()) {
            fail(pos_, "expected a statement");
            return;
        }
        char c = text_[pos_];
        if (c == ';') {
            ++pos_;
            return;
        }
        if (c == '{') {
            std::size_t close = matchingBrace(text_, pos_);
            if (close == std::string_view::npos) {
                fail(pos_, "expected '}' to close this '{'");
                return;
            }
            std::size_t end = close;
            ++pos_;
            while (!failed_) {
                skipSpace();
                if (pos_ >= end) break;
                parseStatement(out);
            }
            pos_ = close + 1;
            return;
        }
        std::string_view word = peekWord();
        if (word == "if") {
            pos_ += 2;
            Statement s;
            s.kind = Statement::Kind::If;
            if (!parenthesised(s.value, "if")) return;
            parseStatement(s.body);
            skipSpace();
            if (peekWord() == "else") {
                pos_ += 4;
                parseStatement(s.elseBody);
            }
            out.push_back(std::move(s));
            return;
        }
        if (word == "while") {
            pos_ += 5;
            Statement s;
            s.kind = Statement::Kind::While;
            if (!parenthesised(s.value, "while")) return;
            parseStatement(s.body);
            out.push_back(std::move(s));
            return;
        }
        if (word == "do") {
            pos_ += 2;
            Statement s;
            s.kind = Statement::Kind::DoWhile;
            parseStatement(s.body);
            skipSpace();
            if (peekWord() != "while") {
                fail(pos_, "expected 'while (condition);' after the body of 'do'");
                return;
            }
            pos_ += 5;
            if (!parenthesised(s.value, "while")) return;
            expectSemicolon();
            out.push_back(std::move(s));
            return;
        }
        if (word == "for" || word == "array") {
            fail(pos_, "'" + std::string(word) + "' statements are not supported yet");
            return;
        }
        std::size_t end = findTopLevel(pos_, ';');
        if (end == std::string_view::npos) {
            fail(pos_, "expected ';' after the statement");
            return;
        }
        // name = expression;
        if (!word.empty()) {
            std::size_t after = pos_ + word.size();
            while (after < text_.size() && std::isspace(static_cast<unsigned char>(text_[after])))
                ++after;
            if (after < text_.size() && text_[after] == '[' && scope_.arrays &&
                scope_.arrays->count(std::string(word))) {
                // name[i]... = value;
                std::size_t eq = findTopLevel(after, '=');
                while (eq != std::string_view::npos && eq + 1 < text_.size() &&
                       text_[eq + 1] == '=')
                    eq = findTopLevel(eq + 2, '=');
                if (eq == std::string_view::npos || eq > end) {
                    fail(pos_, "expected '=' after the array element");
                    return;
                }
                Statement s;
                s.kind = Statement::Kind::AssignElement;
                ExpressionScope es;
                if (scope_.formals) es.variables = *scope_.formals;
                es.defines = scope_.defines;
                es.state = scope_.state;
                es.arrays = scope_.arrays;
                s.address =
                    compileElementAddress(text_.substr(pos_, eq - pos_), locate_(pos_), es, diags_);
                if (s.address.empty()) {
                    failed_ = true;
                    return;
                }
                s.value = compile(eq + 1, end);
                if (failed_) return;
                pos_ = end + 1;
                out.push_back(std::move(s));
                return;
            }
            if (after < end && text_[after] == '=' &&
                (after + 1 >= text_.size() || text_[after + 1] != '=')) {
                Statement s;
                s.kind = Statement::Kind::Assign;
                std::string name(word);
                if (!assignable(name, pos_, s.kind, s.target)) return;
                s.value = compile(after + 1, end);
                if (failed_) return;
                pos_ = end + 1;
                out.push_back(std::move(s));
                return;
            }
        }
        Statement s;
        s.kind = Statement::Kind::Evaluate;
        s.value = compile(pos_, end);
        if (failed_) return;
        pos_ = end + 1;
        out.push_back(std::move(s));
    }

    // The slot `name` writes to: the production's parameter of that name (cpfg lets a
    // block change it for the rest of the production), else a state slot, new when the
    // name is new.
    bool assignable(const std::string& name, std::size_t at, Statement::Kind& kind,
                    std::uint32_t& slot) {
        if (scope_.formals) {
            const auto& formals = *scope_.formals;
            auto it = std::find(formals.begin(), formals.end(), name);
            if (it != formals.end()) {
                kind = Statement::Kind::AssignParameter;
                slot = static_cast<std::uint32_t>(it - formals.begin());
                return true;
            }
        }
        if (name == "Q" || name == "Z") {
            fail(at, "'" + name +
                         "' is predefined (the step number / derivation length) and "
                         "cannot be assigned");
            return false;
        }
        auto it = scope_.state->find(name);
        if (it != scope_.state->end()) {
            slot = it->second;
            return true;
        }
        slot = static_cast<std::uint32_t>(scope_.stateNames->size());
        scope_.stateNames->push_back(name + scope_.owner);
        (*scope_.state)[name] = slot;
        return true;
    }

    std::string_view text_;
    const std::function<SourceLocation(std::size_t)>& locate_;
    BlockScope& scope_;
    DiagnosticList& diags_;
    std::size_t pos_ = 0;
    bool failed_ = false;
};

}  // namespace

bool parseArrayDeclarations(std::string_view text,
                            const std::function<SourceLocation(std::size_t)>& locate,
                            ArrayState& ls, DiagnosticList& diags) {
    std::size_t pos = 0;
    auto skip = [&] {
        while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos]))) ++pos;
    };
    auto fail = [&](std::size_t at, const std::string& message) {
        diags.error(locate(std::min(at, text.empty() ? 0 : text.size() - 1)), message);
        return false;
    };
    auto constant = [&](std::size_t from, std::size_t to, double& value) {
        std::string_view part = text.substr(from, to - from);
        std::size_t lead = part.find_first_not_of(" \t\r\n");
        if (lead == std::string_view::npos) return fail(from, "expected a value");
        std::size_t last = part.find_last_not_of(" \t\r\n");
        try {
            value = evaluateConstant(part.substr(lead, last - lead + 1), locate(from + lead),
                                     *ls.defines);
        } catch (const Error& e) {
            for (const auto& d : e.diagnostics()) diags.add(d);
            return false;
        }
        return true;
    };
    while (true) {
        skip();
        if (pos >= text.size()) return true;
        if (text[pos] == ';') {
            ++pos;
            continue;
        }
        if (text.substr(pos, 5) != "array" || pos + 5 >= text.size() ||
            !std::isspace(static_cast<unsigned char>(text[pos + 5])))
            return fail(pos, "expected 'array name[size] = { values };' in 'define:'");
        pos += 5;
        while (true) {
            skip();
            std::size_t nameAt = pos;
            while (pos < text.size() && isNameChar(text[pos])) ++pos;
            std::string name(text.substr(nameAt, pos - nameAt));
            if (name.empty() || !isNameStart(name[0]))
                return fail(nameAt, "expected the array's name");
            if (ls.arrays->count(name))
                return fail(nameAt, "array '" + name + "' is declared twice");
            ArrayShape shape;
            std::size_t count = 1;
            skip();
            while (pos < text.size() && text[pos] == '[') {
                std::size_t close = text.find(']', pos);
                if (close == std::string_view::npos) return fail(pos, "expected ']'");
                double size = 0;
                if (!constant(pos + 1, close, size)) return false;
                if (!(size >= 1) || size != std::floor(size) || size > 1e6 ||
                    static_cast<double>(count) * size > 1e7)
                    return fail(pos + 1,
                                "an array dimension is a whole number from 1 (at most "
                                "10000000 elements in all)");
                shape.dims.push_back(static_cast<std::uint32_t>(size));
                count *= static_cast<std::size_t>(size);
                pos = close + 1;
                skip();
            }
            if (shape.dims.empty()) return fail(pos, "expected '[size]' after '" + name + "'");
            shape.base = static_cast<std::uint32_t>(ls.stateNames->size());
            for (std::size_t k = 0; k < count; ++k)
                ls.stateNames->push_back(name + "[" + std::to_string(k) + "]");
            if (pos < text.size() && text[pos] == '=') {
                ++pos;
                skip();
                if (pos >= text.size() || text[pos] != '{')
                    return fail(pos, "expected '{' and the initial values");
                std::size_t close = text.find('}', pos);
                if (close == std::string_view::npos) return fail(pos, "expected '}'");
                std::size_t from = pos + 1, k = 0;
                while (from < close) {
                    while (from < close && std::isspace(static_cast<unsigned char>(text[from])))
                        ++from;
                    std::size_t comma = text.find(',', from);
                    if (comma == std::string_view::npos || comma > close) comma = close;
                    double v = 0;
                    if (!constant(from, comma, v)) return false;
                    if (k >= count)
                        return fail(from, "more initial values than '" + name + "' has elements");
                    ls.initialState->emplace_back(shape.base + static_cast<std::uint32_t>(k++), v);
                    from = comma + 1;
                }
                pos = close + 1;
                skip();
            }
            (*ls.arrays)[name] = shape;
            if (pos < text.size() && text[pos] == ',') {
                ++pos;
                continue;
            }
            break;
        }
        skip();
        if (pos >= text.size() || text[pos] != ';')
            return fail(pos, "expected ';' after the array");
        ++pos;
    }
}

bool parseBlock(std::string_view text, const std::function<SourceLocation(std::size_t)>& locate,
                BlockScope& scope, Block& out, DiagnosticList& diags) {
    return StatementParser(text, locate, scope, diags).parseAll(out);
}

}  // namespace graftal::parsing

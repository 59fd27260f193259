// The parser of the .l language, shared by the files that implement it: parser.cpp reads
// lines, declarations and keyword directives; production_parser.cpp reads productions and
// checks the L-system as a whole.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/lang/lsystem.hpp"
#include "graftal/lang/parser_target.hpp"
#include "graftal/lang/source_text.hpp"
#include "module_lexer.hpp"
#include "statement_parser.hpp"

namespace graftal::parsing {

std::string lower(std::string_view s);
bool isBlank(std::string_view s);
std::size_t firstNonBlank(std::string_view s);  // npos when blank
std::string_view trimView(std::string_view s);

struct Arrow {
    std::size_t pos = std::string_view::npos;
    std::size_t len = 0;
};

// `-->` wins; then the book's `→`; then `->` (not the `<-` `>` of a context like `<->`).
Arrow findArrow(std::string_view s);
// Finds `c` outside parentheses, from `from`; npos when absent.
std::size_t findTopLevel(std::string_view s, char c, std::size_t from = 0);
std::size_t findLastTopLevel(std::string_view s, char c);

// The keywords a line may start with, in the spelling the messages use.
extern const std::vector<std::string> kKeywords;

class Parser {
  public:
    // Reads `src` and writes what it finds through `target`; problems go to `diags`.
    Parser(const SourceText& src, const ParseOptions& options, DiagnosticList& diags,
           ParserTarget& target)
        : src_(src),
          options_(options),
          diags_(diags),
          target_(target),
          surfaceLetters_(options.surfaceLetters) {}

    void run();

  private:
    SourceLocation at(const SourceLine& line, std::size_t offset) const;

    void collectDeclarations();

    static bool isModuleDeclaration(std::string_view rest);

    static std::string normaliseKeyword(std::string_view s);

    void parseDefine(const SourceLine& line, std::size_t start);

    void parseModuleDeclaration(const SourceLine& line, std::size_t start);

    void parseLine(const SourceLine& line);

    // ---- directives ------------------------------------------------------------------

    bool constantValue(const SourceLine& line, std::size_t from, double& value);

    void parseDirective(const SourceLine& line, const std::string& kw, std::size_t valueStart);

    void parseSchedule(const SourceLine& line, std::size_t valueStart);

    void parseAxiom(const SourceLine& line, std::size_t valueStart);

    void checkBrackets(const std::vector<ModuleToken>& toks, const SourceLine& line,
                       const char* what);

    // Start:, StartEach:, EndEach:, End: blocks (read before everything else, so that
    // their variables are global wherever the lines stand).
    void parseGlobalBlocks();
    bool parseGlobalBlock(const SourceLine& line, const std::string& kw, std::size_t valueStart);
    // A `{ ... }` at text[open] of `line` into `out`; false after reporting.
    bool parseBlockAt(const SourceLine& line, std::size_t open, std::size_t close,
                      BlockScope& scope, Block& out);
    static bool isGlobalBlockKeyword(const std::string& kw);

    void parseIgnore(const SourceLine& line, const std::string& kw, std::size_t valueStart);
    void parseAges(const SourceLine& line, std::size_t valueStart);

    // View settings for 3D pictures (view_parser.cpp).
    bool parseViewSetting(const SourceLine& line, const std::string& kw, std::size_t valueStart);
    bool vectorValue(const SourceLine& line, std::size_t from, Vec3& out);

    // ---- productions -----------------------------------------------------------------

    bool parsePatterns(const SourceLine& line, std::size_t from, std::size_t to,
                       std::vector<ModulePattern>& out, std::vector<std::string>& formals,
                       const char* what, bool allowEmpty);

    void parseProduction(const SourceLine& line, Arrow arrow);

    void resolveSchedule();

    void finish();

    static constexpr std::size_t kMaxErrors = 20;
    std::size_t errorCount() const;

    const SourceText& src_;
    const ParseOptions& options_;
    DiagnosticList& diags_;
    ParserTarget& target_;
    std::map<std::string, std::string> defines_;  // #define and -D, for expressions
    std::vector<std::string> tableNames_;         // in declaration order
    bool scheduleRepeats_ = false;
    std::map<std::string, int> defineLines_;
    // The state blocks and expressions share (see LSystem::stateNames); handed to the
    // target once everything is read.
    std::map<std::string, std::uint32_t> globals_ = {{"Q", 0}, {"Z", 1}};
    std::vector<std::string> stateNames_ = {"Q", "Z"};
    std::map<std::string, ArrayShape> arrays_;
    std::vector<std::pair<std::uint32_t, double>> initialState_;
    bool sawLsystemHeader_ = false;
    bool sawAxiom_ = false;
    int axiomLine_ = 0;
    bool sawIgnore_ = false, sawConsider_ = false;
    bool ended_ = false;
    enum class Section { Main, Decomposition, Homomorphism } section_ = Section::Main;
    int currentTable_ = -1;
    struct RawScheduleEntry {
        std::string name;
        int steps = -1;
        SourceLocation location;
    };
    std::vector<RawScheduleEntry> rawSchedule_;
    int scheduleLine_ = 0;
    // One-letter surface names (the view file's and the .l's `surface:` lines read so
    // far): after ~ such a letter is the surface alone, as cpfg reads it.
    std::string surfaceLetters_;
};

}  // namespace graftal::parsing

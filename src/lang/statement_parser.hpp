// Statement blocks of the .l language: `{ x = 1; if (x > 0) { ... } else ...; }` as cpfg
// reads them in productions and in Start:, StartEach:, EndEach: and End:.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "graftal/lang/lsystem.hpp"

namespace graftal::parsing {

// What the statements of one block may name, and where new variables go.
struct BlockScope {
    const std::vector<std::string>* formals = nullptr;  // the production's parameters
    const std::map<std::string, std::string>* defines = nullptr;
    std::map<std::string, std::uint32_t>* state = nullptr;  // visible variables; grows
    std::vector<std::string>* stateNames = nullptr;         // LSystem::stateNames; grows
    const std::map<std::string, ArrayShape>* arrays = nullptr;
    std::string owner;  // appended to the names of new slots, e.g. " (line 7)"
};

// Parses `text`, the inside of a block; `locate(i)` is the location of text[i]. A name
// assigned for the first time becomes a new state slot. Returns false after reporting.
bool parseBlock(std::string_view text, const std::function<SourceLocation(std::size_t)>& locate,
                BlockScope& scope, Block& out, DiagnosticList& diags);

// The state the arrays of `define:` blocks are added to.
struct ArrayState {
    const std::map<std::string, std::string>* defines = nullptr;
    std::map<std::string, ArrayShape>* arrays = nullptr;
    std::vector<std::string>* stateNames = nullptr;  // grows by one slot per element
    std::vector<std::pair<std::uint32_t, double>>* initialState = nullptr;
};

// Parses the inside of `define: { array a[2] = {1, 2}, b[2][3]; ... }`, adding the arrays
// to `state` (their elements become state slots).
bool parseArrayDeclarations(std::string_view text,
                            const std::function<SourceLocation(std::size_t)>& locate,
                            ArrayState& state, DiagnosticList& diags);

// The end of the `{ ... }` block opening at text[open]: the index of its '}', npos when
// it is not closed. Braces inside "strings" do not count.
std::size_t matchingBrace(std::string_view text, std::size_t open);

}  // namespace graftal::parsing

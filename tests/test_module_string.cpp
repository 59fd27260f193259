#include <gtest/gtest.h>

#include "graftal/core/module_string.hpp"

using namespace graftal;

TEST(ModuleString, PrintsModulesConcatenated) {
    SymbolTable t;
    ModuleString s;
    for (char c : std::string("F+F")) s.push(static_cast<Symbol>(c));
    EXPECT_EQ(s.toString(t), "F+F");
    EXPECT_FALSE(s.hasParameters());
}

TEST(ModuleString, PrintsParametersInShortestRoundTripForm) {
    SymbolTable t;
    ModuleString s;
    s.push('A', std::vector<double>{1, 2.5});
    s.push('B');
    s.push('C', std::vector<double>{0.1, -3, 1e20});
    EXPECT_EQ(s.toString(t), "A(1,2.5)BC(0.1,-3,1e+20)");
    ASSERT_EQ(s.params(0).size(), 2u);
    EXPECT_EQ(s.params(1).size(), 0u);
    EXPECT_EQ(s.params(2)[1], -3);
}

TEST(ModuleString, DeclaredNamesPrintAsDeclared) {
    SymbolTable t;
    Symbol apex = t.declare("apex");
    EXPECT_GE(apex, kFirstNamedSymbol);
    EXPECT_EQ(t.declare("apex"), apex);
    ModuleString s;
    s.push(apex);
    s.push('[');
    s.push(apex);
    s.push(']');
    EXPECT_EQ(s.toString(t), "apex[apex]");
}

TEST(ModuleString, LongestNamesComeFirst) {
    SymbolTable t;
    t.declare("ab");
    t.declare("abc");
    t.declare("a1");
    ASSERT_EQ(t.namesLongestFirst().size(), 3u + 5u) << "three declared, five query modules";
    EXPECT_EQ(t.name(t.namesLongestFirst()[0]), "abc");
}

TEST(FormatNumber, IntegersHaveNoDecimalPoint) {
    EXPECT_EQ(formatNumber(3), "3");
    EXPECT_EQ(formatNumber(-0.0), "0");
    EXPECT_EQ(formatNumber(0.1 + 0.2), "0.30000000000000004");
    EXPECT_EQ(formatNumber(1e15), "1e+15");
}

TEST(ModuleString, CountSymbolsAgreesWithCountingOneByOne) {
    ModuleString s;
    std::vector<std::uint64_t> expected(140, 0);
    std::uint32_t x = 12345;
    for (int i = 0; i < 1'500'003; ++i) {
        x = x * 1664525u + 1013904223u;
        Symbol sym = static_cast<Symbol>((x >> 16) % 140);
        s.push(sym);
        ++expected[sym];
    }
    for (unsigned threads : {1u, 2u, 3u, 7u}) EXPECT_EQ(countSymbols(s, 140, threads), expected);
}

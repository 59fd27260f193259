// Numbers to text and back as std::to_chars and std::from_chars do it, for every standard
// library graftal is built with: emscripten's libc++ (14) has the integer overloads but not
// the floating-point ones, so there the same text is made from printf and strtod.
#pragma once

#include <charconv>
#include <concepts>

namespace graftal {

#if defined(_LIBCPP_VERSION) && _LIBCPP_VERSION < 170000
#define GRAFTAL_FLOAT_CHARCONV_FALLBACK 1
#endif

// The shortest text that reads back as the same number, fixed or scientific whichever is
// shorter (fixed on a tie): std::to_chars(first, last, v). Needs room for 32 characters.
std::to_chars_result numberToChars(char* first, char* last, double v);
std::to_chars_result numberToChars(char* first, char* last, float v);

// A decimal number in std::from_chars's general format (no leading blank or '+', no hex).
std::from_chars_result numberFromChars(const char* first, const char* last, double& v);

// The same from printf and strtod: what the functions above are where the standard library
// lacks the floating-point overloads (and what the tests compare with it elsewhere).
std::to_chars_result printfNumberToChars(char* first, char* last, double v);
std::to_chars_result printfNumberToChars(char* first, char* last, float v);
std::from_chars_result strtodNumberFromChars(const char* first, const char* last, double& v);

// Integers go to the standard library, which has them everywhere.
template <std::integral Integer>
std::to_chars_result numberToChars(char* first, char* last, Integer v) {
    return std::to_chars(first, last, v);
}

template <std::integral Integer>
std::from_chars_result numberFromChars(const char* first, const char* last, Integer& v) {
    return std::from_chars(first, last, v);
}

}  // namespace graftal

// std::bit_cast where the standard library has it, and the compiler's builtin that
// implements it where it does not (emscripten's libc++ 14, for the web build).
#pragma once

#include <type_traits>
#if __has_include(<bit>)
#include <bit>
#endif

namespace graftal {

template <class To, class From>
    requires(sizeof(To) == sizeof(From) && std::is_trivially_copyable_v<To> &&
             std::is_trivially_copyable_v<From>)
constexpr To bitCast(const From& from) noexcept {
#ifdef __cpp_lib_bit_cast
    return std::bit_cast<To>(from);
#else
    return __builtin_bit_cast(To, from);
#endif
}

}  // namespace graftal

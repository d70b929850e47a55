#pragma once
// std::bit_cast (C++20 <bit>) for the standard libraries that lack it:
// Emscripten 3.1.6's libc++ (the web engine's build, web/CMakeLists.txt) has
// no std::bit_cast. It is the compilers' builtin, as std::bit_cast itself is
// in libstdc++ and newer libc++ (GCC 11+, clang 9+): constexpr, no copy.
#include <type_traits>

namespace overflight {

// The object representation of `from` read as a To (same size, both
// trivially copyable).
template <typename To, typename From>
constexpr To bit_cast(const From& from) noexcept {
    static_assert(sizeof(To) == sizeof(From), "bit_cast between types of different sizes");
    static_assert(std::is_trivially_copyable_v<To> && std::is_trivially_copyable_v<From>);
    return __builtin_bit_cast(To, from);
}

} // namespace overflight

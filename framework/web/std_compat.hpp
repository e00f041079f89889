#pragma once
// What Debian's Emscripten 3.1.6 (its libc++ predates C++20's <bit> in full) lacks of the
// standard library springlab uses, force-included into every object of the web build
// (CMakeLists.txt). Where the library has it, this adds nothing.
#include <version>

#if !defined(__cpp_lib_bit_cast)
#include <type_traits>
namespace std {
// std::bit_cast as C++20 defines it, on the compiler's builtin.
template <class To, class From>
  requires(sizeof(To) == sizeof(From) && is_trivially_copyable_v<To> && is_trivially_copyable_v<From>)
constexpr To bit_cast(const From& from) noexcept {
  return __builtin_bit_cast(To, from);
}
}  // namespace std
#endif

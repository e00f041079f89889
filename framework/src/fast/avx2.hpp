#pragma once
// Loops built twice, for the machine's baseline and for AVX2, and the one this CPU runs.
// GCC on x86-64 compiles a twin with target("avx2"): 4 doubles per instruction where the CPU
// has it, a portable binary everywhere. AVX2 without FMA: the same operations in the same
// order, so both twins give bitwise the same results (test SpringFamilies.Avx2AndBaselineLoops
// GiveTheSameBits). Other compilers build the baseline only. (Explicit twins, not
// target_clones: GCC 12's clones lose `restrict` on their parameters, and with it the
// vectorisation.) Not on Windows: MinGW-w64's GCC does not align the stack to 32 bytes for
// AVX spills there (GCC bug 54412), so an AVX2 function can fault.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(_WIN32)
#define SPRINGLAB_AVX2_VARIANT 1
#else
#define SPRINGLAB_AVX2_VARIANT 0
#endif

namespace springlab {

// Whether this CPU (and its operating system) runs AVX2 instructions.
bool hasAvx2();
// Whether the twins' AVX2 builds run: hasAvx2(), unless a test turned them off
// (allowAvx2(false)) to compare them with the baseline's, which must give the same bits.
bool useAvx2();
void allowAvx2(bool allowed);

}  // namespace springlab

// SPRINGLAB_AVX2_TWINS(kernel, (parameters), (arguments)) defines kernelPortable and, where
// built, kernelAvx2, each `kernel arguments;` with every call inside inlined (flatten), and
// kernelForThisCpu(), the twin to call. `restrict` goes on the twins' own parameters: on the
// inlined kernel's alone GCC 12 drops it and does not vectorise.
#if SPRINGLAB_AVX2_VARIANT
#define SPRINGLAB_AVX2_TWINS(kernel, parameters, arguments)                                          \
  [[gnu::flatten]] void kernel##Portable parameters { kernel arguments; }                          \
  [[gnu::flatten]] __attribute__((target("avx2"))) void kernel##Avx2 parameters { kernel arguments; } \
  auto kernel##ForThisCpu() { return ::springlab::useAvx2() ? kernel##Avx2 : kernel##Portable; }
#else
#define SPRINGLAB_AVX2_TWINS(kernel, parameters, arguments)                 \
  [[gnu::flatten]] void kernel##Portable parameters { kernel arguments; } \
  auto kernel##ForThisCpu() { return kernel##Portable; }
#endif

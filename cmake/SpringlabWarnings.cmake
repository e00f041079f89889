# Warnings every target of ours compiles with; sanitizers on request.
#
# springlab_warnings          the framework, the reference, the tests
# springlab_student_warnings  the student's exercises (labs/): the same warnings, but the
#                             conversion class (`int n = v.size();`, `k < v.size()`) stays a
#                             warning even with SPRINGLAB_WARNINGS_AS_ERRORS
#
# SPRINGLAB_WARNINGS_AS_ERRORS is OFF by default: a student's build never stops on a warning.
# CI (.ci/run) and the instructor's `./springlab test` in a tree with solutions/ turn it ON.
# The grader compiles a submission with these flags minus -Werror (tools/springlab_grader).
add_library(springlab_warnings INTERFACE)
add_library(springlab_student_warnings INTERFACE)
if(MSVC)
  # /W4 is MSVC's -Wall -Wextra; C4244/C4267 are its -Wconversion.
  target_compile_options(springlab_warnings INTERFACE /W4 /permissive-)
  target_compile_options(springlab_student_warnings INTERFACE /W4 /permissive-)
  if(SPRINGLAB_WARNINGS_AS_ERRORS)
    target_compile_options(springlab_warnings INTERFACE /WX)
    target_compile_options(springlab_student_warnings INTERFACE /WX /wd4244 /wd4267 /wd4389 /wd4018)
  endif()
else()
  set(springlab_warning_flags -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion)
  # Without OpenMP (Apple Clang) the loops stay serial: their pragmas are ignored, and the
  # thread counts and helpers only those pragmas use are left unused. (After -Wall, which
  # Clang would otherwise let turn them back on; the OpenMP builds keep these warnings.)
  if(NOT SPRINGLAB_OPENMP)
    list(APPEND springlab_warning_flags -Wno-unknown-pragmas -Wno-unused-variable
         -Wno-unused-function -Wno-unused-but-set-variable)
  endif()
  target_compile_options(springlab_warnings INTERFACE ${springlab_warning_flags})
  target_compile_options(springlab_student_warnings INTERFACE ${springlab_warning_flags})
  if(SPRINGLAB_WARNINGS_AS_ERRORS)
    target_compile_options(springlab_warnings INTERFACE -Werror)
    target_compile_options(springlab_student_warnings INTERFACE -Werror -Wno-error=conversion
                           -Wno-error=float-conversion -Wno-error=sign-compare)
  endif()
endif()

# Stubs do not use their parameters yet: springlab_stub_warnings silences that one warning.
# It must come after the -Wextra it overrides (Clang takes the last of the two; GCC does not
# care), so a lab target links it after its warnings library: CMake adds the interface
# options in link order, and a target's own options before all of them.
add_library(springlab_stub_warnings INTERFACE)
if(MSVC)
  target_compile_options(springlab_stub_warnings INTERFACE /wd4100)
else()
  target_compile_options(springlab_stub_warnings INTERFACE -Wno-unused-parameter)
endif()

# Flags that are GCC/Clang spellings only: a helper so MSVC builds skip them.
function(springlab_gnu_options target scope)
  if(NOT MSVC)
    target_compile_options(${target} ${scope} ${ARGN})
  endif()
endfunction()

if(SPRINGLAB_SANITIZERS)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

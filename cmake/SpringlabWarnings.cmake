# Warnings every target of ours compiles with; sanitizers on request.
add_library(springlab_warnings INTERFACE)
target_compile_options(springlab_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                       -Wno-sign-conversion)
if(SPRINGLAB_WARNINGS_AS_ERRORS)
  target_compile_options(springlab_warnings INTERFACE -Werror)
endif()
if(SPRINGLAB_SANITIZERS)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

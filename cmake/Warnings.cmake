# Warnings and sanitizers as an INTERFACE target every scansurf target links.
add_library(scansurf_warnings INTERFACE)
target_compile_options(scansurf_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion
  -Wno-missing-field-initializers)  # `VkXxxInfo info{VK_STRUCTURE_TYPE_XXX};` zero-fills the rest on purpose
if(SCANSURF_SANITIZE)
  target_compile_options(scansurf_warnings INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer)
  target_link_options(scansurf_warnings INTERFACE -fsanitize=address,undefined)
endif()
if(SCANSURF_WERROR)
  target_compile_options(scansurf_warnings INTERFACE -Werror)
endif()

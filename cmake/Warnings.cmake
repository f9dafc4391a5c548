# Warnings and sanitizers as an INTERFACE target every scansurf target links.
add_library(scansurf_warnings INTERFACE)
target_compile_options(scansurf_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion)
if(SCANSURF_SANITIZE)
  target_compile_options(scansurf_warnings INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer)
  target_link_options(scansurf_warnings INTERFACE -fsanitize=address,undefined)
endif()

# Flags every trackphys target shares, carried by an interface target so that they never
# leak into a consumer's build through the installed package.
add_library(trackphys_options INTERFACE)

# Same inputs, same build -> bit-identical results: no fused multiply-add contraction.
target_compile_options(trackphys_options INTERFACE
  -ffp-contract=off
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  $<$<BOOL:${TRACKPHYS_WARNINGS_AS_ERRORS}>:-Werror>)

if(TRACKPHYS_SANITIZE)
  target_compile_options(trackphys_options INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  target_link_options(trackphys_options INTERFACE -fsanitize=address,undefined)
endif()

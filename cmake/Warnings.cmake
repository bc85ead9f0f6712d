# Warnings and floating-point flags for our own targets only (third-party headers are SYSTEM).
function(laytracks_target_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
    -Wnon-virtual-dtor -Wimplicit-fallthrough
    # No fused multiply-add contraction: predicates and constructions must round as written.
    -ffp-contract=off)
  if(LAYTRACKS_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

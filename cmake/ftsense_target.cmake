# Warnings and standard per target, never global.
function(ftsense_target_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(FTSENSE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()


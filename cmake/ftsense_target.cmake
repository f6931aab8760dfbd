# Warnings and standard per target, never global.
function(ftsense_target_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(FTSENSE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# Test programs compile as unity batches (up to seven test files per translation unit): their files
# include the same heavy headers (GoogleTest, Eigen, nlohmann_json, the pipeline), whose inline code
# every translation unit would otherwise parse and optimise again. Measured on one batch of eight
# core test files at -O3: 67 s as one unit against 191 s as eight (docs/reliability.md).
# -DFTSENSE_UNITY_TESTS=OFF rebuilds one edited test file alone (quicker while working on it).
option(FTSENSE_UNITY_TESTS "Compile test programs as unity batches" ON)
function(ftsense_unity_test_target target)
  if(FTSENSE_UNITY_TESTS)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_MODE BATCH UNITY_BUILD_BATCH_SIZE 7)
  endif()
endfunction()

# Contact-point force distribution QP (method.md section 4).
# include()d from plugins/biped/CMakeLists.txt. Expects the caller to have run
#   find_package(Eigen3 3.4 REQUIRED NO_MODULE), find_package(Ceres 2.1 REQUIRED),
#   find_package(GTest) and optionally find_package(benchmark), and enable_testing().
# Paths are relative to this file, so the fragment works from any including directory.

set(FTSENSE_CONTACT_FORCE_QP_DIR "${CMAKE_CURRENT_LIST_DIR}")

add_library(ftsense_contact_force_qp STATIC
  "${FTSENSE_CONTACT_FORCE_QP_DIR}/src/contact_force_qp.cpp"
  "${FTSENSE_CONTACT_FORCE_QP_DIR}/src/contact_force_qp_ceres.cpp")
add_library(ftsense::contact_force_qp ALIAS ftsense_contact_force_qp)
target_include_directories(ftsense_contact_force_qp PUBLIC
  "$<BUILD_INTERFACE:${FTSENSE_CONTACT_FORCE_QP_DIR}/include>"
  "$<INSTALL_INTERFACE:include>")
target_link_libraries(ftsense_contact_force_qp PUBLIC Eigen3::Eigen PRIVATE Ceres::ceres)
target_compile_features(ftsense_contact_force_qp PUBLIC cxx_std_20)
target_compile_options(ftsense_contact_force_qp PRIVATE -Wall -Wextra -Wpedantic)
set_target_properties(ftsense_contact_force_qp PROPERTIES POSITION_INDEPENDENT_CODE ON)
# Its Impl holds types of the file's anonymous namespace: inside a unity batch (both presets
# build so) GCC would warn -Wsubobject-linkage, so the file compiles alone.
set_source_files_properties("${FTSENSE_CONTACT_FORCE_QP_DIR}/src/contact_force_qp_ceres.cpp"
                            PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)

if(TARGET GTest::gtest_main)
  include(GoogleTest)
  add_executable(ftsense_contact_force_qp_tests
    "${FTSENSE_CONTACT_FORCE_QP_DIR}/tests/test_contact_force_qp.cpp")
  target_link_libraries(ftsense_contact_force_qp_tests PRIVATE ftsense::contact_force_qp GTest::gtest_main)
  target_compile_options(ftsense_contact_force_qp_tests PRIVATE -Wall -Wextra -Wpedantic)
  gtest_discover_tests(ftsense_contact_force_qp_tests DISCOVERY_TIMEOUT 60)
endif()

if(TARGET benchmark::benchmark)
  add_executable(ftsense_contact_force_qp_bench
    "${FTSENSE_CONTACT_FORCE_QP_DIR}/bench/bench_contact_force_qp.cpp")
  target_link_libraries(ftsense_contact_force_qp_bench PRIVATE ftsense::contact_force_qp benchmark::benchmark)
  target_compile_options(ftsense_contact_force_qp_bench PRIVATE -Wall -Wextra -Wpedantic)
endif()

# dtwire_add_test(NAME name LABEL unit|verification|slow SOURCES ... LIBS ...)
# One GoogleTest executable per call; every test case becomes a ctest test with the label.
function(dtwire_add_test)
  cmake_parse_arguments(T "" "NAME;LABEL;TIMEOUT" "SOURCES;LIBS" ${ARGN})
  if(NOT T_LABEL)
    message(FATAL_ERROR "dtwire_add_test(${T_NAME}): LABEL is required")
  endif()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 600)
  endif()
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main dtwire_warnings)
  target_compile_definitions(${T_NAME} PRIVATE
    DTWIRE_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data"
    DTWIRE_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  gtest_discover_tests(${T_NAME}
    WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}
    PROPERTIES LABELS ${T_LABEL} TIMEOUT ${T_TIMEOUT}
    DISCOVERY_TIMEOUT 60)
endfunction()

# Warnings on for every project target (not for third-party headers).
add_library(dtwire_warnings INTERFACE)
target_compile_options(dtwire_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow=local -Wno-unused-parameter>)

# Every project target links this interface, so it also carries the Release build's debug-information
# switch: deal.II's flags (Debian's build flags) add -g, which makes a deal.II object about a third
# slower to compile and the test executables slow to link (docs/validation.md, "Build time").
# -g0 comes after deal.II's flags on the command line and wins; DTWIRE_DEBUG_INFO=ON keeps -g.
option(DTWIRE_DEBUG_INFO "Keep debug information in Release builds" OFF)
if(NOT DTWIRE_DEBUG_INFO)
  target_compile_options(dtwire_warnings INTERFACE $<$<AND:$<CONFIG:Release>,$<CXX_COMPILER_ID:GNU,Clang>>:-g0>)
endif()

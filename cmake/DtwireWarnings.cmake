# Warnings on for every project target (not for third-party headers).
add_library(dtwire_warnings INTERFACE)
target_compile_options(dtwire_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow=local -Wno-unused-parameter>)

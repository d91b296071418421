# Writes generated/dtwire/version.hpp from the git checkout at SOURCE_DIR (script mode: cmake -P).
# configure_file leaves the header untouched while its text stays the same, so only a new commit
# (or a tree turning dirty or clean) recompiles the one file that includes it (core/provenance.cpp).
find_package(Git QUIET)
set(DTWIRE_GIT_HASH "unknown")
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --short=12 HEAD
    WORKING_DIRECTORY ${SOURCE_DIR}
    OUTPUT_VARIABLE _hash OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE _rc)
  if(_rc EQUAL 0 AND _hash)
    set(DTWIRE_GIT_HASH "${_hash}")
    execute_process(COMMAND ${GIT_EXECUTABLE} status --porcelain --untracked-files=no
      WORKING_DIRECTORY ${SOURCE_DIR}
      OUTPUT_VARIABLE _dirty OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(_dirty)
      set(DTWIRE_GIT_HASH "${DTWIRE_GIT_HASH}-dirty")
    endif()
  endif()
endif()
configure_file(${SOURCE_DIR}/cmake/version.hpp.in ${OUTPUT} @ONLY)

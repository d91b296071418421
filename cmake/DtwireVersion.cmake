# Version and git hash, baked into a generated header that only core/provenance.cpp includes
# (the rest asks dtwire::git_hash()). The header is written at configure time and refreshed at
# every build (target dtwire_version), so a build after a commit records that commit.
set(DTWIRE_VERSION_HEADER ${CMAKE_BINARY_DIR}/generated/dtwire/version.hpp)
set(_dtwire_version_args -DSOURCE_DIR=${CMAKE_CURRENT_SOURCE_DIR} -DOUTPUT=${DTWIRE_VERSION_HEADER}
    -DPROJECT_VERSION=${PROJECT_VERSION} -P ${CMAKE_CURRENT_SOURCE_DIR}/cmake/DtwireVersionWrite.cmake)
execute_process(COMMAND ${CMAKE_COMMAND} ${_dtwire_version_args})
add_custom_target(dtwire_version
  COMMAND ${CMAKE_COMMAND} ${_dtwire_version_args}
  BYPRODUCTS ${DTWIRE_VERSION_HEADER}
  COMMENT "Reading the git hash into version.hpp")

# Installs the build into PREFIX and runs the installed dtwire away from the source and build
# trees: its defaults (campaign file, DEM parameter file) must come from PREFIX/share/dtwire.
# usage: cmake -DBUILD_DIR=... -DPREFIX=... -P installed_prefix_test.cmake
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX}
                RESULT_VARIABLE result OUTPUT_QUIET ERROR_VARIABLE error)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "cmake --install failed: ${error}")
endif()
set(dtwire ${PREFIX}/bin/dtwire)
set(campaign ${PREFIX}/share/dtwire/experiments/default/campaign.toml)
foreach(file ${dtwire} ${campaign} ${PREFIX}/share/dtwire/scripts/plot_curves.py)
  if(NOT EXISTS ${file})
    message(FATAL_ERROR "not installed: ${file}")
  endif()
endforeach()

# The default campaign is the installed one.
execute_process(COMMAND ${dtwire} campaign --help WORKING_DIRECTORY ${PREFIX}
                RESULT_VARIABLE result OUTPUT_VARIABLE help ERROR_VARIABLE error)
string(FIND "${help}" "${campaign}" at)
if(NOT result EQUAL 0 OR at EQUAL -1)
  message(FATAL_ERROR "dtwire campaign --help (exit ${result}) does not default to ${campaign}:\n${help}${error}")
endif()

# A command that reads installed data by default (the thesis parameter set) runs.
execute_process(COMMAND ${dtwire} dem driver --law thesis --path axial_pull --out ${PREFIX}/driver_run
                WORKING_DIRECTORY ${PREFIX} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE error)
if(NOT result EQUAL 0 OR NOT EXISTS ${PREFIX}/driver_run/single_wire/axial_pull.csv)
  message(FATAL_ERROR "installed dtwire dem driver failed (exit ${result}):\n${output}${error}")
endif()

# The campaign file is checked completely (commands, placeholders, graph) by the installed binary.
execute_process(COMMAND ${dtwire} campaign ${campaign} --only sw_mesh -o ${PREFIX}/campaign_run
                WORKING_DIRECTORY ${PREFIX} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE error)
if(NOT result EQUAL 0 OR NOT EXISTS ${PREFIX}/campaign_run/report.html)
  message(FATAL_ERROR "installed dtwire campaign --only sw_mesh failed (exit ${result}):\n${output}${error}")
endif()
message(STATUS "installed dtwire works from ${PREFIX}")

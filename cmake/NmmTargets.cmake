# SPDX-License-Identifier: MIT
# Helpers shared by every module: warning flags and module library declaration.

set(NMM_WARNING_FLAGS -Wall -Wextra -Wpedantic -Wshadow -Woverloaded-virtual -Wsuggest-override
                      -Wfloat-conversion)
if(NMM_WARNINGS_AS_ERRORS)
  list(APPEND NMM_WARNING_FLAGS -Werror)
endif()

# Applies the project's warnings to one of our own targets (never to third-party code).
function(nmm_target_warnings target)
  target_compile_options(${target} PRIVATE ${NMM_WARNING_FLAGS})
endfunction()

# nmm_add_module(NAME SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# One static library per top-level folder; include paths are relative to the source root
# ("mesh/geometry.hpp"), so an #include always names its module.
function(nmm_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC "${PROJECT_SOURCE_DIR}")
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  nmm_target_warnings(${name})
endfunction()

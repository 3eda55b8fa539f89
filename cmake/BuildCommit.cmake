# Writes OUT, a header defining CDBENCH_BUILD_COMMIT: the commit the sources in SOURCE_DIR are at
# when the build runs, "+dirty" appended when tracked files outside results/ differ from it,
# "unknown" outside a git checkout. Run at every build (cmake -P); the file is rewritten only when
# that changes, so only what includes it is compiled again.
cmake_minimum_required(VERSION 3.25)
execute_process(COMMAND git -C "${SOURCE_DIR}" rev-parse HEAD
                OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE
                RESULT_VARIABLE failed ERROR_QUIET)
if(failed OR commit STREQUAL "")
  set(commit "unknown")
else()
  # Result files a run writes into results/ do not make the code differ from the commit.
  execute_process(COMMAND git -C "${SOURCE_DIR}" status --porcelain --untracked-files=no -- .
                          ":(exclude)results"
                  OUTPUT_VARIABLE changes OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT changes STREQUAL "")
    string(APPEND commit "+dirty")
  endif()
endif()
file(CONFIGURE OUTPUT "${OUT}"
     CONTENT "#pragma once\n// Written by cmake/BuildCommit.cmake at build time.\n#define CDBENCH_BUILD_COMMIT \"@commit@\"\n"
     @ONLY)

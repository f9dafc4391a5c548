# Helpers for the command-line tests (cmake -P scripts): run scansurf and check its exit code
# and output. Expects SCANSURF (the executable).

# Runs scansurf with ARGN; fails unless it exits with expected_code. Leaves stdout+stderr in
# last_output.
function(run_scansurf expected_code)
  execute_process(COMMAND ${SCANSURF} ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(last_output "${out}${err}" PARENT_SCOPE)
  if(NOT code EQUAL expected_code)
    message(FATAL_ERROR "scansurf ${ARGN}: exit ${code}, expected ${expected_code}\n${out}${err}")
  endif()
endfunction()

# Fails unless the last run's output matches the regular expression.
function(expect_output pattern)
  if(NOT last_output MATCHES "${pattern}")
    message(FATAL_ERROR "output does not match '${pattern}':\n${last_output}")
  endif()
endfunction()

# Fails unless every file named in ARGN exists in `dir`.
function(expect_files dir)
  foreach(file ${ARGN})
    if(NOT EXISTS "${dir}/${file}")
      message(FATAL_ERROR "missing ${dir}/${file}")
    endif()
  endforeach()
endfunction()

# Fails when a failed run left anything in `dir` (which may not exist).
function(expect_nothing_left dir)
  if(EXISTS "${dir}")
    file(GLOB leftovers "${dir}/*")
    if(leftovers)
      message(FATAL_ERROR "failed runs left output behind: ${leftovers}")
    endif()
  endif()
endfunction()

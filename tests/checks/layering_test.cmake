# The module layering is enforced by the build: compiled with a module's include view
# (engine/CMakeLists.txt, scansurf_module), a header of a module below it compiles and a
# header of a module above it does not. Inputs: CXX, VIEWS (build/engine/layers), PUBLIC
# (engine/include), GENERATED (build/engine/include), GLM, SHARED (shaders/shared), WORK.
file(MAKE_DIRECTORY "${WORK}")
# module, header, whether it may include it
set(cases
  scansurf_geometry core/parallel.h yes
  scansurf_geometry gpu/context.h no
  scansurf_geometry passes/classification.h no
  scansurf_io geometry/polygon.h yes
  scansurf_io gpu/resources.h no
  scansurf_io passes/preview.h no
  scansurf_gpu geometry/polygon.h no
  scansurf_passes geometry/polygon.h yes
  scansurf_passes io/atomic_file.h no
  scansurf_core geometry/polygon.h no)
set(failures 0)
set(glm "")
if(NOT GLM STREQUAL "/usr/include")  # a compiler's own include directory must not be -isystem'd again
  set(glm -isystem "${GLM}")
endif()
set(i 0)
list(LENGTH cases n)
while(i LESS n)
  list(GET cases ${i} module)
  math(EXPR j "${i} + 1")
  list(GET cases ${j} header)
  math(EXPR k "${i} + 2")
  list(GET cases ${k} allowed)
  math(EXPR i "${i} + 3")
  set(probe "${WORK}/probe_${i}.cpp")
  file(WRITE "${probe}" "#include \"${header}\"\nint main() { return 0; }\n")
  execute_process(COMMAND "${CXX}" -std=c++20 -fsyntax-only -I "${VIEWS}/${module}" -I "${PUBLIC}" -I "${GENERATED}"
                          ${glm} -I "${SHARED}" "${probe}"
                  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
  if(allowed STREQUAL "yes" AND NOT rc EQUAL 0)
    message(SEND_ERROR "${module} may include ${header}, but it does not compile:\n${err}")
    math(EXPR failures "${failures} + 1")
  elseif(allowed STREQUAL "no" AND rc EQUAL 0)
    message(SEND_ERROR "${module} must not see ${header}, yet it compiles with the module's include view")
    math(EXPR failures "${failures} + 1")
  endif()
endwhile()
if(failures GREATER 0)
  message(FATAL_ERROR "${failures} layering case(s) failed")
endif()
message(STATUS "layering: every module sees only the modules below it")

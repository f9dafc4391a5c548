# The module layering is enforced by the build: compiled with a module's include view
# (engine/CMakeLists.txt, scansurf_module), a header of a module below it compiles and a
# header of a module above it does not. Inputs: CXX, VIEWS (build/engine/layers), PUBLIC
# (engine/include), GENERATED (build/engine/include), GLM, SHARED (shaders/shared), WORK.
file(MAKE_DIRECTORY "${WORK}")
# module, header, whether it may include it
set(cases
  scansurf_contours core/parallel.h yes
  scansurf_contours geometry/overlaps/overlap_analysis.h no
  scansurf_contours gpu/context.h no
  scansurf_contours passes/classification.h no
  scansurf_grid geometry/contours/polygon.h yes
  scansurf_grid geometry/overlaps/overlap_analysis.h no
  scansurf_contours geometry/grid/footprint.h no
  scansurf_overlaps geometry/contours/polygon.h yes
  scansurf_overlaps geometry/extraction/assembly.h no
  scansurf_extraction geometry/overlaps/overlap_split.h yes
  scansurf_extraction geometry/smoothing/contour_fit.h no
  scansurf_smoothing geometry/extraction/assembly.h yes
  scansurf_smoothing geometry/mesh/incident_triangles.h yes
  scansurf_smoothing geometry/shape/cube_fans.h no
  scansurf_shape geometry/smoothing/carrier_projection.h yes
  scansurf_shape geometry/simplification/simplify_mesh.h no
  scansurf_mesh geometry/contours/polygon.h no
  scansurf_mesh geometry/smoothing/smooth_mesh.h no
  scansurf_remesh geometry/mesh/vec3.h yes
  scansurf_remesh geometry/simplification/simplify_mesh.h no
  scansurf_simplification geometry/remesh/remesh_mesh.h yes
  scansurf_simplification geometry/shape/triangle_shape.h no
  scansurf_interpolation geometry/contours/polygon.h no
  scansurf_io geometry/contours/polygon.h yes
  scansurf_io geometry/shape/triangle_shape.h yes
  scansurf_io gpu/resources.h no
  scansurf_io passes/preview_renderer.h no
  scansurf_gpu geometry/contours/polygon.h no
  scansurf_passes geometry/contours/polygon.h yes
  scansurf_passes io/atomic_file.h no
  scansurf_core geometry/contours/polygon.h no)
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

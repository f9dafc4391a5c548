# End-to-end checks of the scansurf command line: the bundled example, exit codes and
# messages on bad input, and that a failed run leaves no partial output behind.
# Run by ctest with -DSCANSURF=<exe> -DEXAMPLES=<dir> -DDATA=<dir> -DOUT=<dir>.

function(run_scansurf expected_code)
  execute_process(COMMAND ${SCANSURF} ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(last_output "${out}${err}" PARENT_SCOPE)
  if(NOT code EQUAL expected_code)
    message(FATAL_ERROR "scansurf ${ARGN}: exit ${code}, expected ${expected_code}\n${out}${err}")
  endif()
endfunction()

function(expect_output pattern)
  if(NOT last_output MATCHES "${pattern}")
    message(FATAL_ERROR "output does not match '${pattern}':\n${last_output}")
  endif()
endfunction()

file(REMOVE_RECURSE "${OUT}")

# The bundled example: one PLY per feature plus the multi-label mesh, a summary, timings.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/phantom" --voxel-size 1)
expect_output("device: ")
expect_output("nesting order \\(computed, innermost first\\): target prostate")
expect_output("BODY +1 +[0-9]+ +[0-9.]+ +1 +0 yes")
expect_output("time: read")
foreach(name BODY prostate rectum target vessel vertebra multilabel)
  if(NOT EXISTS "${OUT}/phantom/${name}.ply")
    message(FATAL_ERROR "missing ${OUT}/phantom/${name}.ply")
  endif()
endforeach()
file(GLOB leftovers "${OUT}/phantom/.scansurf-staging*" "${OUT}/phantom/*.tmp-*")
if(leftovers)
  message(FATAL_ERROR "temporary files left behind: ${leftovers}")
endif()

# The partition convention.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/partition" --grid 128 96 --convention partition -q)

# Bad input: exit 3, naming the file, feature, slice and contour; nothing written, and an
# existing output left as it was.
file(MAKE_DIRECTORY "${OUT}/bad")
file(WRITE "${OUT}/bad/skin.ply" "previous result")
run_scansurf(3 "${DATA}/too_few_points.json" -o "${OUT}/bad")
expect_output("too_few_points.json: feature \"skin\" \\(#0\\), slice z=2.5 \\(#1\\), contour 1: fewer than 3 distinct points")
file(READ "${OUT}/bad/skin.ply" kept)
if(NOT kept STREQUAL "previous result")
  message(FATAL_ERROR "a failed run replaced an existing output")
endif()
run_scansurf(3 "${DATA}/truncated.json" -o "${OUT}/bad")
expect_output("truncated.json")

# A contour too small to cover a pixel centre is reported by name, not dropped in silence.
run_scansurf(0 "${DATA}/tiny_contour.json" -o "${OUT}/tiny" --voxel-size 1)
expect_output("warning: .*tiny_contour.json: feature \"organ\".*slice z=0.*contour 1")

# Usage errors: exit 2.
run_scansurf(2 "${EXAMPLES}/phantom.json")
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --convention sideways)
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --voxel-size 1 --grid 10 10)

# An output path that cannot be a directory: exit 4 before any work.
run_scansurf(4 "${EXAMPLES}/phantom.json" -o "${EXAMPLES}/phantom.json/out")
expect_output("phantom.json/out")

# No Vulkan driver at all: exit 5 with a clear message.
set(ENV{VK_ICD_FILENAMES} "${OUT}/no-such-icd.json")
set(ENV{VK_DRIVER_FILES} "${OUT}/no-such-icd.json")
run_scansurf(5 "${EXAMPLES}/phantom.json" -o "${OUT}/nodevice")
expect_output("no Vulkan (driver|device) found")
unset(ENV{VK_ICD_FILENAMES})
unset(ENV{VK_DRIVER_FILES})

# A device selector that matches nothing: exit 5, listing the devices seen.
run_scansurf(5 "${EXAMPLES}/phantom.json" -o "${OUT}/nodevice" --device no-such-gpu)
expect_output("no usable Vulkan device matches \"no-such-gpu\"")

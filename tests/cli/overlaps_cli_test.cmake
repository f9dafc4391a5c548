# Incidental and real overlaps through the command line: --list-overlaps, --overlap-tolerance,
# the summary's line per pair and the report's records, on the independently drawn prostate
# and rectum with a PTV over both (written here by scansurf_make_examples).
# Run by ctest with -DSCANSURF=<exe> -DMAKE_EXAMPLES=<exe> -DOUT=<dir>.

include("${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake")

file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND ${MAKE_EXAMPLES} "${OUT}" drawn-pelvis-ptv RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "scansurf_make_examples failed (${code})")
endif()
set(input "${OUT}/drawn-pelvis-ptv.json")

# The verdicts, without surfacing: the drawn neighbours incidental, the PTV real.
run_scansurf(0 "${input}" --list-overlaps --voxel-size 1)
expect_output("at most 2 % of the smaller feature and each connected region of it lies within 2 mm of the nearer outline or is at most 1 %")
expect_output("prostate +rectum +[0-9.]+ +[0-9.]+ % of [a-z]+ +[0-9.]+ +[0-9]+ +incidental: one layer, shared voxels split")
expect_output("rectum +PTV +[0-9.]+ +[0-9.]+ % of rectum +- +[0-9]+ +real: separate layers \\(too large\\)")
expect_output("BODY +prostate .* nested: one holds the other")
expect_output("surface layers: 2")
if(EXISTS "${OUT}/prostate.ply")
  message(FATAL_ERROR "--list-overlaps wrote surfaces")
endif()

# The rule off: every shared voxel means layers.
run_scansurf(0 "${input}" --list-overlaps --voxel-size 1 --overlap-tolerance off)
expect_output("overlap tolerance off")
expect_output("prostate +rectum .* real: separate layers \\(tolerance off\\)")
expect_output("surface layers: 3")

# A depth and percentage of one's own; bad ones are usage errors.
run_scansurf(0 "${input}" --list-overlaps --voxel-size 1 --overlap-tolerance 0.5,1)
expect_output("at most 1 % of the smaller feature and each connected region of it lies within 0.5 mm of the nearer outline or is at most 0.5 %")
expect_output("prostate +rectum .* real: separate layers \\(too (large|deep)\\)")
foreach(bad "-1" "1,101" "x" "auto," "1,2,3")
  run_scansurf(2 "${input}" --list-overlaps --overlap-tolerance "${bad}")
endforeach()

# Surfacing: one line per pair in the summary, the records in the report.
run_scansurf(0 "${input}" -o "${OUT}/run" --voxel-size 1 --report "${OUT}/run/report.json")
expect_output("overlap: prostate and rectum share [0-9.]+ mm3 \\([0-9.]+ % of [a-z]+, at most [0-9.]+ mm deep\\): incidental, "
              "split between them \\(prostate gave up [0-9.]+ mm3, rectum [0-9.]+ mm3\\)")
expect_output("overlap: rectum and PTV share [0-9.]+ mm3 \\([0-9.]+ % of rectum\\): surfaced in separate layers")
file(READ "${OUT}/run/report.json" report)
string(JSON verdict GET "${report}" overlaps partial 0 verdict)
string(JSON a GET "${report}" overlaps partial 0 a)
string(JSON given GET "${report}" overlaps partial 0 given_up a)
string(JSON depth GET "${report}" overlaps tolerance depth)
if(NOT verdict STREQUAL "incidental" OR NOT a STREQUAL "prostate" OR NOT given GREATER 0 OR NOT depth EQUAL 2)
  message(FATAL_ERROR "report: first partial overlap ${a} ${verdict}, given up ${given}, depth limit ${depth}")
endif()

# The report records every parameter as the run used it: the grid's pixel size and counts
# (integers as integers), the threads, the layers per gap.
string(JSON voxel GET "${report}" parameters voxel_size)
string(JSON threads GET "${report}" parameters threads)
if(NOT voxel EQUAL 1 OR NOT threads GREATER 0 OR NOT report MATCHES "\"grid_nx\": *[0-9]+," OR
   NOT report MATCHES "\"draco_level\": *7,")
  message(FATAL_ERROR "report parameters: voxel_size ${voxel}, threads ${threads}")
endif()

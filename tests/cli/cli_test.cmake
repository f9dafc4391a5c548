# End-to-end checks of the scansurf command line: the bundled example, exit codes and
# messages on bad input, and that a failed run leaves no partial output behind.
# Run by ctest with -DSCANSURF=<exe> -DEXAMPLES=<dir> -DDATA=<dir> -DOUT=<dir>.

include("${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake")

file(REMOVE_RECURSE "${OUT}")

# The bundled example: one PLY per feature plus the multi-label mesh, a summary, timings.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/phantom" --voxel-size 1)
expect_output("device: ")
expect_output("nesting order \\(computed, innermost first\\): target prostate")
expect_output("BODY +1 +0 +[0-9]+ +[0-9.]+ +[0-9.]+ +1 +0 yes")
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

# The run's audit: every surface of the bundled example matches its contours (no finding), and
# the summary's statistics are the audit's.
if(last_output MATCHES "surface components where|genus [0-9]+ where|slab volume is|is open|not manifold")
  message(FATAL_ERROR "the audit found fault with the bundled example:\n${last_output}")
endif()

# Warnings of one kind: three on the terminal and a count of the rest, every one in the report.
set(specks "")
foreach(k RANGE 0 5)
  string(APPEND specks "{\"z\": ${k}, \"contours\": [[[0,0],[20,0],[20,20],[0,20]], [[40.01,40.01],[40.02,40.01],[40.02,40.02]]]},")
endforeach()
string(REGEX REPLACE ",$" "" specks "${specks}")
file(WRITE "${OUT}/specks.json" "{\"version\": 1, \"units\": \"mm\", \"features\": [{\"name\": \"a\", \"slices\": [${specks}]}]}")
run_scansurf(0 "${OUT}/specks.json" -o "${OUT}/specks" --report "${OUT}/specks/report.json" -q)
string(REGEX MATCHALL "covers no pixel centre" shown "${last_output}")
list(LENGTH shown shown_count)
if(NOT shown_count EQUAL 3)
  message(FATAL_ERROR "expected 3 of the 6 'covers no pixel centre' warnings on the terminal, got ${shown_count}:\n${last_output}")
endif()
expect_output("3 more warnings like this one \\(6 in all; every one is in the report\\)")
file(READ "${OUT}/specks/report.json" specks_report)
string(JSON specks_warnings LENGTH "${specks_report}" warnings)
if(specks_warnings LESS 6)
  message(FATAL_ERROR "the report holds ${specks_warnings} warnings, not every one of the 6")
endif()

# Usage errors a person can act on: an option misspelt names the one meant; a missing input is
# an I/O error (exit 4) naming the file.
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --voxel-sise 1)
expect_output("unknown option --voxel-sise; did you mean --voxel-size")
run_scansurf(4 "${OUT}/no-such-input.json" -o "${OUT}/x")
expect_output("cannot read '.*no-such-input.json': no such file")
expect_nothing_left("${OUT}/x")

# The partition convention.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/partition" --grid 128 96 --convention partition -q)

# Smoothing options: --no-smooth really writes other (raw) surfaces; every option is accepted;
# an out-of-range strength is a usage error.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/smoothed" --grid 96 64 -q)
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/raw" --grid 96 64 --no-smooth -q)
file(SHA256 "${OUT}/smoothed/BODY.ply" smoothed_hash)
file(SHA256 "${OUT}/raw/BODY.ply" raw_hash)
if(smoothed_hash STREQUAL raw_hash)
  message(FATAL_ERROR "--no-smooth wrote the same surface as the default smoothing")
endif()
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/options" --grid 96 64 -q --smooth-iterations 5
             --smooth-strength 0.5 --no-contour-fit --no-junction-smoothing)
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --smooth-strength 1.5)
# --snap (vertices crowding a voxel centre merge into it; issue 28): off writes other surfaces with
# more triangles, the report gives the fraction, and a fraction past 0.45 is refused.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/unsnapped" --grid 96 64 -q --snap 0
             --report "${OUT}/unsnapped/report.json")
file(READ "${OUT}/unsnapped/report.json" unsnapped_report)
string(JSON unsnapped_fraction GET "${unsnapped_report}" parameters snap)
string(JSON unsnapped_triangles GET "${unsnapped_report}" multilabel_mesh triangles)
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/snapped" --grid 96 64 -q --report "${OUT}/snapped/report.json")
file(READ "${OUT}/snapped/report.json" snapped_report)
string(JSON snapped_fraction GET "${snapped_report}" parameters snap)
string(JSON snapped_triangles GET "${snapped_report}" multilabel_mesh triangles)
string(JSON snapped_points GET "${snapped_report}" triangle_shape points)
string(JSON unsnapped_points GET "${unsnapped_report}" triangle_shape points)
if(NOT snapped_points GREATER 0 OR NOT unsnapped_points EQUAL 0)
  message(FATAL_ERROR "--snap: the report's snapped points ${snapped_points} (default) / ${unsnapped_points} (--snap 0)")
endif()
# The cubes' fans are re-triangulated with or without snapping.
string(JSON snapped_fans GET "${snapped_report}" triangle_shape cube_fans)
string(JSON unsnapped_fans GET "${unsnapped_report}" triangle_shape cube_fans)
if(NOT snapped_fans GREATER 0 OR NOT unsnapped_fans GREATER 0)
  message(FATAL_ERROR "the report's cube fans: ${snapped_fans} (default) / ${unsnapped_fans} (--snap 0)")
endif()
if(NOT unsnapped_fraction MATCHES "^0(\\.0*)?$" OR NOT snapped_fraction MATCHES "^0\\.050*" OR NOT snapped_triangles LESS unsnapped_triangles)
  message(FATAL_ERROR "--snap: fractions ${unsnapped_fraction} / ${snapped_fraction}, triangles ${unsnapped_triangles} / ${snapped_triangles}")
endif()
# --volume-unit: the summary's table and the report give volumes in cm³ (a thousandth of the mm³),
# the report saying so; a unit scansurf does not know is a usage error naming the option.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/cc" --grid 96 64 --volume-unit cc --report "${OUT}/cc/report.json")
expect_output("volume cm3 +contour cm3")
file(READ "${OUT}/cc/report.json" cc_report)
string(JSON cc_unit GET "${cc_report}" volume_unit)
string(JSON cc_body GET "${cc_report}" features 0 contour_volume)
string(JSON mm_body GET "${snapped_report}" features 0 contour_volume)
string(JSON mm_unit GET "${snapped_report}" volume_unit)
# CMake has no floating point: whole mm³ from both (cm³ with its first three decimals).
string(REGEX REPLACE "\\..*" "" mm_whole "${mm_body}")
string(REGEX REPLACE "^([0-9]+)\\.([0-9][0-9][0-9]).*" "\\1\\2" cc_whole "${cc_body}")
math(EXPR cc_off "${cc_whole} - ${mm_whole}")
if(NOT cc_unit STREQUAL "cm^3" OR NOT mm_unit STREQUAL "mm^3" OR cc_off GREATER 1 OR cc_off LESS -1)
  message(FATAL_ERROR "--volume-unit cc: BODY ${cc_body} ${cc_unit}, by default ${mm_body} ${mm_unit}")
endif()
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --volume-unit litres)
expect_output("--volume-unit")
foreach(bad 0.5 -0.1 nan)
  run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --snap ${bad})
endforeach()
# Simplification is on by default (issue 28): the default run reports it with edge length 2.5 and
# has fewer triangles than --no-simplify, which reports it off and has no simplification figures.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/unsimplified" --grid 96 64 -q --no-simplify
             --report "${OUT}/unsimplified/report.json")
file(READ "${OUT}/unsimplified/report.json" unsimplified_report)
string(JSON unsimplified_on GET "${unsimplified_report}" parameters simplification)
string(JSON unsimplified_triangles GET "${unsimplified_report}" multilabel_mesh triangles)
string(JSON unsimplified_figures ERROR_VARIABLE no_figures GET "${unsimplified_report}" simplification)
string(JSON simplified_on GET "${snapped_report}" parameters simplification)
string(JSON simplified_edge GET "${snapped_report}" parameters simplify_edge_length)
string(JSON simplified_after GET "${snapped_report}" simplification triangles_after)
if(unsimplified_on OR NOT no_figures OR NOT simplified_on OR NOT simplified_edge MATCHES "^2\\.50*$"
   OR NOT simplified_after EQUAL snapped_triangles OR NOT snapped_triangles LESS unsimplified_triangles)
  message(FATAL_ERROR "simplification by default: on ${simplified_on}, edge ${simplified_edge}, "
                      "${snapped_triangles} triangles against ${unsimplified_triangles} with --no-simplify (on ${unsimplified_on})")
endif()
# --no-keep-volume leaves the volumes as relaxation made them (other surfaces), and the report
# says so.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/relaxed" --grid 96 64 -q --no-keep-volume
             --report "${OUT}/relaxed/report.json")
file(SHA256 "${OUT}/relaxed/BODY.ply" relaxed_hash)
file(READ "${OUT}/relaxed/report.json" relaxed_report)
string(JSON relaxed_keep GET "${relaxed_report}" parameters keep_volume)
if(relaxed_hash STREQUAL smoothed_hash OR relaxed_keep)
  message(FATAL_ERROR "--no-keep-volume wrote the default surface, or its report says keep_volume ${relaxed_keep}")
endif()

# Remeshing (off by default): --remesh remeshes, --no-remesh keeps the smoothed mesh,
# --edge-length is accepted, and a length that is not a positive finite number is a usage
# error naming it.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/remeshed" --grid 96 64 --remesh -q)
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/unremeshed" --grid 96 64 --no-remesh -q)
file(SHA256 "${OUT}/remeshed/BODY.ply" remeshed_hash)
file(SHA256 "${OUT}/unremeshed/BODY.ply" unremeshed_hash)
if(remeshed_hash STREQUAL unremeshed_hash OR NOT smoothed_hash STREQUAL unremeshed_hash)
  message(FATAL_ERROR "--remesh wrote the same surface as --no-remesh, or the default remeshed")
endif()
# --no-curvature-sizing keeps one target length where the surface curves (the vertebra's tight
# bends get shorter edges by default), and the report says which ran.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/uniform" --grid 96 64 --remesh --no-curvature-sizing -q
             --report "${OUT}/uniform/report.json")
file(SHA256 "${OUT}/uniform/vertebra.ply" uniform_hash)
file(SHA256 "${OUT}/remeshed/vertebra.ply" sized_hash)
file(READ "${OUT}/uniform/report.json" uniform_report)
string(JSON uniform_sizing GET "${uniform_report}" parameters curvature_sizing)
if(uniform_hash STREQUAL sized_hash OR uniform_sizing)
  message(FATAL_ERROR "--no-curvature-sizing wrote the same vertebra as the default, or its report says curvature_sizing ${uniform_sizing}")
endif()
# The report says what it is about: the command line, when the run started, and its units.
string(JSON arg1 GET "${uniform_report}" command_line 1)
string(JSON started GET "${uniform_report}" started)
string(JSON length_unit GET "${uniform_report}" length_unit)
string(JSON volume_unit GET "${uniform_report}" volume_unit)
if(NOT arg1 STREQUAL "${EXAMPLES}/phantom.json" OR NOT started MATCHES "^20[0-9][0-9]-[01][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9]Z$"
   OR NOT length_unit STREQUAL "mm" OR NOT volume_unit STREQUAL "mm^3")
  message(FATAL_ERROR "report: command_line[1] '${arg1}', started '${started}', units '${length_unit}' / '${volume_unit}'")
endif()
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/coarse" --grid 96 64 --remesh --edge-length 6 --report "${OUT}/coarse/report.json")
expect_output("remeshing \\(edge length 6 mm\\): [0-9]+ -> [0-9]+ triangles")
expect_output("time:.* remeshing [0-9.]+ s;")
file(READ "${OUT}/coarse/report.json" coarse_report)
string(JSON coarse_length GET "${coarse_report}" remeshing edge_length)
string(JSON coarse_after GET "${coarse_report}" remeshing triangles_after)
string(JSON coarse_triangles GET "${coarse_report}" multilabel_mesh triangles)
string(JSON coarse_chunks GET "${coarse_report}" remeshing chunks)
string(JSON coarse_bands GET "${coarse_report}" remeshing bands)
if(NOT coarse_length EQUAL 6 OR NOT coarse_after EQUAL coarse_triangles OR NOT coarse_chunks EQUAL 1 OR NOT coarse_bands EQUAL 0)
  message(FATAL_ERROR "report.json remeshing: edge length ${coarse_length}, ${coarse_after} triangles, mesh ${coarse_triangles}, "
                      "${coarse_chunks} chunks, ${coarse_bands} bands (a small mesh is remeshed whole)")
endif()
foreach(bad 0 -1 nan inf abc)
  run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --edge-length ${bad})
  expect_output("--edge-length: '${bad}' is not a positive, finite number")
endforeach()

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

# The version, and numbers that once aborted the program: never a crash, always exit 2 or 5
# with a message.
run_scansurf(0 --version)
expect_output("^scansurf [0-9]+\\.[0-9]+\\.[0-9]+")
run_scansurf(5 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --device 99999999999999999999)
expect_output("no usable Vulkan device matches \"99999999999999999999\"")
# Interpolation (issue 10): auto on the phantom (0.49 mm pixels, 2.5 mm slices) adds layers and
# says so in the report; off and N are honoured; anything else is a usage error.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/interp" --interpolate 2 --caps flat --report "${OUT}/interp/r.json")
file(READ "${OUT}/interp/r.json" interp_report)
string(JSON interp_used GET "${interp_report}" interpolation used)
string(JSON interp_layers GET "${interp_report}" interpolation surfaced_layers)
string(JSON interp_caps GET "${interp_report}" interpolation caps)
string(JSON interp_parameter GET "${interp_report}" parameters interpolation)
if(NOT interp_used OR NOT interp_layers EQUAL 83 OR NOT interp_caps STREQUAL "flat" OR NOT interp_parameter STREQUAL "2")
  message(FATAL_ERROR "interpolation report: used ${interp_used}, ${interp_layers} layers, caps ${interp_caps}, parameter ${interp_parameter}")
endif()
foreach(bad 0 17 foo -1)
  run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --interpolate ${bad})
endforeach()
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --caps dome)
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --smooth-strength 0)
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --smooth-strength nan)
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --grid 0 0)
# -o NAME.stl: one file with every feature's closed surface (its facet count is the features'
# triangles together); -o NAME.ply: the multi-label mesh; --format with a file is a usage error.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/one/all.stl" --grid 96 64 -q --report "${OUT}/one/all.json")
file(READ "${OUT}/one/all.stl" stl_count OFFSET 80 LIMIT 4 HEX)
string(REGEX REPLACE "^(..)(..)(..)(..)$" "\\4\\3\\2\\1" stl_count "${stl_count}")
math(EXPR stl_count "0x${stl_count}")
file(READ "${OUT}/one/all.json" one_report)
string(JSON one_features LENGTH "${one_report}" features)
math(EXPR one_last "${one_features} - 1")
set(one_triangles 0)
foreach(f RANGE ${one_last})
  string(JSON t GET "${one_report}" features ${f} triangles)
  math(EXPR one_triangles "${one_triangles} + ${t}")
endforeach()
string(JSON one_outputs GET "${one_report}" outputs)
if(NOT stl_count EQUAL one_triangles OR NOT one_outputs MATCHES "all.stl")
  message(FATAL_ERROR "-o all.stl: ${stl_count} facets for ${one_triangles} feature triangles; outputs ${one_outputs}")
endif()
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/one/all.ply" --grid 96 64 -q)
string(JSON one_mesh GET "${one_report}" multilabel_mesh triangles)
file(STRINGS "${OUT}/one/all.ply" ply_faces REGEX "^element face" LIMIT_COUNT 1)
if(NOT ply_faces STREQUAL "element face ${one_mesh}")
  message(FATAL_ERROR "-o all.ply: '${ply_faces}', the multi-label mesh has ${one_mesh} triangles")
endif()
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x.stl" --format ply)
expect_output("--format needs an output directory")
expect_nothing_left("${OUT}/x.stl")
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --grid 3 3)
expect_output("--grid")
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --grid 1048576 3)
expect_output("--grid")
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --threads 99999999999999999999)
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --preview "${OUT}/x/p.png" --preview-size 2147483648 2147483648)
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --preview "${OUT}/x/p.png" --preview-size 16384 16384)

# The memory budget (issue 15, cause 2): a grid that cannot fit is refused before anything is
# allocated, with exit 9 and a message that says what it needs and what to change; so is a run
# over --max-memory. Nothing is written.
run_scansurf(9 "${EXAMPLES}/phantom.json" -o "${OUT}/budget" --grid 16384 16384)
expect_output("error: the surfaces of .*phantom.json on a grid of 16384 x 16384 x 42 voxels need about [0-9.]+ GiB of memory \\(label volume 21.0 GiB")
expect_output("choose a coarser --voxel-size or --grid, or set --max-memory")
run_scansurf(9 "${EXAMPLES}/phantom.json" -o "${OUT}/budget" --voxel-size 0.0078)
run_scansurf(9 "${EXAMPLES}/phantom.json" -o "${OUT}/budget" --max-memory 20M)
expect_output("need about [0-9.]+ MiB of memory .* 20.0 MiB may be used: the limit asked for")
expect_nothing_left("${OUT}/budget")
# A preview is in the budget from the start: refused before the work, not after it.
run_scansurf(9 "${EXAMPLES}/phantom.json" -o "${OUT}/budget" --max-memory 1G --preview "${OUT}/budget.png"
  --preview-size 8192 8192)
expect_output("and [0-9.]+ GiB beside them \\(a preview\\)\\); 1.00 GiB may be used")
expect_nothing_left("${OUT}/budget")
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/budget" --max-memory 8X)
expect_output("'8X' is not a memory size")
run_scansurf(0 "${DATA}/overlapping.json" -o "${OUT}/budget" --voxel-size 0.5 --max-memory 2G --report "${OUT}/budget/r.json")
file(READ "${OUT}/budget/r.json" budget_report)
string(JSON budget_limit GET "${budget_report}" memory limit_bytes)
if(NOT budget_limit EQUAL 2147483648)
  message(FATAL_ERROR "report memory.limit_bytes is ${budget_limit}, expected 2147483648")
endif()

# Overlapping structures: two layers by default, each keeping its volume; the partition
# reports the loss (with a warning above 1 %); an unknown mode is a usage error.
run_scansurf(0 "${DATA}/overlapping.json" -o "${OUT}/overlap" --voxel-size 0.5 --report "${OUT}/overlap/r.json")
expect_output("overlaps as layers: 2 layers")
expect_output("overlap: organ and PTV share [0-9.]+ mm3 \\([0-9.]+ % of [A-Za-z]+\\): surfaced in separate layers")
file(READ "${OUT}/overlap/r.json" overlap_report)
string(JSON ptv_layer GET "${overlap_report}" features 1 layer)
string(JSON ptv_contour GET "${overlap_report}" features 1 contour_volume)
string(JSON ptv_surface GET "${overlap_report}" features 1 surface_volume)
string(JSON ptv_overlap GET "${overlap_report}" features 1 overlaps 0 with)
if(NOT ptv_layer EQUAL 1 OR NOT ptv_overlap STREQUAL "organ" OR NOT ptv_surface GREATER 0 OR NOT ptv_contour GREATER 0)
  message(FATAL_ERROR "overlap report: layer ${ptv_layer}, overlaps ${ptv_overlap}")
endif()
run_scansurf(0 "${DATA}/overlapping.json" -o "${OUT}/overlap_partition" --voxel-size 0.5 --overlaps partition)
expect_output("partition: PTV lost [0-9.]+ mm3 \\([0-9.]+ % of its contour volume\\) to organ")
expect_output("warning: feature \"PTV\" lost [0-9]+ % of its contour volume to \"organ\"")
run_scansurf(2 "${DATA}/overlapping.json" -o "${OUT}/x" --overlaps sideways)

# Control characters in a name (ESC, newline) are printed escaped: no forged lines, no
# terminal control sequences.
run_scansurf(0 "${DATA}/control_chars.json" -o "${OUT}/control" --voxel-size 0.5 --overlaps partition)
string(ASCII 27 esc)
string(FIND "${last_output}" "${esc}" raw_escape)
if(NOT raw_escape EQUAL -1 OR last_output MATCHES "\nscansurf: error: forged")
  message(FATAL_ERROR "a control character in a name reached the terminal:\n${last_output}")
endif()
expect_output("organ\\\\x1B\\[2J\\\\x0Ascansurf: error: forged")

# File names (issue 15, cause 7): names equal but for case get distinct files on any file
# system, a 251-character name a shortened one, each with a warning; the report keeps the name.
run_scansurf(0 "${DATA}/file_names.json" -o "${OUT}/names" --voxel-size 0.5 --report "${OUT}/names/r.json")
expect_output("feature \"BODY\": another feature's file name differs only in case .* its files are BODY_2")
expect_output("feature \"LLLL[L]*...\": its name is too long for a file name; its files are L+_[0-9a-f]+\\.\\*")
expect_files("${OUT}/names" Body.ply BODY_2.ply)
# A feature named as the input names the scene files (ball.glb): its own files are ball_2.*,
# and the warning says why.
file(WRITE "${OUT}/ball.json" "{\"version\": 1, \"units\": \"mm\", \"features\": [{\"name\": \"ball\", \"slices\": [
  {\"z\": 0, \"contours\": [[[0, 0], [4, 0], [4, 4], [0, 4]]]}, {\"z\": 2, \"contours\": [[[0, 0], [4, 0], [4, 4], [0, 4]]]}]}]}")
run_scansurf(0 "${OUT}/ball.json" -o "${OUT}/ball" --voxel-size 1 --format ply,glb)
expect_output("feature \"ball\": its name is that of the scene files, named after the input \\(ball.glb, .seg.vtm\\); its files are ball_2")
expect_files("${OUT}/ball" ball_2.ply ball.glb)
# A feature smaller than a pixel: its row says 0 triangles, and one line says why and what to do.
file(WRITE "${OUT}/speck.json" "{\"version\": 1, \"units\": \"mm\", \"features\": [{\"name\": \"ball\", \"slices\": [
  {\"z\": 0, \"contours\": [[[0, 0], [40, 0], [40, 40], [0, 40]]]}, {\"z\": 2, \"contours\": [[[0, 0], [40, 0], [40, 40], [0, 40]]]}]},
  {\"name\": \"dot\", \"slices\": [{\"z\": 0, \"contours\": [[[10.01, 10.01], [10.02, 10.01], [10.02, 10.02]]]}]}]}")
run_scansurf(0 "${OUT}/speck.json" -o "${OUT}/speck" --voxel-size 2)
expect_output("1 of 2 features have no surface: they cover no voxel centre of this grid \\(2 mm pixels\\); a finer --voxel-size gives them one")
# A feature named as a block of the Slicer segmentation (ball.seg_0.vtp) gets other files, told
# before anything is written rather than refused after the build.
file(WRITE "${OUT}/blocks.json" "{\"version\": 1, \"units\": \"mm\", \"features\": [{\"name\": \"blocks.seg_0\", \"slices\": [
  {\"z\": 0, \"contours\": [[[0, 0], [4, 0], [4, 4], [0, 4]]]}, {\"z\": 2, \"contours\": [[[0, 0], [4, 0], [4, 4], [0, 4]]]}]}]}")
run_scansurf(0 "${OUT}/blocks.json" -o "${OUT}/blocks" --voxel-size 1 --format vtp,seg.vtm)
expect_output("feature \"blocks.seg_0\": its name is that of a block of the Slicer segmentation \\(blocks.seg_N.vtp\\); its files are blocks.seg_0_2")
expect_files("${OUT}/blocks" blocks.seg_0_2.vtp blocks.seg_0.vtp blocks.seg.vtm)
file(GLOB long_names "${OUT}/names/LLLL*.ply")
list(LENGTH long_names long_count)
file(READ "${OUT}/names/r.json" names_report)
string(JSON long_name GET "${names_report}" features 2 name)
string(LENGTH "${long_name}" long_length)
if(NOT long_count EQUAL 1 OR NOT long_length EQUAL 251)
  message(FATAL_ERROR "long name: ${long_count} files, report name of ${long_length} characters")
endif()

# The run lock: a second run into a directory another run is writing to fails at once, before
# any work, and leaves that directory alone; a finished run leaves no lock file.
if(NOT EXISTS "${OUT}/names/.scansurf.lock")
  execute_process(COMMAND flock "${OUT}/names/.scansurf.lock" ${SCANSURF} "${EXAMPLES}/phantom.json" -o "${OUT}/names"
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 4 OR NOT "${out}${err}" MATCHES "another scansurf run is writing into '.*names'")
    message(FATAL_ERROR "a locked output directory: exit ${code}\n${out}${err}")
  endif()
else()
  message(FATAL_ERROR "a finished run left its lock file in ${OUT}/names")
endif()

# A link planted where the lock goes is never followed: the file it points to keeps its
# content, a dangling link creates nothing, and the run says why it stopped.
file(MAKE_DIRECTORY "${OUT}/linked")
file(WRITE "${OUT}/victim.txt" "keep me\n")
file(CREATE_LINK "${OUT}/victim.txt" "${OUT}/linked/.scansurf.lock" SYMBOLIC)
run_scansurf(4 "${EXAMPLES}/phantom.json" -o "${OUT}/linked" --grid 64 48 -q)
expect_output("the run lock '.*linked/.scansurf.lock' is a symbolic link; scansurf never follows one there")
file(READ "${OUT}/victim.txt" victim)
if(NOT victim STREQUAL "keep me\n" OR NOT IS_SYMLINK "${OUT}/linked/.scansurf.lock")
  message(FATAL_ERROR "the run followed the lock link: victim now '${victim}'")
endif()
file(REMOVE "${OUT}/linked/.scansurf.lock")
file(CREATE_LINK "${OUT}/nowhere.txt" "${OUT}/linked/.scansurf.lock" SYMBOLIC)
run_scansurf(4 "${EXAMPLES}/phantom.json" -o "${OUT}/linked" --grid 64 48 -q)
if(EXISTS "${OUT}/nowhere.txt")
  message(FATAL_ERROR "a dangling lock link made a file outside the output folder")
endif()

# A reader that closes the output early (scansurf ... | head -c0) ends nothing badly: exit 0,
# the files written, no staging folder or lock left.
execute_process(COMMAND ${SCANSURF} "${EXAMPLES}/phantom.json" -o "${OUT}/piped" --grid 64 48 COMMAND head -c0
                RESULTS_VARIABLE codes)
list(GET codes 0 code)
file(GLOB piped_left "${OUT}/piped/.scansurf*")
if(NOT code EQUAL 0 OR piped_left OR NOT EXISTS "${OUT}/piped/BODY.ply")
  message(FATAL_ERROR "output piped into head -c0: exit ${code}, left behind: ${piped_left}")
endif()

# Inputs are regular files: a link to /dev/zero is not read for ever, a FIFO with no writer
# does not hang the run.
file(CREATE_LINK /dev/zero "${OUT}/zero.json" SYMBOLIC)
run_scansurf(3 "${OUT}/zero.json" -o "${OUT}/zero")
expect_output("zero.json: not a regular file")
find_program(MKFIFO mkfifo)
if(MKFIFO)
  execute_process(COMMAND ${MKFIFO} "${OUT}/fifo.json")
  run_scansurf(3 "${OUT}/fifo.json" -o "${OUT}/fifo")
  expect_output("fifo.json: not a regular file")
endif()

# All or nothing: a file that cannot be replaced (immutable, where chattr can make it so)
# leaves every other old file in place and the run fails.
find_program(CHATTR chattr)
if(CHATTR)
  run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/immutable" --grid 64 48 -q)
  file(SHA256 "${OUT}/immutable/BODY.ply" body_before)
  execute_process(COMMAND ${CHATTR} +i "${OUT}/immutable/rectum.ply" RESULT_VARIABLE locked ERROR_QUIET)
  if(locked EQUAL 0)
    run_scansurf(4 "${EXAMPLES}/phantom.json" -o "${OUT}/immutable" --grid 72 52 -q)
    execute_process(COMMAND ${CHATTR} -i "${OUT}/immutable/rectum.ply")
    expect_output("cannot replace '.*rectum.ply': .*; nothing was replaced")
    file(SHA256 "${OUT}/immutable/BODY.ply" body_after)
    file(GLOB immutable_left "${OUT}/immutable/.scansurf*")
    if(NOT body_before STREQUAL body_after OR immutable_left)
      message(FATAL_ERROR "a failed commit replaced BODY.ply or left ${immutable_left}")
    endif()
  endif()
endif()

# A file name as long as a file name may be (250 characters and .glb): staging adds nothing
# to it.
string(REPEAT "n" 250 long_stem)
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/${long_stem}.glb" --grid 64 48 -q)
if(NOT EXISTS "${OUT}/${long_stem}.glb")
  message(FATAL_ERROR "the 254-character file name was not written")
endif()

# No output replaces the input it is made from.
file(COPY_FILE "${EXAMPLES}/phantom.json" "${OUT}/input.json")
run_scansurf(2 "${OUT}/input.json" -o "${OUT}/self" --grid 64 48 --report "${OUT}/input.json")
expect_output("--report '.*input.json' is the input file")
file(SHA256 "${OUT}/input.json" input_hash)
file(SHA256 "${EXAMPLES}/phantom.json" example_hash)
if(NOT input_hash STREQUAL example_hash)
  message(FATAL_ERROR "a run overwrote its input")
endif()

# SIGTERM at any stage (here after 3 s of a ~10 s run, whichever stage that is) leaves
# nothing behind: no staging folder, no partial file, the old output untouched.
find_program(TIMEOUT timeout)
if(TIMEOUT)
  file(MAKE_DIRECTORY "${OUT}/term")
  file(WRITE "${OUT}/term/BODY.ply" "previous result")
  execute_process(COMMAND ${TIMEOUT} -s TERM 3 ${SCANSURF} "${EXAMPLES}/phantom.json" -o "${OUT}/term" --voxel-size 0.25
                          --format ply,obj -q RESULT_VARIABLE term_code OUTPUT_QUIET ERROR_QUIET)
  file(GLOB term_left RELATIVE "${OUT}/term" "${OUT}/term/*" "${OUT}/term/.*")
  file(READ "${OUT}/term/BODY.ply" term_kept)
  if(term_code EQUAL 124 AND (NOT term_left STREQUAL "BODY.ply" OR NOT term_kept STREQUAL "previous result"))
    message(FATAL_ERROR "SIGTERM left ${term_left} (BODY.ply: ${term_kept})")
  endif()
endif()

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

# Outputs people open directly (issue 4): a GLB scene at -o NAME.glb, a preview picture, the
# label volume with its table, and the JSON report, all in one run; progress as JSON lines.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/open/phantom.glb" --voxel-size 2
             --preview "${OUT}/open/preview.png" --preview-size 320 240 --view front
             --label-volume "${OUT}/open/labels.nrrd" --report "${OUT}/open/report.json" --json-progress)
expect_output("\\{\"event\":\"done\",\"stage\":\"classification\",\"within\":\"surfaces\",\"elapsed\":[0-9.]+,\"seconds\":[0-9.]+")
expect_output("\\{\"event\":\"finish\",\"exit_code\":0")
foreach(name phantom.glb preview.png labels.nrrd labels.ctbl report.json)
  if(NOT EXISTS "${OUT}/open/${name}")
    message(FATAL_ERROR "missing ${OUT}/open/${name}")
  endif()
endforeach()
file(READ "${OUT}/open/phantom.glb" magic LIMIT 4 HEX)
file(READ "${OUT}/open/preview.png" png_magic LIMIT 4 HEX)
file(READ "${OUT}/open/labels.nrrd" nrrd_magic LIMIT 4 HEX)
if(NOT magic STREQUAL "676c5446" OR NOT png_magic STREQUAL "89504e47" OR NOT nrrd_magic STREQUAL "4e525244")
  message(FATAL_ERROR "wrong file signatures: '${magic}' '${png_magic}' '${nrrd_magic}'")
endif()
file(READ "${OUT}/open/report.json" report)
string(JSON body_name GET "${report}" features 0 name)
string(JSON body_genus GET "${report}" features 0 genus)
string(JSON body_closed GET "${report}" features 0 closed)
string(JSON stages LENGTH "${report}" timings)
string(JSON max_error GET "${report}" parameters draco_max_error)
if(NOT max_error GREATER 0 OR NOT max_error LESS 0.2)  # 2 mm voxels: 1/25 voxel = 0.08 mm
  message(FATAL_ERROR "unexpected draco_max_error ${max_error}")
endif()
string(JSON generator GET "${report}" generator)
if(NOT generator MATCHES "^scansurf [0-9]+\\.[0-9]+\\.[0-9]+$")
  message(FATAL_ERROR "report generator '${generator}'")
endif()
if(NOT body_name STREQUAL "BODY" OR NOT body_genus EQUAL 0 OR NOT body_closed OR stages LESS 5)
  message(FATAL_ERROR "unexpected report: ${body_name} genus ${body_genus} closed ${body_closed}, ${stages} stages")
endif()
file(GLOB leftovers "${OUT}/open/.scansurf-staging*" "${OUT}/open/*.tmp-*")
if(leftovers)
  message(FATAL_ERROR "temporary files left behind: ${leftovers}")
endif()

# Every per-feature format in a directory, plus the scene named after the input.
run_scansurf(0 "${EXAMPLES}/phantom.json" -o "${OUT}/formats" --voxel-size 2 --format drc,obj,stl,glb -q)
foreach(name BODY.drc BODY.obj BODY.stl target.drc target.obj target.stl phantom.glb)
  if(NOT EXISTS "${OUT}/formats/${name}")
    message(FATAL_ERROR "missing ${OUT}/formats/${name}")
  endif()
endforeach()
if(EXISTS "${OUT}/formats/BODY.ply")
  message(FATAL_ERROR "--format without ply wrote PLY files")
endif()

# Unknown formats: exit 2 before any work, naming what was asked.
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/unknown" --format fbx)
expect_output("unknown output format \"fbx\"")
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/unknown" --preview "${OUT}/unknown/p.jpg")
expect_output("preview '.*p.jpg': unknown format \\(expected a .png file\\)")
# An unwritable output location: exit 4 before any work, nothing written anywhere.
run_scansurf(4 "${EXAMPLES}/phantom.json" -o "${OUT}/unwritable" --report "${EXAMPLES}/phantom.json/report.json")
expect_output("phantom.json")
file(GLOB written "${OUT}/unwritable/*")
if(written)
  message(FATAL_ERROR "a run that failed its output check wrote ${written}")
endif()
# A feature too small for any pixel centre has no surface: its PLY is empty, the formats that
# cannot hold an empty mesh are skipped with a warning, the run still succeeds.
run_scansurf(0 "${DATA}/speck_feature.json" -o "${OUT}/speck" --voxel-size 1 --format ply,drc,obj,stl,glb)
expect_output("warning: feature \"speck\" has no surface: no .drc written for it")
foreach(name organ.drc organ.obj organ.stl organ.ply speck.ply speck_feature.glb)
  if(NOT EXISTS "${OUT}/speck/${name}")
    message(FATAL_ERROR "missing ${OUT}/speck/${name}")
  endif()
endforeach()
if(EXISTS "${OUT}/speck/speck.drc")
  message(FATAL_ERROR "an empty surface was written as .drc")
endif()

# Input is recognised by content: a file of no supported format is refused (exit 3) with a
# message naming it and listing the formats.
run_scansurf(3 "${DATA}/not_contours.txt" -o "${OUT}/notcontours")
expect_output("not_contours.txt: not a contour file scansurf reads \\(it starts with \"these are notes")
expect_output("contour-set JSON; DICOM RT Structure Set .*; Reconstruct series .*; IMOD binary model")
run_scansurf(3 "${DATA}/not_contours.txt" --list-objects)

# A Reconstruct series (tests/data/reconstruct: 3 sections, a translated Transform, an image
# domain, hidden and open traces): its objects listed, then surfaced from one section file.
run_scansurf(0 "${DATA}/reconstruct/tiny.ser" --list-objects --object soma)
expect_output("tiny.ser: Reconstruct series \"tiny\", 3 sections \\(index 1..3\\), 3 objects \\(x, y, z in .*m\\)")
expect_output("number  name +contours +skipped +sections +z range +selected")
expect_output("1  axon +2 +0 +2  0.1 .. 0.15 +no")
expect_output("2  note +0 +1 +0  - +no")
expect_output("3  soma +3 +0 +3  0.05 .. 0.15 +yes")
expect_output("warning: .*tiny.ser: object \"note\": skipped 1 open trace\\(s\\) \\(it has no closed trace\\)")
run_scansurf(0 "${DATA}/reconstruct/tiny.2" -o "${OUT}/tiny" --voxel-size 0.02)
expect_output("Reconstruct series \"tiny\": 3 sections \\(index 1..3\\), 3 objects, 2 surfaced")
foreach(name axon soma multilabel)
  if(NOT EXISTS "${OUT}/tiny/${name}.ply")
    message(FATAL_ERROR "missing ${OUT}/tiny/${name}.ply")
  endif()
endforeach()
run_scansurf(2 "${DATA}/reconstruct/tiny.ser" -o "${OUT}/x" --object nucleus)
expect_output("--object \"nucleus\" matches no object; the file holds \"axon\", \"note\", \"soma\"")
run_scansurf(2 "${DATA}/reconstruct/tiny.ser" --list-rois)
expect_output("--list-rois applies to DICOM RTSTRUCT and 3D Slicer segmentation input, not to Reconstruct series .*\\(use --list-objects\\)")
run_scansurf(2 "${EXAMPLES}/phantom.json" -o "${OUT}/x" --object BODY)
expect_output("object selection applies to Reconstruct and IMOD input, not to contour-set JSON")

# --json-progress is strict JSON lines on stderr: every line a JSON object, every stage begun
# and then done once (the engine's within "surfaces"), warnings and errors as records, and the
# run's last record "finish" with its exit code, after the warnings.
function(check_json_progress expected_code)
  execute_process(COMMAND ${SCANSURF} ${ARGN} --json-progress RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
  if(NOT code EQUAL expected_code)
    message(FATAL_ERROR "json progress run: exit ${code}, expected ${expected_code}\n${err}")
  endif()
  string(REGEX REPLACE "\n$" "" err "${err}")
  string(REPLACE ";" "," err "${err}")
  string(REPLACE "[" "(" err "${err}")  # CMake lists treat brackets specially; our records hold no arrays
  string(REPLACE "]" ")" err "${err}")
  string(REPLACE "\n" ";" lines "${err}")
  set(open "")
  set(last "")
  set(kinds "")
  foreach(line IN LISTS lines)
    string(JSON event ERROR_VARIABLE bad GET "${line}" event)
    if(bad)
      message(FATAL_ERROR "--json-progress printed a line that is not a JSON object: '${line}' (${bad})")
    endif()
    list(APPEND kinds "${event}")
    if(event STREQUAL "begin" OR event STREQUAL "done")
      string(JSON stage GET "${line}" stage)
      string(JSON layer ERROR_VARIABLE nolayer GET "${line}" layer)
      set(key "${stage}@${layer}")
      if(event STREQUAL "begin")
        list(APPEND open "${key}")
      else()
        list(FIND open "${key}" at)
        if(at LESS 0)
          message(FATAL_ERROR "stage '${key}' done without a begin:\n${err}")
        endif()
        list(REMOVE_AT open ${at})
      endif()
    endif()
    set(last "${line}")
  endforeach()
  if(open AND expected_code EQUAL 0)
    message(FATAL_ERROR "stages begun and never done: ${open}")
  endif()
  string(JSON lastEvent GET "${last}" event)
  string(JSON lastCode ERROR_VARIABLE nocode GET "${last}" exit_code)
  if(NOT lastEvent STREQUAL "finish" OR NOT lastCode EQUAL expected_code)
    message(FATAL_ERROR "the last record is not finish with exit code ${expected_code}: ${last}")
  endif()
  set(json_events "${kinds}" PARENT_SCOPE)
endfunction()

check_json_progress(0 "${DATA}/speck_feature.json" -o "${OUT}/jsonprogress")
list(FIND json_events "warning" warningAt)
if(warningAt LESS 0)
  message(FATAL_ERROR "the speck's warning is not a JSON record: ${json_events}")
endif()
check_json_progress(3 "${DATA}/truncated.json" -o "${OUT}/jsonprogress_bad")
list(GET json_events -2 beforeLast)
if(NOT beforeLast STREQUAL "error")
  message(FATAL_ERROR "a failed run's error is not a JSON record before finish: ${json_events}")
endif()

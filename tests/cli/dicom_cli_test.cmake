# End-to-end checks of DICOM RTSTRUCT input on the public samples (../shared/data/rtstruct,
# see its SOURCES.md): listing, ROI selection, the reference CT grid, exit codes and messages.
# Run by ctest with -DSCANSURF=<exe> -DSAMPLES=<dir> -DOUT=<dir>.

include("${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake")

if(NOT EXISTS "${SAMPLES}/pydicom-rtstruct.dcm")
  message("SKIPPED: no public RTSTRUCT samples at ${SAMPLES} (../shared beside the clone)")
  return()
endif()
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
set(MIM "${SAMPLES}/rt-utils/mim_phantom")

# Listing: every ROI with its number, type, contours by geometric type, slices and z range.
run_scansurf(0 "${SAMPLES}/pydicom-rtstruct.dcm" --list-rois)
expect_output("RT Structure Set \"sep30\", 3 ROIs")
expect_output("1 +patient +EXTERNAL +3 CLOSED_PLANAR +3 +-200 \\.\\. -180 +yes")
expect_output("2 +Isocenter 1 +ISOCENTER +1 POINT +0 ")
run_scansurf(0 "${MIM}/rt.dcm" --list-rois --roi "roi-[12]")
expect_output("3 +ROI-3 +- +3 CLOSED_PLANAR +3 +60 \\.\\. 70 +no")
# A 3D Slicer segmentation lists its segments the same way (../shared/data/slicer, beside the
# RTSTRUCT samples).
set(SLICER "${SAMPLES}/../slicer/EclipseEnt_Structures.seg.vtm")
if(EXISTS "${SLICER}")
  run_scansurf(0 "${SLICER}" --list-rois --roi "Optic*")
  expect_output("16 segments")
  expect_output("9 +Optic Chiasm +- +3 CLOSED_PLANAR +3 +137 \\.\\. 142 +yes")
  expect_output("1 +BODY +- +136 CLOSED_PLANAR +136 +-100\\.5 \\.\\. 237 +no")
endif()

# The file without a DICOM file header, with POINT ROIs skipped (one warning each).
run_scansurf(0 "${SAMPLES}/pydicom-rtstruct.dcm" -o "${OUT}/pydicom" --voxel-size 4)
expect_output("ROI \"Isocenter 1\" \\(#2\\): skipped 1 POINT contour\\(s\\)")
expect_output("patient +1 +0 +[0-9]+ +[0-9.]+ +[0-9.]+ +1 +0 yes")

# The MIM phantom on its own CT: the CT's 512 x 512 pixels plus the border, over the 3 CT slices
# that hold contours (of 5) and a background layer each side.
run_scansurf(0 "${MIM}/rt.dcm" --reference "${MIM}" -o "${OUT}/mim" --roi "ROI-*" --report "${OUT}/mim.json")
# The report's input files: the structure set and the 5 CT files it was placed on.
file(READ "${OUT}/mim.json" mim_report)
string(JSON mim_inputs LENGTH "${mim_report}" input_files)
if(NOT mim_inputs EQUAL 6)
  message(FATAL_ERROR "the report lists ${mim_inputs} input files, not the RTSTRUCT and its 5 CT files")
endif()
expect_output("grid: 514 x 514 x 5 voxels \\(0.488281 x 0.488281 mm pixels, 3 slices")
foreach(n 1 2 3 4)
  expect_output("ROI-${n} +${n} +0 +[0-9]+ +[0-9.]+ +[0-9.]+ +1 +[01] yes")
  if(NOT EXISTS "${OUT}/mim/ROI-${n}.ply")
    message(FATAL_ERROR "missing ${OUT}/mim/ROI-${n}.ply")
  endif()
endforeach()
# Selection: only the ROIs asked for.
run_scansurf(0 "${SAMPLES}/rt-utils/non_existent_reference_rt.dcm" -o "${OUT}/selected" --roi "roi-4" -q)
file(GLOB selected "${OUT}/selected/*.ply")
list(LENGTH selected count)
if(NOT count EQUAL 2)
  message(FATAL_ERROR "--roi roi-4: expected ROI-4.ply and multilabel.ply, got ${selected}")
endif()

# Bad input and options.
run_scansurf(2 "${MIM}/rt.dcm" -o "${OUT}/bad" --roi Liver)
expect_output("--roi \"Liver\" matches no ROI; the file holds \"ROI-1\", \"ROI-2\", \"ROI-3\", \"ROI-4\"")
file(WRITE "${OUT}/notes.dcm" "plain text, not DICOM\n")
run_scansurf(3 "${OUT}/notes.dcm" -o "${OUT}/bad")
# Recognised by content, not by its name: a text file called .dcm is no format scansurf reads.
expect_output("notes.dcm: not a contour file scansurf reads \\(it starts with \"plain text, not \"\\); supported formats")
run_scansurf(2 "${MIM}/rt.dcm" -o "${OUT}/bad" --object ROI-1)
expect_output("object selection applies to Reconstruct and IMOD input, not to DICOM RTSTRUCT .*\\(select its ROIs with --roi\\)")
run_scansurf(2 "${MIM}/rt.dcm" --list-objects)
expect_output("--list-objects applies to Reconstruct and IMOD input, not to DICOM RTSTRUCT .*\\(use --list-rois\\)")
file(GLOB ct_files "${MIM}/2.16.*.dcm")
list(GET ct_files 0 ct_file)
run_scansurf(3 "${ct_file}" -o "${OUT}/bad")
expect_output("a DICOM CT object \\(SOP class CTImageStorage\\), not an RT Structure Set")
run_scansurf(3 "${SAMPLES}/pydicom-rtstruct.dcm" --reference "${MIM}" -o "${OUT}/bad")
expect_output("frame of reference .* differs from the reference series'")
run_scansurf(4 "${MIM}/rt.dcm" --reference "${OUT}/no-such-dir" -o "${OUT}/bad")
run_scansurf(2 "${MIM}/rt.dcm")
expect_output("-o/--output is required")
expect_nothing_left("${OUT}/bad")

# The label volume on the MIM phantom's CT as a DICOM Segmentation and as gzip NIfTI.
run_scansurf(0 --help)
expect_output("--label-volume F +write the label volume by extension: \\.nrrd or \\.seg\\.nrrd")
expect_output("--dicom-seg[^\n]*DICOM Segmentation")
run_scansurf(0 "${MIM}/rt.dcm" --reference "${MIM}" -o "${OUT}/mim-seg" --no-smooth -q
  --dicom-seg "${OUT}/mim-seg/mim.dcm" --label-volume "${OUT}/mim-seg/mim.nii.gz")
file(READ "${OUT}/mim-seg/mim.dcm" preamble OFFSET 128 LIMIT 4 HEX)
if(NOT preamble STREQUAL "4449434d")  # "DICM"
  message(FATAL_ERROR "--dicom-seg: ${OUT}/mim-seg/mim.dcm is not a DICOM file")
endif()
file(READ "${OUT}/mim-seg/mim.nii.gz" magic LIMIT 2 HEX)
if(NOT magic STREQUAL "1f8b")
  message(FATAL_ERROR "--label-volume x.nii.gz: not gzip (starts with ${magic})")
endif()
file(READ "${OUT}/mim-seg/mim.label.txt" table)
if(NOT table MATCHES "ITK-SnAP Label Description File" OR NOT table MATCHES "\n +4 +[0-9]+ +[0-9]+ +[0-9]+ +1 +1 +1 +\"ROI-4\"")
  message(FATAL_ERROR "--label-volume x.nii.gz: unexpected label table:\n${table}")
endif()
find_program(DCIODVFY dciodvfy)
if(DCIODVFY)
  execute_process(COMMAND ${DCIODVFY} "${OUT}/mim-seg/mim.dcm" OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if("${out}${err}" MATCHES "(^|\n)Error")
    message(FATAL_ERROR "dciodvfy finds errors in the DICOM SEG:\n${out}${err}")
  endif()
else()
  message(STATUS "dciodvfy (dicom3tools) not installed: DICOM SEG not validated")
endif()
# The SEG and its CT say the same of the patient and the study, empty attributes included.
find_program(DCENTVFY dcentvfy)
file(GLOB mim_ct "${MIM}/2.*.dcm")
if(DCENTVFY AND mim_ct)
  list(GET mim_ct 0 first_ct)
  execute_process(COMMAND ${DCENTVFY} "${OUT}/mim-seg/mim.dcm" "${first_ct}" OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if("${out}${err}" MATCHES "(Error|Warning)")
    message(FATAL_ERROR "dcentvfy finds the SEG and its CT disagree:\n${out}${err}")
  endif()
endif()
# A DICOM SEG needs the CT grid: no --reference, or a grid of its own, is a usage error.
run_scansurf(2 "${MIM}/rt.dcm" -o "${OUT}/bad" --dicom-seg "${OUT}/bad/x.dcm")
expect_output("needs the CT series the label volume lies on \\(--reference CT_DIR\\)")
run_scansurf(2 "${MIM}/rt.dcm" --reference "${MIM}" --voxel-size 1 -o "${OUT}/bad" --dicom-seg "${OUT}/bad/x.dcm")
expect_output("leave out --voxel-size and --grid")
run_scansurf(2 "${MIM}/rt.dcm" -o "${OUT}/bad" --label-volume "${OUT}/bad/x.mha")
expect_output("known: .nrrd, .seg.nrrd, .nii, .nii.gz")
expect_nothing_left("${OUT}/bad")

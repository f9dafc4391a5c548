# The NIfTI reference library (libnifti2-dev: nifti1_io and znzlib) as imported targets,
# scansurf_nifti::niftiio and scansurf_nifti::znz, found where the machine has them. Used by
# the build and by the installed package's config (static builds link them), so the package
# names targets, never the absolute paths of one machine's libraries.
if(NOT TARGET scansurf_nifti::niftiio)
  find_library(SCANSURF_NIFTIIO_LIBRARY niftiio REQUIRED)
  find_library(SCANSURF_ZNZ_LIBRARY znz REQUIRED)
  add_library(scansurf_nifti::znz UNKNOWN IMPORTED)
  set_target_properties(scansurf_nifti::znz PROPERTIES IMPORTED_LOCATION "${SCANSURF_ZNZ_LIBRARY}" INTERFACE_LINK_LIBRARIES ZLIB::ZLIB)
  add_library(scansurf_nifti::niftiio UNKNOWN IMPORTED)
  set_target_properties(scansurf_nifti::niftiio PROPERTIES IMPORTED_LOCATION "${SCANSURF_NIFTIIO_LIBRARY}"
                                                           INTERFACE_LINK_LIBRARIES scansurf_nifti::znz)
endif()

# Every external dependency, all from Debian 12 packages (cmake/install-deps.sh installs them).
find_package(Threads REQUIRED)
find_package(Vulkan REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
if(SCANSURF_BUILD_CLI)
  find_package(CLI11 REQUIRED)
endif()
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)
# Draco (libdraco-dev): mesh compression and its glTF encoder; Debian ships a CMake config
# with draco::draco (cmake/scansurfConfig.cmake.in finds it again for consumers).
find_package(draco CONFIG REQUIRED)
add_library(scansurf_draco INTERFACE)
target_link_libraries(scansurf_draco INTERFACE draco::draco)
# Draco's scene and glTF headers include Eigen (libeigen3-dev).
find_package(Eigen3 REQUIRED NO_MODULE)
target_link_libraries(scansurf_draco INTERFACE Eigen3::Eigen)
find_package(PNG REQUIRED)
find_package(ZLIB REQUIRED)
find_package(OpenSSL REQUIRED COMPONENTS Crypto)  # SHA-256 of the inputs, for the report
# DICOM RT Structure Sets and CT series (engine/io): Debian's DCMTK config, targets DCMTK::<module>;
# DICOM SEG output uses DCMTK::dcmseg with dcmfg and dcmiod.
find_package(DCMTK REQUIRED CONFIG)
# Reconstruct series (XML, engine/io/reconstruct_reader.cpp): Debian's pugixml config,
# target pugixml::pugixml.
find_package(pugixml REQUIRED CONFIG)
# NIfTI label volumes (engine/io/nifti_writer.cpp): the NIfTI reference library's nifti1_io and
# znzlib from libnifti2-dev (which pulls in libniftiio-dev and libznz-dev). Its CMake config
# cannot be used on Debian 12: NIFTITargets-none.cmake names /usr/lib/libznz.so.3.0.0 and
# /usr/bin/nifti_tool, which the packages do not install (the libraries are in the multiarch
# directory), so find_package(NIFTI CONFIG) stops with a fatal error; and the packages ship no
# pkg-config file. Hence a plain header and library search.
find_path(SCANSURF_NIFTI_INCLUDE_DIR nifti1_io.h PATH_SUFFIXES nifti REQUIRED)
include("${CMAKE_CURRENT_LIST_DIR}/NiftiTargets.cmake")
set(SCANSURF_NIFTI_LIBRARIES scansurf_nifti::niftiio)
# The CPU geometry's vectors (engine/geometry/mesh/vec3.h): GLM, header-only (libglm-dev).
find_path(SCANSURF_GLM_INCLUDE_DIR glm/vec3.hpp REQUIRED)
if(SCANSURF_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()

# Every external dependency, all from Debian 12 packages (cmake/install-deps.sh installs them).
find_package(Threads REQUIRED)
find_package(Vulkan REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(glm REQUIRED)
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)
# DICOM RT Structure Sets and CT series (engine/io): Debian's DCMTK config, targets DCMTK::<module>.
find_package(DCMTK REQUIRED CONFIG)
if(SCANSURF_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()

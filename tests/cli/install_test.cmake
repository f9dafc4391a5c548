# Installs the build into a fresh prefix, then configures, builds and runs examples/embed, an
# outside project that knows scansurf only through find_package(scansurf) and
# <scansurf/scansurf.h>. Arguments: -DBUILD_DIR, -DSOURCE_DIR, -DWORK (scratch), -DGENERATOR.
file(REMOVE_RECURSE "${WORK}")
set(prefix "${WORK}/prefix")
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  if(err MATCHES "validation (error|warning)")
    message(FATAL_ERROR "${what}: Vulkan validation messages:\n${err}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

run("cmake --install" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
foreach(f include/scansurf/scansurf.h include/scansurf/version.h bin/scansurf)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
file(GLOB_RECURSE config "${prefix}/*/scansurfConfig.cmake")
if(NOT config)
  message(FATAL_ERROR "scansurfConfig.cmake not installed")
endif()
# Nothing internal leaks: the public headers include only public headers.
file(GLOB headers "${prefix}/include/scansurf/*.h")
foreach(h IN LISTS headers)
  file(STRINGS "${h}" includes REGEX "^#include \"")
  foreach(line IN LISTS includes)
    if(NOT line MATCHES "^#include \"scansurf/")
      message(FATAL_ERROR "${h} includes a non-public header: ${line}")
    endif()
  endforeach()
endforeach()

# The package is relocatable: it names imported targets, never this machine's library paths,
# and works from wherever the prefix is moved.
file(GLOB_RECURSE exported "${prefix}/*/scansurfTargets*.cmake")
foreach(file IN LISTS exported)
  file(READ "${file}" text)
  if(text MATCHES "/usr/lib/[^\"]*\\.(so|a)")
    message(FATAL_ERROR "${file} names a library by its absolute path: ${CMAKE_MATCH_0}")
  endif()
endforeach()
set(moved "${WORK}/moved-prefix")
file(RENAME "${prefix}" "${moved}")
set(prefix "${moved}")
run("configure examples/embed" ${CMAKE_COMMAND} -S "${SOURCE_DIR}/examples/embed" -B "${WORK}/embed" -G "${GENERATOR}"
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}")
run("build examples/embed" ${CMAKE_COMMAND} --build "${WORK}/embed")
run("run examples/embed" "${WORK}/embed/embed_example" "${SOURCE_DIR}/examples/phantom.json" "${WORK}/phantom.glb")
message("${output}")
if(NOT output MATCHES "BODY +[0-9]+ triangles .* closed" OR output MATCHES "OPEN")
  message(FATAL_ERROR "examples/embed did not build closed surfaces:\n${output}")
endif()
file(SIZE "${WORK}/phantom.glb" size)
if(size LESS 10000)
  message(FATAL_ERROR "examples/embed wrote a GLB of only ${size} bytes")
endif()

# The Python package, installed under the prefix (PYTHON_DIR relative to it), imports and builds
# from there, away from the build tree.
if(PYTHON AND PYTHON_DIR)
  set(ENV{PYTHONPATH} "${prefix}/${PYTHON_DIR}")
  # (Newlines, not semicolons, between the statements: a semicolon would split the argument.)
  run("import the installed Python package" "${PYTHON}" -c [=[
import scansurf, sys
r = scansurf.build(scansurf.read(sys.argv[1]), voxel_size=2.0)
assert r.surfaces['BODY'].closed
print(scansurf.__file__, end='')
]=] "${SOURCE_DIR}/examples/phantom.json")
  if(NOT output MATCHES "^${prefix}/")
    message(FATAL_ERROR "the Python package was imported from ${output}, not from the installed prefix")
  endif()
  message("Python package: ${output}")
  # Every Python snippet of README and docs/python.md, as written, from this prefix.
  run("the documented snippets" "${PYTHON}" "${SOURCE_DIR}/tests/cli/docs_snippets.py" --root "${SOURCE_DIR}"
      --prefix "${prefix}" --python-dir "${PYTHON_DIR}" --work "${WORK}/snippets" --cmake "${CMAKE_COMMAND}"
      --generator "${GENERATOR}")
  message("${output}")
endif()

# The install test (ctest: install_consumer): what a user does with an installed bimloc.
#   1. cmake --install the build tree into a fresh prefix;
#   2. configure and build tests/install/consumer (find_package(bimloc), bimloc::localizer) there;
#   3. run it on a plan: one synthetic turn through bimloc::Localizer, its line checked;
#   4. pkg-config --cflags --libs bimloc resolves, and a compile + link with those flags alone works.
# Run as: cmake -DBUILD_DIR= -DWORK_DIR= -DCONSUMER_DIR= -DPLAN= -DLIBDIR= -DGENERATOR= -DCXX=
#               [-DPKG_CONFIG=] [-DWITH_SIM=ON] -P check_install.cmake
foreach(var BUILD_DIR WORK_DIR CONSUMER_DIR PLAN LIBDIR GENERATOR CXX)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_install.cmake: -D${var}=... is missing")
  endif()
endforeach()

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${ARGN}\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()

set(prefix "${WORK_DIR}/prefix")
file(REMOVE_RECURSE "${WORK_DIR}")

# 1. Install; every file the package promises is there.
run("cmake --install" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
foreach(f include/bimloc/localizer.hpp include/bimloc/bim/ifc_reader.hpp
          ${LIBDIR}/libbimloc_localizer.so ${LIBDIR}/cmake/bimloc/bimlocConfig.cmake
          ${LIBDIR}/cmake/bimloc/bimlocConfigVersion.cmake ${LIBDIR}/cmake/bimloc/bimlocTargets.cmake
          ${LIBDIR}/pkgconfig/bimloc.pc)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "not installed: ${prefix}/${f}")
  endif()
endforeach()
# No private header (PCL, Ceres, IFC++ behind them) leaks into the installed ones.
file(GLOB_RECURSE headers "${prefix}/include/bimloc/*")
foreach(h ${headers})
  file(STRINGS "${h}" leaks REGEX "#include *[<\"](pcl/|ceres/|ifcpp/)")
  if(leaks)
    message(FATAL_ERROR "${h} includes a private dependency: ${leaks}")
  endif()
endforeach()

# SameMajorVersion: 0.1.0 satisfies requests for 0.0.5 and 0.1, not 0.2 (newer) nor 1.0.
function(version_compatible requested result)
  set(PACKAGE_FIND_VERSION ${requested})
  string(REPLACE "." ";" parts ${requested})
  list(GET parts 0 PACKAGE_FIND_VERSION_MAJOR)
  include("${prefix}/${LIBDIR}/cmake/bimloc/bimlocConfigVersion.cmake")
  set(${result} ${PACKAGE_VERSION_COMPATIBLE} PARENT_SCOPE)
endfunction()
foreach(case "0.0.5;TRUE" "0.1;TRUE" "0.2;FALSE" "1.0;FALSE")
  list(GET case 0 requested)
  list(GET case 1 want)
  version_compatible(${requested} got)
  if(NOT "${got}" STREQUAL "${want}")
    message(FATAL_ERROR "find_package(bimloc ${requested}): compatible is '${got}', expected ${want}")
  endif()
endforeach()

# With the bench, the command is installed and finds the installed localizer ($ORIGIN/../lib).
if(WITH_SIM)
  run("the installed bimloc command" "${prefix}/bin/bimloc" --help)
  execute_process(COMMAND ldd "${prefix}/bin/bimloc" OUTPUT_VARIABLE ldd_out)
  string(REGEX MATCH "libbimloc_localizer[^\n]*" ldd_line "${ldd_out}")
  if(NOT ldd_line MATCHES "=> ${prefix}/(bin/\\.\\./)?${LIBDIR}/libbimloc_localizer")
    message(FATAL_ERROR "the installed bimloc does not use the installed localizer: ${ldd_line}")
  endif()
  message(STATUS "installed bimloc: ${ldd_line}")
endif()

# 2. The consumer, against that prefix only.
run("configuring the consumer" ${CMAKE_COMMAND} -S "${CONSUMER_DIR}" -B "${WORK_DIR}/build" -G "${GENERATOR}"
    "-DCMAKE_CXX_COMPILER=${CXX}" -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}")
file(STRINGS "${WORK_DIR}/build/CMakeCache.txt" found REGEX "^bimloc_DIR:")
if(NOT found STREQUAL "bimloc_DIR:PATH=${prefix}/${LIBDIR}/cmake/bimloc")
  message(FATAL_ERROR "the consumer found another bimloc: ${found}")
endif()
run("building the consumer" ${CMAKE_COMMAND} --build "${WORK_DIR}/build")

# 3. One turn through the installed localizer (IFC++, PCL and Ceres behind it, found by its RUNPATH).
set(expected "bimloc consumer: plan=[1-9][0-9]* storeys room=[^ ]+ points=[1-9][0-9]* state=(searching|converged) used_points=1 walls_observed=([3-9]|[1-9][0-9])\n")
run("running the consumer" "${WORK_DIR}/build/consumer" "${PLAN}")
if(NOT run_out MATCHES "${expected}")
  message(FATAL_ERROR "unexpected consumer output:\n${run_out}\nexpected (regex): ${expected}")
endif()
message(STATUS "CMake consumer: ${run_out}")

# 4. pkg-config.
if(NOT PKG_CONFIG)
  message(STATUS "pkg-config not found: its part of the test is skipped")
  return()
endif()
set(ENV{PKG_CONFIG_PATH} "${prefix}/${LIBDIR}/pkgconfig")
run("pkg-config" ${PKG_CONFIG} --cflags --libs bimloc)
string(STRIP "${run_out}" flags)
foreach(want "-I${prefix}/include" "-L${prefix}/${LIBDIR}" "-lbimloc_localizer" "-I/usr/include/eigen3")
  string(FIND " ${flags} " " ${want} " at)
  if(at EQUAL -1)
    message(FATAL_ERROR "pkg-config --cflags --libs bimloc: '${want}' missing in: ${flags}")
  endif()
endforeach()
message(STATUS "pkg-config --cflags --libs bimloc: ${flags}")
separate_arguments(flag_list UNIX_COMMAND "${flags}")
run("compiling the consumer with pkg-config's flags" ${CXX} -std=c++17 -O1 "${CONSUMER_DIR}/main.cpp" ${flag_list}
    -o "${WORK_DIR}/consumer_pc")
set(ENV{LD_LIBRARY_PATH} "${prefix}/${LIBDIR}")
run("running the pkg-config consumer" "${WORK_DIR}/consumer_pc" "${PLAN}")
if(NOT run_out MATCHES "${expected}")
  message(FATAL_ERROR "unexpected output of the pkg-config consumer:\n${run_out}")
endif()
message(STATUS "pkg-config consumer: ${run_out}")

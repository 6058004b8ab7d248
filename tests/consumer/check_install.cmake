# ctest install.find_package_consumer: cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DCXX=... -P THIS
# Installs the build into WORK_DIR/prefix; checks that the exported interface carries no build
# flag, no version define and no header-only dependency, and bssrdf::core no Ceres; builds
# tests/consumer with find_package(bssrdf) (against bssrdf::bssrdf and bssrdf::core) and again with
# pkg-config; and checks that both print what the installed
# CLI computes for the same medium.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "failed (${status}): ${ARGN}\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")

file(GLOB targets "${prefix}/lib*/cmake/bssrdf/bssrdfTargets.cmake")
file(GLOB version_file "${prefix}/lib*/cmake/bssrdf/bssrdfConfigVersion.cmake")
if(NOT targets OR NOT version_file)
  message(FATAL_ERROR "no bssrdfTargets.cmake / bssrdfConfigVersion.cmake under ${prefix}")
endif()
file(READ "${targets}" exported)
foreach(leak "march=native" "BSSRDF_VERSION" "nlohmann" "Eigen3")
  string(FIND "${exported}" "${leak}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the exported interface mentions ${leak}:\n${exported}")
  endif()
endforeach()

# The core library's exported link interface carries no Ceres (that is the fitting library's).
string(REGEX MATCH "set_target_properties\\(bssrdf::core[^)]*\\)" core_block "${exported}")
string(FIND "${core_block}" "INTERFACE_LINK_LIBRARIES" has_links)
string(TOLOWER "${core_block}" core_lower)
string(FIND "${core_lower}" "ceres" core_ceres)
if(has_links EQUAL -1 OR NOT core_ceres EQUAL -1)
  message(FATAL_ERROR "bssrdf::core should link OpenEXR and Threads but not Ceres:\n${core_block}")
endif()

# bssrdf::core names the installed include directory once (install(TARGETS ... INCLUDES DESTINATION) beside
# its own $<INSTALL_INTERFACE:include> once listed it twice), and bssrdf::bssrdf lists none twice.
foreach(target core bssrdf)
  string(REGEX MATCH "set_target_properties\\(bssrdf::${target} [^)]*\\)" block "${exported}")
  set(dirs "")
  if(block MATCHES "INTERFACE_INCLUDE_DIRECTORIES \"([^\"]*)\"")
    set(dirs "${CMAKE_MATCH_1}")
  endif()
  set(unique "${dirs}")
  list(REMOVE_DUPLICATES unique)
  if(NOT "${unique}" STREQUAL "${dirs}" OR (target STREQUAL "core" AND NOT dirs STREQUAL "\${_IMPORT_PREFIX}/include"))
    message(FATAL_ERROR "bssrdf::${target}: include directories '${dirs}' (core: \${_IMPORT_PREFIX}/include once)")
  endif()
endforeach()

# find_package
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}" -B "${WORK_DIR}/build" -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build "${WORK_DIR}/build")
run("${WORK_DIR}/build/consumer")
string(STRIP "${out}" from_cmake)
run("${WORK_DIR}/build/consumer_core")
string(STRIP "${out}" from_core)

# pkg-config (a static library: --static lists its private dependencies)
file(GLOB pc_dir "${prefix}/lib*/pkgconfig")
set(ENV{PKG_CONFIG_PATH} "${pc_dir}")
run(pkg-config --static --cflags --libs bssrdf)
string(STRIP "${out}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run(${CXX} "${SOURCE_DIR}/main.cpp" -o "${WORK_DIR}/consumer-pc" ${flags})
run("${WORK_DIR}/consumer-pc")
string(STRIP "${out}" from_pkg_config)

# The installed CLI on the same medium.
run("${prefix}/bin/bssrdf" profile --sigma-a 0.032 --sigma-s 0.74 --eta 1.3 --model better-dipole --format json)
string(JSON total GET "${out}" channels 0 total_reflectance)
execute_process(COMMAND printf "%.6f" "${total}" OUTPUT_VARIABLE expected)
foreach(got from_cmake from_core from_pkg_config)
  if(NOT "${${got}}" STREQUAL "${expected}")
    message(FATAL_ERROR "${got}: consumer printed '${${got}}', the installed CLI gives ${expected}")
  endif()
endforeach()
message(STATUS "find_package and pkg-config consumers print ${from_cmake} = the installed CLI's total reflectance")

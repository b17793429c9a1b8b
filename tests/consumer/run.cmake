# Consumer-build tests (tests/CMakeLists.txt): cmake -DMODE=... -P run.cmake
#   MODE=install       installs the build tree BUILD_DIR into PREFIX
#   MODE=installed     builds and runs installed/ against PREFIX (every component)
#   MODE=core_only     builds and runs core_only/ against PREFIX with Vulkan and pkg-config (the
#                      way to OpenImageIO) hidden, then again through pkg-config's bluetile-core
#   MODE=subdirectory  builds and runs subdirectory/, which add_subdirectory()s SOURCE_DIR
# Each step's output is shown only when it fails.
cmake_minimum_required(VERSION 3.25)

function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}")
  endif()
  message(STATUS "${what}: ok")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

# configure_build_run(<project folder> <program argument> <cmake arguments...>)
function(configure_build_run project argument)
  set(build ${WORK_DIR}/${project})
  file(REMOVE_RECURSE ${build})
  step("configure ${project}" ${CMAKE_COMMAND} -S ${CMAKE_CURRENT_LIST_DIR}/${project} -B ${build}
    -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} ${ARGN})
  step("build ${project}" ${CMAKE_COMMAND} --build ${build} -j 2 --target consumer ${EXTRA_TARGETS})
  step("run ${project}" ${build}/consumer ${build}/${argument})
  message(STATUS "${step_output}")
endfunction()

if(MODE STREQUAL "install")
  file(REMOVE_RECURSE ${PREFIX})
  step("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})
elseif(MODE STREQUAL "installed")
  configure_build_run(installed image.png -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_BUILD_TYPE=Debug)
elseif(MODE STREQUAL "core_only")
  configure_build_run(core_only none -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_BUILD_TYPE=Debug
    -DCMAKE_DISABLE_FIND_PACKAGE_Vulkan=ON -DCMAKE_DISABLE_FIND_PACKAGE_PkgConfig=ON)
  # The same program through pkg-config, as a Makefile user would build it.
  file(GLOB pc_dir ${PREFIX}/lib*/pkgconfig ${PREFIX}/lib/*/pkgconfig)
  step("pkg-config bluetile-core" ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pc_dir}
    pkg-config --cflags --libs bluetile-core)
  string(STRIP "${step_output}" flags)
  separate_arguments(flags UNIX_COMMAND "${flags}")
  step("compile with pkg-config" ${CXX_COMPILER} -std=c++20 ${CMAKE_CURRENT_LIST_DIR}/core_only/main.cpp
    -o ${WORK_DIR}/core_only/consumer_pc ${flags})
  step("run the pkg-config build" ${WORK_DIR}/core_only/consumer_pc)
elseif(MODE STREQUAL "subdirectory")
  # No build type: the consumer's (empty) one must survive; the shaders are compiled too, since
  # they are what broke in a subdirectory before.
  set(EXTRA_TARGETS bluetile_raster_shaders)
  configure_build_run(subdirectory none -DBLUETILE_SOURCE_DIR=${SOURCE_DIR})
else()
  message(FATAL_ERROR "unknown MODE '${MODE}'")
endif()

# Consumer-build tests (tests/CMakeLists.txt): cmake -DMODE=... -P run.cmake
#   MODE=install       installs the build tree BUILD_DIR into PREFIX
#   MODE=installed     builds and runs installed/ against PREFIX (every component)
#   MODE=core_only     builds and runs core_only/ against PREFIX with Vulkan and pkg-config (the
#                      way to OpenImageIO) hidden, then again through pkg-config's bluetile-core
#   MODE=subdirectory  builds and runs subdirectory/, which add_subdirectory()s SOURCE_DIR
#   MODE=headers       builds headers/ against PREFIX: every installed header alone, with
#                      -Wall -Wextra -Wpedantic -Werror
#   MODE=components    builds and runs components/ against PREFIX (find_package called several
#                      times), then configures it asking for an unknown component: that fails,
#                      naming it
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

# step_fails(<what> <regex> <command...>): the command fails, and its output matches regex.
function(step_fails what regex)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc EQUAL 0)
    message(FATAL_ERROR "${what} succeeded, expected a failure:\n${out}")
  endif()
  string(REGEX REPLACE "[ \n]+" " " flat "${out}")
  if(NOT flat MATCHES "${regex}")
    message(FATAL_ERROR "${what} failed without saying '${regex}':\n${out}")
  endif()
  message(STATUS "${what}: fails as expected")
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
  set(step_output "${step_output}" PARENT_SCOPE)
endfunction()

if(MODE STREQUAL "install")
  file(REMOVE_RECURSE ${PREFIX})
  step("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})
  # The umbrella is installed, internal headers (src/bluetile/CMakeLists.txt) are not.
  if(NOT EXISTS ${PREFIX}/include/bluetile/bluetile.h)
    message(FATAL_ERROR "bluetile/bluetile.h was not installed")
  endif()
  foreach(internal core/text.h voronoi/kept_delaunay.h raster/raster_reference.h gpu/pipelines.h io/font.h)
    if(EXISTS ${PREFIX}/include/bluetile/${internal})
      message(FATAL_ERROR "the internal header bluetile/${internal} was installed")
    endif()
  endforeach()
elseif(MODE STREQUAL "installed")
  configure_build_run(installed image.png -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_BUILD_TYPE=Debug)
  # pkg-config's bluetile (every component) defines what the umbrella header needs, as the
  # CMake targets do.
  file(GLOB pc_dir ${PREFIX}/lib*/pkgconfig ${PREFIX}/lib/*/pkgconfig)
  step("pkg-config bluetile" ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pc_dir} pkg-config --cflags bluetile)
  foreach(define BLUETILE_WITH_IMAGES BLUETILE_WITH_RASTER)
    if(NOT step_output MATCHES "-D${define}=1")
      message(FATAL_ERROR "pkg-config --cflags bluetile lacks -D${define}=1: '${step_output}'")
    endif()
  endforeach()
  # A program built through pkg-config with a relative PKG_CONFIG_PATH finds the image plugin
  # when run from another folder: its RUNPATH is absolute.
  file(RELATIVE_PATH pc_relative ${WORK_DIR} ${pc_dir})
  step("pkg-config bluetile-images, relative PKG_CONFIG_PATH" ${CMAKE_COMMAND} -E chdir ${WORK_DIR}
    ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pc_relative} pkg-config --cflags --libs bluetile-images)
  string(STRIP "${step_output}" flags)
  if(NOT flags MATCHES "-Wl,-rpath,${PREFIX}/")
    message(FATAL_ERROR "pkg-config --libs bluetile-images gives no absolute RUNPATH under ${PREFIX}: '${flags}'")
  endif()
  separate_arguments(flags UNIX_COMMAND "${flags}")
  step("compile with pkg-config" ${CMAKE_COMMAND} -E chdir ${WORK_DIR} ${CXX_COMPILER} -std=c++20
    ${CMAKE_CURRENT_LIST_DIR}/components/main.cpp -o images_pc ${flags})
  step("run the pkg-config build from another folder" ${CMAKE_COMMAND} -E chdir ${CMAKE_CURRENT_LIST_DIR}
    ${WORK_DIR}/images_pc ${WORK_DIR}/image_pc.png)
elseif(MODE STREQUAL "core_only")
  configure_build_run(core_only table.h -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_BUILD_TYPE=Debug
    -DCMAKE_DISABLE_FIND_PACKAGE_Vulkan=ON -DCMAKE_DISABLE_FIND_PACKAGE_PkgConfig=ON)
  string(REGEX MATCH "table sum [^\n]*" consumer_sum "${step_output}")
  # The C header it wrote, compiled as C: the same floats.
  step("compile the C header as C" ${CXX_COMPILER} -x c -std=c99 -I${WORK_DIR}/core_only
    ${CMAKE_CURRENT_LIST_DIR}/core_only/table_sum.c -o ${WORK_DIR}/core_only/table_sum)
  step("run the C program" ${WORK_DIR}/core_only/table_sum)
  string(STRIP "${step_output}" c_sum)
  if(NOT consumer_sum STREQUAL c_sum)
    message(FATAL_ERROR "the C header holds other values: '${c_sum}', the consumer wrote '${consumer_sum}'")
  endif()
  # The same program through pkg-config, as a Makefile user would build it.
  file(GLOB pc_dir ${PREFIX}/lib*/pkgconfig ${PREFIX}/lib/*/pkgconfig)
  step("pkg-config bluetile-core" ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pc_dir}
    pkg-config --cflags --libs bluetile-core)
  string(STRIP "${step_output}" flags)
  separate_arguments(flags UNIX_COMMAND "${flags}")
  step("compile with pkg-config" ${CXX_COMPILER} -std=c++20 ${CMAKE_CURRENT_LIST_DIR}/core_only/main.cpp
    -o ${WORK_DIR}/core_only/consumer_pc ${flags})
  step("run the pkg-config build" ${WORK_DIR}/core_only/consumer_pc ${WORK_DIR}/core_only/table_pc.h)
elseif(MODE STREQUAL "subdirectory")
  # No build type: the consumer's (empty) one must survive; the shaders are compiled too, since
  # they are what broke in a subdirectory before.
  set(EXTRA_TARGETS bluetile_raster_shaders)
  configure_build_run(subdirectory none -DBLUETILE_SOURCE_DIR=${SOURCE_DIR})
elseif(MODE STREQUAL "headers")
  configure_build_run(headers none -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_BUILD_TYPE=Debug)
elseif(MODE STREQUAL "components")
  configure_build_run(components image.png -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_BUILD_TYPE=Debug)
  step_fails("find_package(bluetile REQUIRED COMPONENTS core bogus)"
    "bluetile has no component 'bogus'; its components are core, images, raster"
    ${CMAKE_COMMAND} -S ${CMAKE_CURRENT_LIST_DIR}/components -B ${WORK_DIR}/components-unknown -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${PREFIX} -DUNKNOWN_COMPONENT=bogus)
else()
  message(FATAL_ERROR "unknown MODE '${MODE}'")
endif()

# Install rules: headers, the component libraries, the image plugin, the tool, the CMake package
# (find_package(bluetile [COMPONENTS core images raster])) and pkg-config files.
#
# Layout under the prefix:
#   include/bluetile/<folder>/*.h
#   <libdir>/libbluetile_{core,images,raster}.{a,so}
#   <libdir>/bluetile/libbluetile_oiio.so      the image plugin, found through the RUNPATH below
#   <libdir>/cmake/bluetile/                   package config, version file, one export per component
#   <libdir>/pkgconfig/bluetile{,-core,-images,-raster}.pc
#   bin/bluetile
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(bluetile_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/bluetile)
set(bluetile_plugin_dir ${CMAKE_INSTALL_LIBDIR}/bluetile)
set(bluetile_components core)
if(TARGET bluetile_images)
  list(APPEND bluetile_components images)
endif()
if(TARGET bluetile_raster)
  list(APPEND bluetile_components raster)
endif()

foreach(component ${bluetile_components})
  install(TARGETS bluetile_${component} EXPORT bluetile-${component}-targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT ${component}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT ${component}
    FILE_SET HEADERS DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT ${component})
  install(EXPORT bluetile-${component}-targets NAMESPACE bluetile:: DESTINATION ${bluetile_cmake_dir}
    COMPONENT ${component})
endforeach()

if(TARGET bluetile_images)
  install(TARGETS bluetile_oiio LIBRARY DESTINATION ${bluetile_plugin_dir} COMPONENT images)
  # The library dlopens the plugin by bare name: a program linking the installed (static)
  # library gets the plugin folder in its RUNPATH; a shared libbluetile_images has it in its own.
  target_link_options(bluetile_images INTERFACE
    $<INSTALL_INTERFACE:-Wl,-rpath,$<INSTALL_PREFIX>/${bluetile_plugin_dir}>)
  set_target_properties(bluetile_images PROPERTIES INSTALL_RPATH "$ORIGIN/bluetile")
endif()

if(TARGET bluetile)
  file(RELATIVE_PATH tool_to_plugin /prefix/${CMAKE_INSTALL_BINDIR} /prefix/${bluetile_plugin_dir})
  set_target_properties(bluetile PROPERTIES INSTALL_RPATH "$ORIGIN/${tool_to_plugin}")
  install(TARGETS bluetile RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tool)
endif()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/bluetileConfig.cmake.in
  ${PROJECT_BINARY_DIR}/bluetileConfig.cmake INSTALL_DESTINATION ${bluetile_cmake_dir})
# 0.x: a minor version may change the interface.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/bluetileConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/bluetileConfig.cmake ${PROJECT_BINARY_DIR}/bluetileConfigVersion.cmake
  DESTINATION ${bluetile_cmake_dir} COMPONENT core)

# pkg-config: one file per component, and bluetile.pc for all of them. Static libraries carry
# their dependencies in Libs (there is no shared object to carry them). The prefix is written
# absolute when installing (the one `cmake --install --prefix` names): the image plugin's RUNPATH
# must be absolute, and ${pcfiledir} is relative wherever PKG_CONFIG_PATH is, which gave a program
# that found its plugin only when run from the folder it was built in.
set(pc_prefix "@BLUETILE_PC_PREFIX@")  # left for install_pc_file below
set(pc_core_requires glm)
set(pc_core_libs "-pthread")
set(pc_images_requires bluetile-core)
list(TRANSFORM CMAKE_DL_LIBS PREPEND -l OUTPUT_VARIABLE pc_images_libs)
list(APPEND pc_images_libs "-Wl,-rpath,\${libdir}/bluetile")
set(pc_raster_requires "bluetile-images vulkan")
set(pc_raster_libs "")
set(pc_all_requires "")
# What bluetile/bluetile.h includes follows the components linked, as the CMake targets define it.
set(pc_core_cflags "")
set(pc_images_cflags " -DBLUETILE_WITH_IMAGES=1")
set(pc_raster_cflags " -DBLUETILE_WITH_RASTER=1")
foreach(component ${bluetile_components})
  set(pc_name bluetile-${component})
  set(pc_cflags "${pc_${component}_cflags}")
  set(pc_description "bluetile ${component} component")
  set(pc_requires ${pc_${component}_requires})
  # The plugin's RUNPATH is needed however the library is linked.
  set(pc_rpath ${pc_${component}_libs})
  set(pc_deps ${pc_${component}_libs})
  list(FILTER pc_rpath INCLUDE REGEX "rpath")
  list(FILTER pc_deps EXCLUDE REGEX "rpath")
  if(BUILD_SHARED_LIBS)
    set(pc_libs -lbluetile_${component} ${pc_rpath})
    set(pc_libs_private ${pc_deps})
  else()
    set(pc_libs -lbluetile_${component} ${pc_rpath} ${pc_deps})
    set(pc_libs_private "")
  endif()
  string(REPLACE ";" " " pc_libs "${pc_libs}")
  string(REPLACE ";" " " pc_libs_private "${pc_libs_private}")
  configure_file(${PROJECT_SOURCE_DIR}/cmake/bluetile.pc.in ${PROJECT_BINARY_DIR}/pkgconfig/${pc_name}.pc.in @ONLY)
  list(APPEND pc_all_requires ${pc_name})
endforeach()
set(pc_name bluetile)
set(pc_cflags "")
set(pc_description "bluetile: blue-noise sample points by Lloyd relaxation (every installed component)")
list(JOIN pc_all_requires " " pc_requires)
set(pc_libs "")
set(pc_libs_private "")
configure_file(${PROJECT_SOURCE_DIR}/cmake/bluetile.pc.in ${PROJECT_BINARY_DIR}/pkgconfig/bluetile.pc.in @ONLY)

# install_pc_file(NAME COMPONENT): at install time, NAME.pc with the install prefix filled in.
function(install_pc_file name component)
  set(template ${PROJECT_BINARY_DIR}/pkgconfig/${name}.pc.in)
  set(staged ${PROJECT_BINARY_DIR}/pkgconfig/installed/${name}.pc)
  install(CODE "
    set(BLUETILE_PC_PREFIX \"\${CMAKE_INSTALL_PREFIX}\")
    configure_file(\"${template}\" \"${staged}\" @ONLY)
    file(INSTALL DESTINATION \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/pkgconfig\" TYPE FILE FILES \"${staged}\")"
    COMPONENT ${component})
endfunction()
foreach(component ${bluetile_components})
  install_pc_file(bluetile-${component} ${component})
endforeach()
install_pc_file(bluetile core)

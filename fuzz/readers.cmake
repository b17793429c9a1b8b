# The sources behind the fuzz targets' readers, listed once: the fuzz build compiles them with
# libFuzzer's instrumentation (fuzz/CMakeLists.txt), and every test build links the same list into
# the corpus replay (tests/CMakeLists.txt). A reader that comes to call a source missing here then
# fails to link in the ordinary build too, not only in the fuzz build that CI runs last.
set(bluetile_fuzz_reader_sources
  ${PROJECT_SOURCE_DIR}/src/bluetile/core/input_file.cpp
  ${PROJECT_SOURCE_DIR}/src/bluetile/core/output_file.cpp
  ${PROJECT_SOURCE_DIR}/src/bluetile/core/point_file.cpp
  ${PROJECT_SOURCE_DIR}/src/bluetile/core/point_table.cpp
  ${PROJECT_SOURCE_DIR}/src/bluetile/core/rng.cpp
  ${PROJECT_SOURCE_DIR}/src/bluetile/core/text.cpp
  ${PROJECT_SOURCE_DIR}/src/bluetile/core/torus.cpp
  ${PROJECT_SOURCE_DIR}/src/bluetile/tiling/tile_set.cpp
  ${PROJECT_SOURCE_DIR}/src/bluetile/tiling/tile_set_file.cpp)
# Density-map images, on top of those: the reader, and the OpenImageIO plugin's loader.
set(bluetile_fuzz_image_sources
  ${PROJECT_SOURCE_DIR}/src/bluetile/core/density_grid.cpp
  ${PROJECT_SOURCE_DIR}/src/bluetile/core/process_limits.cpp
  ${PROJECT_SOURCE_DIR}/src/bluetile/io/density_map.cpp
  ${PROJECT_SOURCE_DIR}/src/bluetile/io/image_file.cpp)
# The targets: fuzz/<reader>_fuzzer.cpp each; density_map needs the images.
set(bluetile_fuzz_readers point_file tile_set tile_set_semantics point_table)

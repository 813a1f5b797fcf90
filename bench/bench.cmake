# Benchmarks (issue 6): Google Benchmark executables, built with GBL_BUILD_BENCH=ON (the default)
# and run by bench/run.sh. They are not registered with CTest: goals are read from their output,
# not asserted by timed tests.
#
#   codec_bench     CPU mirror: per-encoding and per-layout encode/decode throughput vs memcpy
#   gpu_pass_bench  G-buffer and lighting pass times per layout (Vulkan timestamp queries)
#   compare_bench   computeRunMetrics / FLIP at 1080p on synthetic images
#   png_bench       a 4K RGB PNG by the old stb encoder and by encodePng on one and several cores
function(gbl_bench name)
  cmake_parse_arguments(B "" "" "DEPS" ${ARGN})
  if(NOT EXISTS ${CMAKE_SOURCE_DIR}/bench/${name}.cpp)
    return()
  endif()
  add_executable(${name} bench/${name}.cpp)
  target_link_libraries(${name} PRIVATE ${B_DEPS} benchmark::benchmark)
endfunction()

gbl_bench(codec_bench DEPS gbl_encoding gbl_layout gbl_codec)
gbl_bench(gpu_pass_bench DEPS gbl_render gbl_layout gbl_codec gbl_image gbl_scene)
gbl_bench(compare_bench DEPS gbl_measure gbl_report)
gbl_bench(png_bench DEPS gbl_image)
if(TARGET png_bench)
  target_include_directories(png_bench PRIVATE ${CMAKE_SOURCE_DIR}/tests/support)  # the old encoder
endif()

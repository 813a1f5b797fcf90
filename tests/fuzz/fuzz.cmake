# The libFuzzer targets (scripts/fuzz.sh), built in the sanitizer build by clang (build-asan,
# scripts/test-sanitizers.sh): the libraries they reach carry libFuzzer's coverage counters
# (-fsanitize=fuzzer-no-link), so the fuzzers and the sanitized unit tests share one compilation
# of them instead of a second one of their own.
set(GBL_FUZZED_LIBRARIES gbl_base gbl_image gbl_scene gbl_encoding gbl_layout gbl_codec)
foreach(library IN LISTS GBL_FUZZED_LIBRARIES)
  target_compile_options(${library} PRIVATE -fsanitize=fuzzer-no-link)
endforeach()
function(gbl_fuzzer name)
  add_executable(${name} EXCLUDE_FROM_ALL tests/fuzz/${name}.cpp)
  target_link_libraries(${name} PRIVATE ${ARGN})
  target_compile_options(${name} PRIVATE -fsanitize=fuzzer)
  target_link_options(${name} PRIVATE -fsanitize=fuzzer)
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz)
endfunction()
gbl_fuzzer(fuzz_layout_parser gbl_layout gbl_codec)  # the target also runs `layouts export` on what check accepts
gbl_fuzzer(fuzz_gltf_loader gbl_scene)

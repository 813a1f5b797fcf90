# The layering of src/ (docs/ARCHITECTURE.md) is enforced by include paths: a library sees only
# its own folder and the folders of the libraries it links. These tests prove it: each compiles a
# file of a lower library that includes a higher folder's header, and passes only when the
# compiler says the header cannot be found. A positive probe (an allowed include) must compile,
# so a broken probe set-up cannot pass for the wrong reason.
function(gbl_layering_probe name library header expect)
  set(PROBE_LIBRARY ${library})
  set(PROBE_HEADER ${header})
  configure_file(${CMAKE_SOURCE_DIR}/tests/layering/include_probe.cpp.in
                 ${CMAKE_BINARY_DIR}/layering/${name}.cpp @ONLY)
  add_library(${name} OBJECT EXCLUDE_FROM_ALL ${CMAKE_BINARY_DIR}/layering/${name}.cpp)
  target_link_libraries(${name} PRIVATE ${library})
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} --build ${CMAKE_BINARY_DIR} --target ${name})
  if(expect STREQUAL "refused")
    # GCC and Clang both print "<header>: No such file or directory" / "'<header>' file not found".
    set_tests_properties(${name} PROPERTIES LABELS unit RESOURCE_LOCK layering_build
      PASS_REGULAR_EXPRESSION "${header}: No such file or directory|'${header}' file not found")
  else()
    set_tests_properties(${name} PROPERTIES LABELS unit RESOURCE_LOCK layering_build)
  endif()
endfunction()

gbl_layering_probe(layering_base_cannot_see_image gbl_base image.h refused)
gbl_layering_probe(layering_image_cannot_see_scene gbl_image scene.h refused)
gbl_layering_probe(layering_scene_cannot_see_layout gbl_scene layout.h refused)
gbl_layering_probe(layering_layout_cannot_see_codec gbl_layout wiring_codegen.h refused)
gbl_layering_probe(layering_measure_cannot_see_render gbl_measure renderer.h refused)
gbl_layering_probe(layering_report_cannot_see_cli gbl_report cli.h refused)
gbl_layering_probe(layering_search_cannot_see_render gbl_search renderer.h refused)
gbl_layering_probe(layering_search_cannot_see_cli gbl_search cli.h refused)
gbl_layering_probe(layering_search_sees_codec gbl_search cpu_codec.h allowed)
gbl_layering_probe(layering_render_sees_codec gbl_render wiring_codegen.h allowed)
gbl_layering_probe(layering_measure_cannot_see_evaluate gbl_measure gpu_evaluator.h refused)
gbl_layering_probe(layering_render_cannot_see_evaluate gbl_render gpu_evaluator.h refused)
gbl_layering_probe(layering_evaluate_sees_measure gbl_evaluate run_metrics.h allowed)
# app/ runs the comparison and the search below the command line: it cannot see cli/'s headers
# (its flags, its console), and the libraries it uses cannot see its own.
gbl_layering_probe(layering_app_cannot_see_cli gbl_app cli.h refused)
gbl_layering_probe(layering_app_cannot_see_compare_flags gbl_app compare_flags.h refused)
gbl_layering_probe(layering_app_cannot_see_console gbl_app compare_console.h refused)
gbl_layering_probe(layering_report_cannot_see_app gbl_report compare_api.h refused)
gbl_layering_probe(layering_search_cannot_see_app gbl_search search_api.h refused)
gbl_layering_probe(layering_evaluate_cannot_see_app gbl_evaluate compare_session.h refused)
gbl_layering_probe(layering_app_sees_search gbl_app layout_search.h allowed)
gbl_layering_probe(layering_cli_sees_app gbl_cli compare_api.h allowed)

# Each test: gbl_test(<folder>/<file name without .cpp> LABELS unit|gpu DEPS <libraries>).
# Every test links gbl_test_support; gbl_test_support_layout, gbl_test_support_codec and
# gbl_test_support_vk (gpu tests only) are named where a test uses them (tests/support/support.cmake).
# tests/ mirrors src/: a test lives in the folder of the library it tests.
# "unit" tests use no Vulkan and also run under the sanitizer build; "gpu" tests need a driver.
gbl_test(base/stage_clock_test LABELS unit DEPS gbl_base)
gbl_test(base/parallel_for_test LABELS unit DEPS gbl_base)
gbl_test(base/background_writer_test LABELS unit DEPS gbl_base)
gbl_test(base/host_heap_test LABELS unit DEPS gbl_base)
gbl_test(base/disk_cache_test LABELS unit DEPS gbl_base)
gbl_test(base/memory_budget_test LABELS unit DEPS gbl_base)
gbl_test(base/escape_text_test LABELS unit DEPS gbl_base)
gbl_test(base/output_over_input_test LABELS unit DEPS gbl_base)
gbl_test(base/special_output_test LABELS unit DEPS gbl_base)  # devices, FIFOs, sockets: never replaced
gbl_test(image/image_io_test LABELS unit DEPS gbl_image gbl_scene)  # reads environment maps too
gbl_test(image/exr_half_test LABELS unit DEPS gbl_image)
gbl_test(image/tone_map_test LABELS unit DEPS gbl_image)
gbl_test(image/auto_exposure_test LABELS unit DEPS gbl_image)  # UE4's histogram auto-exposure
gbl_test(image/color_map_test LABELS unit DEPS gbl_image)
gbl_test(image/png_writer_test LABELS unit DEPS gbl_image)
gbl_test(image/pfm_io_test LABELS unit DEPS gbl_image gbl_measure)  # the Sample Viewer's float output; diff's kind rule
gbl_test(image/temporal_resolve_test LABELS unit DEPS gbl_image gbl_encoding)  # compare --temporal: resolve, Halton, dithers over frames
gbl_test(gpu/shader_compiler_test LABELS unit DEPS gbl_gpu)
gbl_test(gpu/shader_cache_test LABELS unit DEPS gbl_gpu)
gbl_test(scene/environment_test LABELS unit DEPS gbl_scene)
gbl_test(scene/scene_models_test LABELS unit DEPS gbl_scene nlohmann_json::nlohmann_json)
gbl_test(scene/gltf_loader_test LABELS unit DEPS gbl_scene nlohmann_json::nlohmann_json)
gbl_test(scene/scene_geometry_test LABELS unit DEPS gbl_scene nlohmann_json::nlohmann_json)
gbl_test(scene/default_scene_test LABELS unit DEPS gbl_scene)
gbl_test(scene/light_coverage_test LABELS unit DEPS gbl_scene)  # compare --lighting volumes: light volumes per pixel
gbl_test(encoding/encodings_test LABELS unit DEPS gbl_encoding gbl_measure)  # normals; checks their stats too
gbl_test(encoding/scalar_encodings_test LABELS unit DEPS gbl_encoding gbl_measure)
gbl_test(encoding/color_encodings_test LABELS unit DEPS gbl_encoding gbl_measure)
gbl_test(encoding/engine_encodings_test LABELS unit DEPS gbl_encoding gbl_measure)  # RGB9E5, gamma 2.2, Bevy / Unity / Killzone normals, Killzone 2 power
gbl_test(encoding/niagara_encodings_test LABELS unit DEPS gbl_encoding gbl_measure)  # emissive/albedo ratio, dithered octahedral
gbl_test(encoding/engine_packings_test LABELS unit DEPS gbl_codec)  # each engine's published packing, reimplemented, vs the codec's words
gbl_test(encoding/bevy_packings_test LABELS unit DEPS gbl_codec gbl_layout)  # Bevy's native and WebGL2 packings, reimplemented
gbl_test(encoding/layer_packings_test LABELS unit DEPS gbl_codec gbl_layout)  # the material layers as Bevy, HDRP and UE pack them, reimplemented
gbl_test(encoding/layer_encodings_gpu_test LABELS gpu DEPS gbl_codec gbl_layout gbl_test_support_vk)  # their GLSL twins at the ties, and UE's bottom-normal delta
gbl_test(encoding/encodings_fast_test LABELS unit DEPS gbl_encoding)
gbl_test(encoding/light_buffer_encodings_test LABELS unit DEPS gbl_encoding)
gbl_test(encoding/codec_tables_test LABELS unit DEPS gbl_encoding gbl_gpu)  # the tables buffer = the shaders' arrays
gbl_test(layout/layout_parser_test LABELS unit DEPS gbl_layout)
gbl_test(layout/layout_syntax_test LABELS unit DEPS gbl_layout)
gbl_test(layout/layout_reads_test LABELS unit DEPS gbl_layout)  # encodings that read another attribute (niagara)
gbl_test(layout/shading_model_layout_test LABELS unit DEPS gbl_layout gbl_test_support_layout)  # the selector, conditional fields
gbl_test(layout/visibility_layout_test LABELS unit DEPS gbl_layout gbl_test_support_layout)
gbl_test(layout/layout_mutants_test LABELS unit TIMEOUT 900 DEPS gbl_codec gbl_gpu gbl_render)  # what `check` accepts compiles
gbl_test(layout/layout_files_test LABELS unit DEPS gbl_cli)  # describeLayout is `layouts show`'s
gbl_test(layout/layout_provenance_test LABELS unit DEPS gbl_cli gbl_test_support_layout)  # [sources], from / status, `layouts show`
gbl_test(codec/wiring_codegen_test LABELS unit DEPS gbl_codec gbl_cli gbl_test_support_codec)
gbl_test(codec/cpu_codec_test LABELS unit DEPS gbl_codec gbl_test_support_codec)
gbl_test(codec/shading_model_codec_test LABELS unit DEPS gbl_codec gbl_test_support_codec)  # the selector's words and decode, from its statement
gbl_test(codec/cpu_codec_properties_test LABELS unit DEPS gbl_codec gbl_test_support_layout)
gbl_test(codec/visibility_ids_test LABELS unit DEPS gbl_codec gbl_test_support_layout)  # Nanite's and Bevy's 64-bit ids, reimplemented, vs the packing
gbl_test(codec/gpu_cpu_bits_test LABELS gpu TIMEOUT 900 DEPS gbl_codec gbl_render gbl_test_support_vk)  # every layout on the GPU: 150 s alone
gbl_test(codec/visibility_bits_test LABELS gpu DEPS gbl_codec gbl_render gbl_test_support_vk)  # the ids' GLSL vs its C++ twin
gbl_test(codec/light_buffer_bits_test LABELS gpu DEPS gbl_codec gbl_render gbl_test_support_vk)
gbl_test(codec/layout_export_test LABELS unit DEPS gbl_codec gbl_gpu gbl_test_support_layout)  # HLSL / GLSL export: compiles, names, exact UNORM values
gbl_test(codec/export_tables_test LABELS unit DEPS gbl_codec gbl_gpu)  # the tables as select trees vs the C++ twins
gbl_test(codec/layout_export_gpu_test LABELS gpu TIMEOUT 900 DEPS gbl_codec gbl_render gbl_test_support_vk)  # the export on lavapipe: real formats vs the CPU mirror
if(TARGET layout_export_gpu_test)  # every shipped layout, in two halves that ctest -j2 runs side by side
  set_tests_properties(layout_export_gpu_test PROPERTIES ENVIRONMENT "GBL_VALIDATION=1;GBL_EXPORT_TEST_SHARD=0/2")
  add_test(NAME layout_export_gpu_test_2 COMMAND layout_export_gpu_test)
  set_tests_properties(layout_export_gpu_test_2 PROPERTIES LABELS gpu TIMEOUT 900
    ENVIRONMENT "GBL_VALIDATION=1;GBL_EXPORT_TEST_SHARD=1/2")
endif()
gbl_test(shading/brdf_test LABELS unit DEPS gbl_shading)
gbl_test(shading/brdf_layers_test LABELS unit DEPS gbl_shading)  # clear coat, sheen, anisotropy vs the specifications
gbl_test(shading/brdf_gltf_test LABELS unit DEPS gbl_shading)  # --brdf gltf vs glTF 2.0 Appendix B, written from the text
gbl_test(shading/sheen_albedo_test LABELS unit DEPS gbl_shading)  # the sheen albedo table vs brute force
gbl_test(shading/ibl_layers_test LABELS unit DEPS gbl_shading)  # the layered ground truth vs a quadrature
gbl_test(shading/ibl_math_test LABELS unit DEPS gbl_shading)
gbl_test(shading/ground_truth_mis_test LABELS unit DEPS gbl_shading)
gbl_test(shading/brdf_lut_test LABELS unit DEPS gbl_shading gbl_base)
gbl_test(shading/ibl_gpu_test LABELS gpu DEPS gbl_render gbl_shading gbl_test_support_vk)
gbl_test(shading/ibl_ground_truth_test LABELS gpu DEPS gbl_render gbl_shading gbl_test_support_vk)
gbl_test(shading/ibl_layers_gpu_test LABELS gpu DEPS gbl_shading gbl_test_support_vk)  # the layers' GLSL vs their C++ twins
gbl_test(shading/brdf_gltf_gpu_test LABELS gpu DEPS gbl_shading gbl_test_support_vk)  # --brdf gltf GLSL vs its C++ twin
gbl_test(render/render_test LABELS gpu DEPS gbl_render gbl_test_support_vk)
gbl_test(render/layers_render_test LABELS gpu DEPS gbl_render gbl_test_support_vk)  # the layers in every IBL mode, dropped by a layout, the forward mask
gbl_test(render/srgb_texture_test LABELS gpu DEPS gbl_render gbl_test_support_vk)  # sRGB textures decoded as IEC 61966-2-1 says
gbl_test(render/texture_mip_cache_test LABELS gpu DEPS gbl_render gbl_test_support_vk)
gbl_test(render/visibility_test LABELS gpu DEPS gbl_render gbl_test_support_vk)
gbl_test(render/pipeline_reuse_test LABELS gpu DEPS gbl_render gbl_layout gbl_test_support_vk)
gbl_test(render/render_band_test LABELS gpu DEPS gbl_render gbl_layout gbl_test_support_vk)
gbl_test(render/memory_recycler_test LABELS gpu DEPS gbl_render gbl_layout gbl_test_support_vk)
gbl_test(render/cpu_decode_test LABELS gpu DEPS gbl_render gbl_layout gbl_test_support_vk)  # the read-back on the CPU codec vs the decode pass
gbl_test(evaluate/histogram_test LABELS unit DEPS gbl_evaluate)
gbl_test(evaluate/eval_profile_test LABELS unit DEPS gbl_evaluate)
gbl_test(evaluate/gpu_evaluator_test LABELS gpu DEPS gbl_evaluate gbl_codec gbl_layout gbl_test_support_vk)
gbl_test(evaluate/gpu_evaluator_layers_test LABELS gpu DEPS gbl_evaluate gbl_render gbl_codec gbl_layout gbl_test_support_vk)  # issue 40: the layers on the device
gbl_test(evaluate/gpu_evaluator_band_test LABELS gpu DEPS gbl_evaluate gbl_codec gbl_layout gbl_test_support_vk)
gbl_test(measure/metrics_test LABELS unit DEPS gbl_measure)
gbl_test(measure/flip_test LABELS unit DEPS gbl_measure)
gbl_test(measure/flip_mean_test LABELS unit DEPS gbl_measure)  # the mean against an exact sum, and NVIDIA's float sum
gbl_test(measure/run_metrics_test LABELS unit DEPS gbl_measure)
gbl_test(measure/layer_metrics_test LABELS unit DEPS gbl_measure)  # issue 40: the layers measured
gbl_test(measure/float_sort_test LABELS unit DEPS gbl_measure)
gbl_test(measure/significance_test LABELS unit DEPS gbl_measure)  # the sign-flip test: Fisher's Zea mays
gbl_test(measure/pair_memo_test LABELS unit DEPS gbl_measure)
gbl_test(measure/encoding_stats_test LABELS unit DEPS gbl_measure)
gbl_test(measure/bandwidth_test LABELS unit DEPS gbl_measure gbl_layout)
gbl_test(measure/framebuffer_compression_test LABELS unit DEPS gbl_measure gbl_layout gbl_encoding)  # container arithmetic, calibration vs published GPUs
gbl_test(measure/effective_bandwidth_test LABELS unit DEPS gbl_measure gbl_layout)  # tile fits, lighting reads, traffic per GPU class
gbl_test(measure/view_content_test LABELS unit DEPS gbl_measure)  # views with nothing to measure
gbl_test(measure/png16_diff_test LABELS unit DEPS gbl_measure)  # 16-bit PNGs at 16 bits
gbl_test(report/report_test LABELS unit DEPS gbl_report)
gbl_test(report/report_layers_test LABELS unit DEPS gbl_report nlohmann_json::nlohmann_json)  # issue 40: the layers in the report
gbl_test(report/report_bandwidth_test LABELS unit DEPS gbl_report gbl_layout)  # effective bytes per GPU class in json / csv / html
gbl_test(report/visibility_verdict_test LABELS unit DEPS gbl_report)
gbl_test(report/budget_verdict_test LABELS unit DEPS gbl_report)
gbl_test(report/suite_verdict_test LABELS unit DEPS gbl_report)  # the verdict across scenes, agreement in words
gbl_test(report/rank_agreement_test LABELS unit DEPS gbl_report)  # Kendall's tau, tied ranks
gbl_test(report/plot_labels_test LABELS unit DEPS gbl_report)
gbl_test(report/report_html_glance_test LABELS unit DEPS gbl_report)
gbl_test(report/report_atlas_test LABELS unit DEPS gbl_report)
gbl_test(report/temporal_report_test LABELS unit DEPS gbl_report)  # --temporal N in report.json / csv / html
gbl_test(report/report_browser_test LABELS unit DEPS gbl_report)
gbl_test(report/error_images_test LABELS unit DEPS gbl_report)
# tools/gltf-viewer: the Khronos glTF Sample Viewer in headless Chromium (issue 45), held to the glTF
# specification's BRDF; skipped, like report_browser_test, where Chromium, Node or the package is absent.
gbl_test(tools/gltf_viewer_test LABELS unit DEPS gbl_image nlohmann_json::nlohmann_json)
if(TARGET gltf_viewer_test)
  target_compile_definitions(gltf_viewer_test PRIVATE GBL_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
endif()
# The float reference against the Sample Viewer on a scene of its own (scripts/crosscheck.sh).
gbl_test(tools/crosscheck_test LABELS gpu DEPS gbufferlab gbl_image nlohmann_json::nlohmann_json)
if(TARGET crosscheck_test)
  target_compile_definitions(crosscheck_test PRIVATE GBL_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
endif()
gbl_test(search/layout_packer_test LABELS unit DEPS gbl_search gbl_measure)
gbl_test(search/cpu_reshade_test LABELS unit DEPS gbl_search)
gbl_test(search/layout_search_test LABELS unit DEPS gbl_search)
gbl_test(search/search_constraints_test LABELS unit DEPS gbl_search)  # constraints, --min-bits, the every-metric front, trades
gbl_test(search/search_gpu_test LABELS gpu DEPS gbl_search gbl_render gbl_app gbl_test_support_vk)  # fast evaluation vs full renders
gbl_test(app/compare_bands_test LABELS unit DEPS gbl_app)
gbl_test(app/scene_suite_test LABELS unit DEPS gbl_app)  # --scene and suite files, refused before rendering
gbl_test(app/bundled_scenes_test LABELS unit DEPS gbl_app)  # scenes/: licences, provenance, the default suite
gbl_test(app/search_report_test LABELS unit DEPS gbl_app nlohmann_json::nlohmann_json)  # confirmation over several scenes
# The comparison and the search through the library's API, in this process: no command line.
gbl_test(app/app_api_test LABELS gpu DEPS gbl_app nlohmann_json::nlohmann_json)
gbl_test(cli/search_cli_test LABELS gpu DEPS gbufferlab)
gbl_test(cli/compare_flags_test LABELS unit DEPS gbl_cli)  # compare's default: the bundled suite
gbl_test(cli/cli_test LABELS gpu DEPS gbufferlab gbl_report gbl_image nlohmann_json::nlohmann_json)
gbl_test(cli/compare_scenes_cli_test LABELS gpu DEPS gbufferlab gbl_image nlohmann_json::nlohmann_json)  # several scenes
gbl_test(cli/compare_bands_cli_test LABELS gpu DEPS gbufferlab nlohmann_json::nlohmann_json)
gbl_test(cli/compare_temporal_cli_test LABELS gpu DEPS gbufferlab nlohmann_json::nlohmann_json)  # --temporal N
gbl_test(cli/compare_layers_cli_test LABELS gpu DEPS gbufferlab nlohmann_json::nlohmann_json)  # issue 40: the layers measured
gbl_test(cli/nothing_measured_cli_test LABELS gpu DEPS gbufferlab nlohmann_json::nlohmann_json)  # views with nothing to measure
gbl_test(cli/diff_cli_test LABELS gpu DEPS gbufferlab gbl_measure gbl_image nlohmann_json::nlohmann_json)
# Hostile input, run as the executable and measured (peak memory, time); refusals need no driver.
gbl_test(cli/diff_bounds_cli_test LABELS unit DEPS gbufferlab gbl_measure gbl_image nlohmann_json::nlohmann_json)
gbl_test(cli/input_bounds_cli_test LABELS unit DEPS gbufferlab gbl_render gbl_image)
gbl_test(cli/run_names_cli_test LABELS unit DEPS gbufferlab gbl_base)
gbl_test(cli/messages_cli_test LABELS unit DEPS gbufferlab gbl_base)
gbl_test(cli/viewer_job_cli_test LABELS gpu DEPS gbufferlab gbl_image)  # render --viewer-job, crossdiff
gbl_test(cli/outputs_cli_test LABELS unit DEPS gbufferlab gbl_image)  # special files, --out '', a failed stdout
include(tests/layering/layering.cmake)

# ctest -j runs the costliest tests first (COST: seconds they took on the 2-core CI machine, in
# Release on lavapipe or, for cpu_codec_test, under the sanitizers): a clean clone has no timings
# of its own, and a long test started last would leave the other core idle at the end.
foreach(test_cost IN ITEMS gpu_cpu_bits_test:300 layout_mutants_test:240 layout_export_gpu_test_2:200
                           cpu_codec_test:200 layout_export_gpu_test:110 encodings_fast_test:60 cli_test:50
                           compare_bands_cli_test:45 layout_export_test:45 render_test:40 ibl_gpu_test:40
                           report_browser_test:35 gltf_viewer_test:26 crosscheck_test:10)
  string(REPLACE ":" ";" test_cost ${test_cost})
  list(GET test_cost 0 test_name)
  list(GET test_cost 1 cost)
  if(TEST ${test_name})
    set_tests_properties(${test_name} PROPERTIES COST ${cost})
  endif()
endforeach()

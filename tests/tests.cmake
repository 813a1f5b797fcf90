# Each test: gbl_test(<folder>/<file name without .cpp> LABELS unit|gpu DEPS <libraries>).
# tests/ mirrors src/: a test lives in the folder of the library it tests.
# "unit" tests use no Vulkan and also run under the sanitizer build; "gpu" tests need a driver.
gbl_test(base/stage_clock_test LABELS unit DEPS gbl_base)
gbl_test(image/image_io_test LABELS unit DEPS gbl_image gbl_scene)  # reads environment maps too
gbl_test(image/tone_map_test LABELS unit DEPS gbl_image)
gbl_test(image/color_map_test LABELS unit DEPS gbl_image)
gbl_test(gpu/shader_compiler_test LABELS unit DEPS gbl_gpu)
gbl_test(gpu/shader_cache_test LABELS unit DEPS gbl_gpu)
gbl_test(scene/environment_test LABELS unit DEPS gbl_scene)
gbl_test(scene/scene_test LABELS unit DEPS gbl_scene nlohmann_json::nlohmann_json)
gbl_test(scene/default_scene_test LABELS unit DEPS gbl_scene)
gbl_test(encoding/encodings_test LABELS unit DEPS gbl_encoding gbl_measure)  # checks the stats of each encoding too
gbl_test(layout/layout_parser_test LABELS unit DEPS gbl_layout)
gbl_test(layout/layout_mutants_test LABELS unit DEPS gbl_codec gbl_gpu)  # what `check` accepts compiles
gbl_test(layout/layout_files_test LABELS unit DEPS gbl_cli)  # describeLayout is `layouts show`'s
gbl_test(codec/wiring_codegen_test LABELS unit DEPS gbl_codec gbl_cli)
gbl_test(codec/cpu_codec_test LABELS unit DEPS gbl_codec)
gbl_test(codec/gpu_cpu_bits_test LABELS gpu DEPS gbl_codec gbl_render)
gbl_test(shading/brdf_test LABELS unit DEPS gbl_shading)
gbl_test(shading/ibl_math_test LABELS unit DEPS gbl_shading)
gbl_test(shading/ibl_gpu_test LABELS gpu DEPS gbl_render gbl_shading)
gbl_test(render/render_test LABELS gpu DEPS gbl_render)
gbl_test(measure/metrics_test LABELS unit DEPS gbl_measure)
gbl_test(measure/flip_test LABELS unit DEPS gbl_measure)
gbl_test(measure/run_metrics_test LABELS unit DEPS gbl_measure)
gbl_test(measure/encoding_stats_test LABELS unit DEPS gbl_measure)
gbl_test(measure/bandwidth_test LABELS unit DEPS gbl_measure gbl_layout)
gbl_test(report/report_test LABELS unit DEPS gbl_report)
gbl_test(report/report_browser_test LABELS unit DEPS gbl_report)
gbl_test(report/error_images_test LABELS unit DEPS gbl_report)
gbl_test(cli/cli_test LABELS gpu DEPS gbufferlab nlohmann_json::nlohmann_json)

# Each test: gbl_test(<file name without .cpp> LABELS unit|gpu DEPS <modules>).
# "unit" tests use no Vulkan and also run under the sanitizer build; "gpu" tests need a driver.
gbl_test(image_io_test LABELS unit DEPS gbl_imageio)
gbl_test(environment_test LABELS unit DEPS gbl_imageio)
gbl_test(tone_map_test LABELS unit DEPS gbl_imageio)
gbl_test(brdf_test LABELS unit DEPS gbl_shading)
gbl_test(ibl_math_test LABELS unit DEPS gbl_shading)
gbl_test(metrics_test LABELS unit DEPS gbl_metrics)
gbl_test(flip_test LABELS unit DEPS gbl_metrics)
gbl_test(color_map_test LABELS unit DEPS gbl_metrics)
gbl_test(scene_test LABELS unit DEPS gbl_scene nlohmann_json::nlohmann_json)
gbl_test(default_scene_test LABELS unit DEPS gbl_scene)

# Each test: gbl_test(<file name without .cpp> LABELS unit|gpu DEPS <modules>).
# "unit" tests use no Vulkan and also run under the sanitizer build; "gpu" tests need a driver.

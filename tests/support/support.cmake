# The tests' support libraries (tests/support/), each compiled once and linked by the tests that
# use it; EXCLUDE_FROM_ALL: a build of the unit tests alone (-DGBL_TEST_LABELS=unit) builds no
# Vulkan scaffolding.
#   gbl_test_main            GoogleTest's main(), linked by every test
#   gbl_test_support         temporary folders and files, gbufferlab run from outside (cli_runner.h),
#                            layout texts (layout_text.h), UserError messages; linked by every test
#   gbl_test_support_layout  the shipped layouts read from the source tree (layout_files.h)
#   gbl_test_support_codec   random Surfaces and what the bit tests share (surface_support.h)
#   gbl_test_support_vk      the Vulkan tests' context and fixture, buffers, compute kernels,
#                            read-back and render settings (vk_test_support.h): gpu tests only
set(GBL_TEST_SUPPORT_DIR ${CMAKE_SOURCE_DIR}/tests/support)

add_library(gbl_test_main OBJECT EXCLUDE_FROM_ALL ${GBL_TEST_SUPPORT_DIR}/test_main.cpp)
target_link_libraries(gbl_test_main PUBLIC GTest::gtest)

add_library(gbl_test_support STATIC EXCLUDE_FROM_ALL
  ${GBL_TEST_SUPPORT_DIR}/cli_runner.cpp
  ${GBL_TEST_SUPPORT_DIR}/layout_text.cpp
  ${GBL_TEST_SUPPORT_DIR}/temp_dir.cpp
  ${GBL_TEST_SUPPORT_DIR}/user_error.cpp)
target_include_directories(gbl_test_support PUBLIC ${GBL_TEST_SUPPORT_DIR})
target_link_libraries(gbl_test_support PUBLIC gbl_base GTest::gtest nlohmann_json::nlohmann_json)
target_compile_definitions(gbl_test_support PRIVATE GBL_BINARY="$<TARGET_FILE:gbufferlab>")

add_library(gbl_test_support_layout STATIC EXCLUDE_FROM_ALL ${GBL_TEST_SUPPORT_DIR}/layout_files.cpp)
target_link_libraries(gbl_test_support_layout PUBLIC gbl_test_support gbl_layout)

add_library(gbl_test_support_codec STATIC EXCLUDE_FROM_ALL ${GBL_TEST_SUPPORT_DIR}/surface_support.cpp)
target_link_libraries(gbl_test_support_codec PUBLIC gbl_test_support_layout gbl_codec)

add_library(gbl_test_support_vk STATIC EXCLUDE_FROM_ALL ${GBL_TEST_SUPPORT_DIR}/vk_test_support.cpp)
target_link_libraries(gbl_test_support_vk PUBLIC gbl_test_support_codec gbl_render)

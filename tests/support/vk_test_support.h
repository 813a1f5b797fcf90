#pragma once
// One Vulkan context per test binary (device creation costs ~40 ms with validation), and a
// check that the test which ran did not raise a validation error.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "vk_context.h"

namespace gbl::test {

// lavapipe unless GBL_TEST_DEVICE names another device as --device does ("gpu", an index, a
// name): the GPU-against-CPU tests then check a real driver's arithmetic against the CPU oracle.
inline std::string testDeviceName() {
    const char* d = std::getenv("GBL_TEST_DEVICE");
    return d ? d : "";
}

inline VulkanContext& sharedContext() {
    static std::unique_ptr<VulkanContext> ctx =
        std::make_unique<VulkanContext>(DeviceOptions{testDeviceName(), true});
    return *ctx;
}

// Fails the current test when validation errors were reported during it.
class VulkanTest : public ::testing::Test {
protected:
    void SetUp() override { errorsBefore_ = sharedContext().validationErrorCount(); }
    void TearDown() override {
        EXPECT_EQ(sharedContext().validationErrorCount(), errorsBefore_)
            << "Vulkan validation error: " << sharedContext().firstValidationError();
    }
    VulkanContext& ctx() { return sharedContext(); }

private:
    int errorsBefore_ = 0;
};

}  // namespace gbl::test

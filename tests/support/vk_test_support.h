#pragma once
// One Vulkan context per test binary (device creation costs ~40 ms with validation), and a
// check that the test which ran did not raise a validation error.
#include <gtest/gtest.h>

#include <memory>

#include "vk_context.h"

namespace gbl::test {

inline VulkanContext& sharedContext() {
    static std::unique_ptr<VulkanContext> ctx = std::make_unique<VulkanContext>(DeviceOptions{"", true});
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

#pragma once
// Shared by the IBL tests on lavapipe (ibl_gpu_test.cpp: the pre-computation, the modes, the cache;
// ibl_ground_truth_test.cpp: the converged ground truth): their fixture and the constant environment
// (a white furnace when value = 1).
#include "environment_map.h"
#include "image.h"
#include "vk_test_support.h"

namespace gbl::ibl_test {

inline EnvironmentMap constantEnvironment(float value) {
    EnvironmentMap env;
    env.source = "constant";
    env.image = Image(64, 32, 3, value);
    return env;
}

class IblGpuTest : public test::VulkanTest {};

}  // namespace gbl::ibl_test

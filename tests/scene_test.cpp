#include <gtest/gtest.h>

#include "scene.h"

TEST(Placeholder, Builds) { SUCCEED(); }

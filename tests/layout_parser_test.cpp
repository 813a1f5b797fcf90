#include <gtest/gtest.h>
#include "layout.h"
TEST(Stub, Nothing) {}

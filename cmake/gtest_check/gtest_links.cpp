// Uses the standard library across the GoogleTest boundary (std::string in a test's message),
// which is where a libstdc++-built GoogleTest and a libc++ build disagree.
#include <gtest/gtest.h>

#include <string>

TEST(Links, WithThisStandardLibrary) { EXPECT_EQ(std::string("a") + "b", "ab"); }

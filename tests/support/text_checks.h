// Checks on generated text (gnuplot scripts, HTML pages).
#pragma once

#include <initializer_list>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace turbodyn::testing {

/// `text` contains each of `parts`.
inline void expect_contains(const std::string& text, std::initializer_list<std::string> parts) {
  for (const std::string& p : parts) EXPECT_THAT(text, ::testing::HasSubstr(p));
}

}  // namespace turbodyn::testing

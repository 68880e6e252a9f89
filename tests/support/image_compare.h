#pragma once
// Image assertions for tests: on failure they write the image, the reference
// and their difference under IGI_TEST_OUTPUT_DIR so a person can look.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "image/image.h"

namespace igi::test {

std::string output_path(const std::string& file_name);
// A fresh, empty folder IGI_TEST_OUTPUT_DIR/group/<the running test's name>.
std::filesystem::path fresh_test_dir(const std::string& group);
// Writes NAME.exr/.png, NAME-reference.* and NAME-diff.png.
void write_failure_images(const std::string& name, const Image& image, const Image& reference);
// Bit-for-bit equality; on failure reports the first differing pixel.
::testing::AssertionResult images_identical(const std::string& name, const Image& image, const Image& reference);
// relMSE below a bound.
::testing::AssertionResult images_close(const std::string& name, const Image& image, const Image& reference,
                                        double max_rel_mse);

}  // namespace igi::test

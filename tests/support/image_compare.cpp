#include "support/image_compare.h"

#include <cstring>
#include <filesystem>

#include "image/metrics.h"

namespace igi::test {

std::string output_path(const std::string& file_name) {
  std::filesystem::create_directories(IGI_TEST_OUTPUT_DIR);
  return std::string(IGI_TEST_OUTPUT_DIR) + "/" + file_name;
}

std::filesystem::path fresh_test_dir(const std::string& group) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::path(IGI_TEST_OUTPUT_DIR) / group / info->name();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

void write_failure_images(const std::string& name, const Image& image, const Image& reference) {
  write_image(image, output_path(name + ".exr"));
  write_image(image, output_path(name + ".png"));
  write_image(reference, output_path(name + "-reference.exr"));
  write_image(reference, output_path(name + "-reference.png"));
  if (image.width == reference.width && image.height == reference.height)
    write_image(abs_difference(image, reference), output_path(name + "-diff.png"), ToneMapping{10.0f});
}

::testing::AssertionResult images_identical(const std::string& name, const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height)
    return ::testing::AssertionFailure() << name << ": sizes differ";
  for (size_t i = 0; i < image.pixels.size(); ++i)
    if (std::memcmp(&image.pixels[i], &reference.pixels[i], sizeof(glm::vec3)) != 0) {
      write_failure_images(name, image, reference);
      return ::testing::AssertionFailure()
             << name << ": first difference at pixel (" << i % image.width << ", " << i / image.width
             << "); images written to " << output_path(name + "*");
    }
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult images_close(const std::string& name, const Image& image, const Image& reference,
                                        double max_rel_mse) {
  double e = rel_mse(image, reference);
  if (e <= max_rel_mse) return ::testing::AssertionSuccess() << name << ": relMSE " << e;
  write_failure_images(name, image, reference);
  return ::testing::AssertionFailure() << name << ": relMSE " << e << " > " << max_rel_mse
                                       << "; images written to " << output_path(name + "*");
}

}  // namespace igi::test

#include "cli/option_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "build_id.h"

namespace igi::cli {
namespace {

// Every float option parses the same way: the whole text, as strtod reads it.
bool read_number(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

bool read_side(const std::string& text, int max_side, int& side) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), side);
  return !text.empty() && error == std::errc() && end == text.data() + text.size() && side >= 1 && side <= max_side;
}

CLI::Validator image_size(int max_side) {
  return CLI::Validator(
      [max_side](std::string& text) -> std::string {
        const size_t x = text.find('x');
        int w = 0, h = 0;
        if (x != std::string::npos && read_side(text.substr(0, x), max_side, w) &&
            read_side(text.substr(x + 1), max_side, h))
          return {};
        return "expected WxH, each from 1 to " + std::to_string(max_side) + ", got '" + text + "'";
      },
      "");
}

void parse_size(const std::string& text, int& width, int& height) {
  const size_t x = text.find('x');
  width = std::stoi(text.substr(0, x));
  height = std::stoi(text.substr(x + 1));
}

}  // namespace

CLI::Validator number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double v = 0;
        return read_number(text, v) && std::isfinite(v) ? "" : "expected a number, got '" + text + "'";
      },
      "");
}

CLI::Validator non_negative_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double v = 0;
        return read_number(text, v) && v >= 0.0 ? "" : "expected a non-negative number, got '" + text + "'";
      },
      "");
}

CLI::Validator one_of(std::vector<std::string> words) {
  std::string expected = "expected ";
  for (size_t i = 0; i < words.size(); ++i)
    expected += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
  return CLI::Validator(
      [words, expected](std::string& text) -> std::string {
        if (std::find(words.begin(), words.end(), text) != words.end()) return {};
        return expected + ", got '" + text + "'";
      },
      "");
}

CLI::Validator bounded_number(double bound) {
  char expected[64];
  std::snprintf(expected, sizeof expected, "expected a number within +-%g, got '", bound);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0;
        return read_number(text, v) && std::abs(v) <= bound ? "" : expected + text + "'";
      },
      "");
}

namespace {

bool read_vec3(const std::string& text, double bound, glm::vec3& out) {
  size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const size_t comma = k < 2 ? text.find(',', start) : text.size();
    if (comma == std::string::npos) return false;
    double v = 0;
    if (!read_number(text.substr(start, comma - start), v) || !(std::abs(v) <= bound)) return false;
    out[k] = float(v);
    start = comma + 1;
  }
  return true;
}

}  // namespace

CLI::Option* add_vec3_option(CLI::App& app, const std::string& name, glm::vec3& out, double bound,
                             const std::string& help) {
  char expected[80];
  std::snprintf(expected, sizeof expected, "expected X,Y,Z, three numbers within +-%g, got '", bound);
  return app
      .add_option_function<std::string>(
          name, [&out, bound](const std::string& v) { read_vec3(v, bound, out); }, help)
      ->check(CLI::Validator(
          [=](std::string& text) -> std::string {
            glm::vec3 v;
            return read_vec3(text, bound, v) ? "" : expected + text + "'";
          },
          ""))
      ->type_name("X,Y,Z");
}

CLI::Option* add_sky_option(CLI::App& app, const std::string& name, std::optional<SkyChoice>& out, double bound,
                            const std::string& help) {
  auto read = [bound](const std::string& text, glm::vec3& c) {
    return read_vec3(text, bound, c) && c.x >= 0.0f && c.y >= 0.0f && c.z >= 0.0f;
  };
  char expected[112];
  std::snprintf(expected, sizeof expected, "expected R,G,B (three numbers from 0 to %g) or a map file, got '", bound);
  return app
      .add_option_function<std::string>(
          name,
          [&out, read](const std::string& v) {
            SkyChoice sky;
            if (!read(v, sky.radiance)) sky = SkyChoice{glm::vec3(1.0f), v};
            out = sky;
          },
          help)
      ->check(CLI::Validator(
          [=](std::string& text) -> std::string {
            glm::vec3 c;
            if (read(text, c)) return "";
            std::error_code error;
            if (std::filesystem::is_regular_file(text, error)) return "";
            return expected + text + "': " + (text.find(',') != std::string::npos ? "not a colour" : "no such file");
          },
          ""))
      ->type_name("R,G,B|FILE");
}

CLI::Option* add_size_option(CLI::App& app, const std::string& name, int& width, int& height, int max_side,
                             const std::string& help) {
  return app
      .add_option_function<std::string>(
          name, [&width, &height](const std::string& v) { parse_size(v, width, height); }, help)
      ->check(image_size(max_side))->type_name("WxH");
}

void take_last_by_default(CLI::App& app) {
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

void add_version_flag(CLI::App& app) {
  app.set_version_flag("--version", std::string(build_id()), "print the build id (what master and workers compare) and exit");
}

bool parse(CLI::App& app, std::vector<std::string> args) {
  std::reverse(args.begin(), args.end());  // CLI11 takes the arguments from the back
  try {
    app.parse(args);
  } catch (const CLI::CallForHelp&) {
    return false;
  } catch (const CLI::CallForVersion& e) {
    std::printf("%s\n", e.what());  // "igi-cluster <git describe> <compiler> <embree> isa=..."
    std::exit(0);
  } catch (const CLI::ExtrasError&) {
    const std::string first = app.remaining().front();
    const bool option = first.rfind("-", 0) == 0;
    throw OptionError((option ? "unknown option '" : "unexpected argument '") + first + "'");
  } catch (const CLI::ParseError& e) {
    throw OptionError(e.what());
  }
  return true;
}

void print_option_error(const std::string& program, const std::string& message) {
  std::fprintf(stderr, "%s: %s\nRun %s --help for the options.\n", program.c_str(), message.c_str(), program.c_str());
}

int run_program(const std::string& program, int usage_status, int error_status, const std::function<int()>& body) {
  try {
    return body();
  } catch (const OptionError& e) {
    print_option_error(program, e.what());
    return usage_status;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program.c_str(), e.what());
    return error_status;
  }
}

}  // namespace igi::cli

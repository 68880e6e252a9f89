#pragma once
// The programs' command lines, declared with CLI11: the checks every program
// shares, so that an option, its range and its help are written once, and a
// bad value is refused with one message that names the option and the value
// ("--threads: expected an integer >= 0 and <= 4096, got 'x'"; CLI11 puts the
// option's name in front of the checks' text).
#include <charconv>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "scene/load_scene.h"

namespace igi::cli {

inline constexpr int kMaxThreads = 4096;  // --threads, --worker-threads: 0 = all cores
inline constexpr int kMaxIoThreads = 64;  // --io-threads: ZeroMQ I/O threads

// A bad command line: the message names the option and the value. Programs
// print it after their name, with a hint to --help, and exit with their usage status.
struct OptionError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// An integer of type T (the whole text, no sign for unsigned types) in [min,
// max]; without bounds, any T (a RenderSettings field, whose range
// check_settings() owns).
template <class T>
CLI::Validator integer(T min = std::numeric_limits<T>::min(), T max = std::numeric_limits<T>::max()) {
  const bool any = min == std::numeric_limits<T>::min() && max == std::numeric_limits<T>::max();
  const std::string expected =
      any ? "expected an integer" : "expected an integer >= " + std::to_string(min) + " and <= " + std::to_string(max);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        T value{};
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        const bool whole = error == std::errc() && end == text.data() + text.size() && !text.empty();
        if (whole && value >= min && value <= max) return {};
        return expected + ", got '" + text + "'";
      },
      "");
}

CLI::Validator number();               // finite
CLI::Validator non_negative_number();  // >= 0 (infinity too, as before; NaN never)
// One of `words`: "expected auto, on or off, got 'x'".
CLI::Validator one_of(std::vector<std::string> words);
// An image size WxH (`name`: "--size" and the like) into `width` and `height`, both in [1, max_side].
CLI::Option* add_size_option(CLI::App& app, const std::string& name, int& width, int& height, int max_side,
                             const std::string& help);

// A number within +-bound (NaN and infinity fail): "expected a number within +-1e+09, got 'x'".
CLI::Validator bounded_number(double bound);
// A point or offset X,Y,Z (`name`: "--move-lights"), each a number within +-bound, into `out`.
CLI::Option* add_vec3_option(CLI::App& app, const std::string& name, glm::vec3& out, double bound,
                             const std::string& help);
// A sky (`name`: "--environment"): a colour R,G,B, each a number in [0,
// bound], or the path of a file that exists (an environment map), into `out`
// (set once given).
CLI::Option* add_sky_option(CLI::App& app, const std::string& name, std::optional<SkyChoice>& out, double bound,
                            const std::string& help);

// Options given twice: the last one counts (call before adding options).
void take_last_by_default(CLI::App& app);
// --version: prints the build id (build_id.h, what the handshake compares) and exits 0.
void add_version_flag(CLI::App& app);
// Parses `args` (argv[1] on) into the variables `app` was declared with.
// Returns false when --help was asked; throws OptionError for a bad command line.
bool parse(CLI::App& app, std::vector<std::string> args);

// The help text of the command line that `declare(app, options)` builds (the last of an option given twice counts).
template <class Options, class Declare>
std::string help(const std::string& about, const std::string& program, Declare declare) {
  Options options;
  CLI::App app(about, program);
  take_last_by_default(app);
  declare(app, options);
  return app.help();
}

// Declares the command line with `declare(app, options)` and parses `args` into `options` (the last of an
// option given twice counts);
// returns false when --help was asked, throws OptionError for a bad command line.
template <class Options, class Declare>
bool parse_into(Options& options, Declare declare, std::vector<std::string> args) {
  CLI::App app;
  take_last_by_default(app);
  declare(app, options);
  return parse(app, std::move(args));
}

// The one line a program prints for a bad command line, and the hint to --help.
void print_option_error(const std::string& program, const std::string& message);
// A program's main(): runs `body` (parse, build, run) and returns its status. A bad
// command line (OptionError) is printed by print_option_error() and returns
// `usage_status`; any other exception prints "PROGRAM: what" and returns `error_status`.
int run_program(const std::string& program, int usage_status, int error_status, const std::function<int()>& body);

}  // namespace igi::cli

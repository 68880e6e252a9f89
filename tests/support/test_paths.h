#pragma once
// Where the tests find the programs, their data and their output folder. The
// paths are written by CMake into one generated file (test_paths.cpp in the
// build folder), so that no other test file's compile command names a path:
// a compiler cache then serves the same objects to every clone of the tree.
// Force-included into every file of igi_tests (its precompiled headers).
namespace igi::test::paths {
extern const char* const kTestOutputDir;
extern const char* const kFlipDataDir;
extern const char* const kBadScenesDir;
extern const char* const kDataDir;
extern const char* const kFuzzRegressionsDir;
extern const char* const kRenderBinary;
extern const char* const kMasterBinary;
extern const char* const kViewBinary;
extern const char* const kWorkerBinary;
extern const char* const kSoakBinary;
extern const char* const kOffByOneLibm;
extern const char* const kWindowScriptsDir;
}  // namespace igi::test::paths

#define IGI_TEST_OUTPUT_DIR (::igi::test::paths::kTestOutputDir)
#define IGI_FLIP_DATA_DIR (::igi::test::paths::kFlipDataDir)
#define IGI_BAD_SCENES_DIR (::igi::test::paths::kBadScenesDir)
#define IGI_TEST_DATA_DIR (::igi::test::paths::kDataDir)  // tests/data: the sample scenes
#define IGI_FUZZ_REGRESSIONS_DIR (::igi::test::paths::kFuzzRegressionsDir)
#define IGI_RENDER_BINARY (::igi::test::paths::kRenderBinary)
#define IGI_MASTER_BINARY (::igi::test::paths::kMasterBinary)
#define IGI_VIEW_BINARY (::igi::test::paths::kViewBinary)
#define IGI_WORKER_BINARY (::igi::test::paths::kWorkerBinary)
#define IGI_SOAK_BINARY (::igi::test::paths::kSoakBinary)
#define IGI_OFF_BY_ONE_LIBM (::igi::test::paths::kOffByOneLibm)
#define IGI_WINDOW_SCRIPTS_DIR (::igi::test::paths::kWindowScriptsDir)

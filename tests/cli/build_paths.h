// Absolute paths of what the CLI tests run (the glintlab executable, the test plug-ins, the
// report fixtures), set by the build (tests/CMakeLists.txt) on build_paths.cpp alone: they differ
// between clones, so a unit that saw them would never hit the compiler cache of another clone.
#pragma once

namespace glintlab::cli_test {

extern const char* const kGlintlabExe;
extern const char* const kTestPlugin;                      // tests/plugin/example_plugin.cpp
extern const char* const kTestPluginWrongVersion;          // the same, built as version 0.0.1
extern const char* const kTestPluginBuiltinClash;          // tests/plugin/builtin_clash_plugin.cpp
extern const char* const kTestPluginMisspelledNotClaimed;  // misspelled_not_claimed_plugin.cpp
extern const char* const kTestPluginFaultyEval;            // tests/plugin/faulty_eval_plugin.cpp
extern const char* const kTestNotAPlugin;                  // tests/plugin/not_a_plugin.cpp
extern const char* const kTestPluginZirrKaplanyan;         // examples/zirr_kaplanyan/plugin.cpp
extern const char* const kReportFixtures;                  // tests/reports/fixtures
extern const char* const kVersion;                         // this build's glintlab version

}  // namespace glintlab::cli_test

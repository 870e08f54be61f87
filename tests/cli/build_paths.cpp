#include "cli/build_paths.h"

#if !defined(GLINTLAB_EXE) || !defined(GLINTLAB_TEST_PLUGIN) ||                              \
    !defined(GLINTLAB_TEST_PLUGIN_WRONG_VERSION) ||                                          \
    !defined(GLINTLAB_TEST_PLUGIN_BUILTIN_CLASH) ||                                          \
    !defined(GLINTLAB_TEST_PLUGIN_MISSPELLED_NOT_CLAIMED) ||                                 \
    !defined(GLINTLAB_TEST_PLUGIN_FAULTY_EVAL) ||                                            \
    !defined(GLINTLAB_TEST_NOT_A_PLUGIN) || !defined(GLINTLAB_TEST_PLUGIN_ZIRR_KAPLANYAN) || \
    !defined(GLINTLAB_REPORT_FIXTURES) || !defined(GLINTLAB_TEST_VERSION)
#error "the CLI tests' paths must be defined by the build (tests/CMakeLists.txt)"
#endif

namespace glintlab::cli_test {

const char* const kGlintlabExe = GLINTLAB_EXE;
const char* const kTestPlugin = GLINTLAB_TEST_PLUGIN;
const char* const kTestPluginWrongVersion = GLINTLAB_TEST_PLUGIN_WRONG_VERSION;
const char* const kTestPluginBuiltinClash = GLINTLAB_TEST_PLUGIN_BUILTIN_CLASH;
const char* const kTestPluginMisspelledNotClaimed = GLINTLAB_TEST_PLUGIN_MISSPELLED_NOT_CLAIMED;
const char* const kTestPluginFaultyEval = GLINTLAB_TEST_PLUGIN_FAULTY_EVAL;
const char* const kTestNotAPlugin = GLINTLAB_TEST_NOT_A_PLUGIN;
const char* const kTestPluginZirrKaplanyan = GLINTLAB_TEST_PLUGIN_ZIRR_KAPLANYAN;
const char* const kReportFixtures = GLINTLAB_REPORT_FIXTURES;
const char* const kVersion = GLINTLAB_TEST_VERSION;

}  // namespace glintlab::cli_test

// Where a test binary finds the project's files and the programs it runs.
//
// The values live in one generated source file per test binary
// (lcnc_test_paths() in tests/CMakeLists.txt), not in compile definitions
// of every file: then no other file's compiled form depends on where the
// checkout and the build tree are, and a second clone of the same sources
// reuses the compiler cache (scripts/test.sh). Every source of a test binary
// sees this header (force-included), so the names read as before.
#pragma once

namespace lcnc::test_paths {
const char* source_dir();    // the checkout
const char* binary_dir();    // the build tree
const char* lasercnc_exe();  // the programs the end-to-end tests run
const char* lasercncd_exe();
const char* lasercnc_devices_exe();
const char* lasercnc_hmi_exe();
const char* lupdate_exe();          // Qt Linguist's, for the translation test
const char* lasercnc_hal_module();  // the HAL component
}  // namespace lcnc::test_paths

#define LCNC_SOURCE_DIR (::lcnc::test_paths::source_dir())
#define LCNC_BINARY_DIR (::lcnc::test_paths::binary_dir())
#define LASERCNC_EXE (::lcnc::test_paths::lasercnc_exe())
#define LASERCNCD_EXE (::lcnc::test_paths::lasercncd_exe())
#define LASERCNC_DEVICES_EXE (::lcnc::test_paths::lasercnc_devices_exe())
#define LASERCNC_HMI_EXE (::lcnc::test_paths::lasercnc_hmi_exe())
#define LUPDATE_EXE (::lcnc::test_paths::lupdate_exe())
#define LASERCNC_HAL_MODULE (::lcnc::test_paths::lasercnc_hal_module())

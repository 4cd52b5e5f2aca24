// The folder a system test writes its decks, meshes and results into.
// ctest runs every test of a file as its own process, two at a time, so two tests of one
// file that wrote files of the same name into one folder raced (one read the other's
// half-written deck). Each test therefore gets a folder of its own:
// <build>/system_tests/<file's folder>/<Suite>.<Test> ('/' of parametrised names as '_').
// Outside a test (a suite's set-up) it is the file's folder itself.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

namespace stentor::testing {

inline std::filesystem::path test_dir(const std::string& folder) {
  std::filesystem::path dir = std::filesystem::path(STENTOR_BINARY_DIR) / "system_tests" / folder;
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  if (info == nullptr) return dir;
  std::string name = std::string(info->test_suite_name()) + "." + info->name();
  std::replace(name.begin(), name.end(), '/', '_');
  return dir / name;
}

}  // namespace stentor::testing

// Helpers shared by the test programs: where the shared data and the oracle are, temporary
// folders, and writing diff images on failure.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "tessera/core.h"

namespace tessera::test {

/// ../shared/data next to the source tree (or $TESSERA_SHARED/data); nullopt when absent.
std::optional<std::filesystem::path> shared_data_dir();
/// Path of PVRTexToolCLI configured at build time (or $TESSERA_PVRTEXTOOL); nullopt if missing.
std::optional<std::filesystem::path> pvrtextool();
/// A fresh, empty folder under the build tree for this test (removed at the next run).
std::filesystem::path temp_dir(const std::string& name);
/// Folder in the build tree where tests write diff images when they fail.
std::filesystem::path artifacts_dir();

}  // namespace tessera::test

/// Skips the current test with a message when the shared data folder is absent.
#define TESSERA_REQUIRE_SHARED_DATA(var)                                   \
  auto var##_opt = ::tessera::test::shared_data_dir();                     \
  if (!var##_opt) GTEST_SKIP() << "../shared/data not present; skipping"; \
  const std::filesystem::path var = *var##_opt

// SPDX-License-Identifier: GPL-3.0-or-later
//! Helpers shared by the tests: where the data is, temporary folders, and
//! running the `subfab` command.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace subfab::test {

//! Path of a file in the repository's data/ folder.
inline std::filesystem::path data_path(const std::string& name) {
  return std::filesystem::path(SUBFAB_DATA_DIR) / name;
}

//! The shared models folder: $SUBFAB_MODELS_DIR when set (a worktree whose
//! ../shared is not the models' parent), else ../shared/models beside the
//! checkout (present in CI).
inline std::filesystem::path models_dir() {
  if (const char* dir = std::getenv("SUBFAB_MODELS_DIR"); dir && *dir) return dir;
  return SUBFAB_MODELS_DIR;
}

//! Path of a file in the shared models folder.
inline std::filesystem::path models_path(const std::string& name) { return models_dir() / name; }

//! True when ../shared/models is there.
inline bool have_shared_models() {
  return std::filesystem::is_directory(models_dir());
}

//! A fresh, empty folder under the build tree, unique per test.
inline std::filesystem::path temp_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(info->test_suite_name()) + "." + info->name();
  for (char& c : name)
    if (c == '/') c = '_';
  auto dir = std::filesystem::path(SUBFAB_TEST_TMP_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

//! The whole content of a file ("" if it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

//! A path in double quotes, for run_subfab() argument strings.
//! (Appended, not "\"" + ...: GCC 12 warns -Wrestrict on that, a false positive.)
inline std::string quoted(const std::filesystem::path& path) {
  std::string out = "\"";
  out += path.string();
  out += '"';
  return out;
}

#ifdef SUBFAB_BINARY
//! Result of running the subfab command.
struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr, interleaved
};

//! Runs `subfab <args>` through the shell (args are pasted as they are:
//! quote paths yourself) and captures its output.
inline CommandResult run_subfab(const std::string& args) {
  CommandResult result;
  const std::string command = std::string("\"") + SUBFAB_BINARY + "\" " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  std::size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}
#endif

}  // namespace subfab::test

// Helpers of the bus log tests (tests/replay/, tests/alloc/bus_log_alloc_test.cpp): record a scene's run as a
// bus log in a scratch directory, replay or re-simulate it in-process capturing what it prints, and edit log
// files byte by byte.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>
#include <vector>

#include "tools/commands.hpp"
#include "tools/replay_command.hpp"

namespace gyrostab::testing {

// A fresh directory under the system temp dir, removed with the object.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag) {
    path_ = std::filesystem::temp_directory_path() /
            ("gyrostab-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  static int& counter() {
    static int n = 0;
    return n;
  }
  std::filesystem::path path_;
};

inline std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes, std::size_t n) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(n));
}

// `gyrostab run SCENE --log LOG` for `ticks` ticks, in this process, no output files.
inline int record_run(const std::string& scene, const std::string& log, std::int64_t ticks) {
  tools::RunRequest req;
  req.scene_path = scene;
  req.ticks = ticks;
  req.write_outputs = false;
  req.progress = false;
  req.transport.log_path = log;
  return tools::run_scene(req);
}

struct ReplayResult {
  int rc{-1};
  std::string out;  // stdout + stderr
};

// `gyrostab replay LOG [--resimulate]`, in this process.
inline ReplayResult replay(const std::string& log, bool resimulate = false) {
  tools::RunRequest req;
  req.role = resimulate ? tools::Role::kResimulate : tools::Role::kReplay;
  req.transport.replay_log = log;
  req.write_outputs = false;
  req.progress = false;
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  ReplayResult r;
  r.rc = tools::replay_log(req);
  r.out = ::testing::internal::GetCapturedStdout();
  r.out += ::testing::internal::GetCapturedStderr();
  return r;
}

}  // namespace gyrostab::testing

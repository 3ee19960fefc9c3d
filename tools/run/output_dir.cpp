#include "tools/run/output_dir.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

extern char** environ;

namespace gyrostab::tools {

namespace fs = std::filesystem;

bool check_output_dir(const std::string& dir, std::string& error) {
  if (dir.empty()) {
    error = "--out: an empty path";
    return false;
  }
  std::error_code ec;
  const fs::path p = fs::absolute(dir, ec);
  const fs::path canon = fs::weakly_canonical(p, ec);
  for (const char* system_dir : {"/proc", "/sys", "/dev"}) {
    const std::string s = canon.string();
    const std::string root = system_dir;
    if (s == root || s.rfind(root + "/", 0) == 0) {
      error = "--out " + dir + ": inside " + root + ", not a place for outputs";
      return false;
    }
  }
  if (fs::exists(p, ec) && !fs::is_directory(p, ec)) {
    error = "--out " + dir + ": exists and is not a directory";
    return false;
  }
  fs::create_directories(p, ec);
  if (ec) {
    error = "--out " + dir + ": cannot create it (" + ec.message() + ")";
    return false;
  }
  if (access(p.c_str(), W_OK | X_OK) != 0) {
    error = "--out " + dir + ": not writable (" + std::strerror(errno) + ")";
    return false;
  }
  return true;
}

OutputSet::OutputSet(std::string dir, std::vector<std::string> kind) : dir_(std::move(dir)), kind_(std::move(kind)) {
  staging_ = dir_ + "/.staging-" + std::to_string(getpid());
}

OutputSet::~OutputSet() {
  if (!open_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

bool OutputSet::open(std::string& error) {
  if (!check_output_dir(dir_, error)) return false;
  std::error_code ec;
  fs::remove_all(staging_, ec);  // a stale one of an earlier process with this pid
  if (!fs::create_directory(staging_, ec) || ec) {
    error = "cannot create " + staging_ + ": " + (ec ? ec.message() : "exists");
    return false;
  }
  open_ = true;
  return true;
}

bool OutputSet::write(const std::string& name, const std::string& text, std::string& error) {
  std::ofstream f(staged(name), std::ios::binary);
  f << text;
  f.flush();
  if (!f) {
    error = "cannot write " + staged(name);
    return false;
  }
  return true;
}

bool OutputSet::commit(std::vector<std::string>& written, std::string& error) {
  written.clear();
  std::error_code ec;
  for (const std::string& name : kind_) {
    const fs::path from = staged(name), to = fs::path(dir_) / name;
    if (fs::exists(from, ec)) {
      fs::rename(from, to, ec);
      if (ec) {
        error = "cannot move " + from.string() + " to " + to.string() + ": " + ec.message();
        return false;
      }
      written.push_back(name);
    } else {
      fs::remove(to, ec);  // an earlier run's file of this kind: it would not belong to this run
    }
  }
  fs::remove_all(staging_, ec);
  open_ = false;
  return true;
}

bool write_file_atomic(const std::string& path, const std::string& text, std::string& error) {
  const std::string tmp = path + ".tmp-" + std::to_string(getpid());
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    f.flush();
    if (!f) {
      std::error_code ec;
      fs::remove(tmp, ec);
      error = "cannot write " + path;
      return false;
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    error = "cannot write " + path + ": " + ec.message();
    return false;
  }
  return true;
}

int run_program(const std::vector<std::string>& argv, std::string& error) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0], nullptr, nullptr, args.data(), environ);
  if (rc != 0) {
    error = "cannot start " + argv[0] + ": " + std::strerror(rc);
    return -1;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      error = "cannot wait for " + argv[0] + ": " + std::strerror(errno);
      return -1;
    }
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  error = argv[0] + " was killed by signal " + std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  return -1;
}

std::string list_names(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " and " : ", ";
    out += names[i];
  }
  return out.empty() ? "nothing" : out;
}

}  // namespace gyrostab::tools

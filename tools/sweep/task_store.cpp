#include "tools/sweep/task_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tools/sweep/task_record.hpp"

namespace gyrostab::tools::sweep {
namespace {

std::atomic<std::uint64_t> temp_counter{0};

std::string temp_name(const std::string& path) {
  const std::filesystem::path p(path);
  return (p.parent_path() / ("." + p.filename().string() + ".tmp-" + std::to_string(getpid()) + "-" +
                             std::to_string(temp_counter.fetch_add(1))))
      .string();
}

bool write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// Opens a fresh temporary file beside `path`; -1 with `error`.
int open_temp(const std::string& path, std::string& temp, std::string& error) {
  temp = temp_name(path);
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) error = "cannot create " + temp + ": " + std::strerror(errno);
  return fd;
}

// Opens a temporary file beside `path` and writes `text` to disk (fsync); -1 with `error`, the file removed.
int write_temp(const std::string& path, const std::string& text, std::string& temp, std::string& error) {
  const int fd = open_temp(path, temp, error);
  if (fd < 0) return -1;
  if (!write_all(fd, text) || ::fsync(fd) != 0) {
    error = "cannot write " + temp + ": " + std::strerror(errno);
    ::close(fd);
    ::unlink(temp.c_str());
    return -1;
  }
  return fd;
}

bool finish(int fd, const std::string& temp, const std::string& path, std::string& error) {
  if (::close(fd) != 0) {
    error = "cannot write " + temp + ": " + std::strerror(errno);
    ::unlink(temp.c_str());
    return false;
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    error = "cannot rename " + temp + " to " + path + ": " + std::strerror(errno);
    ::unlink(temp.c_str());
    return false;
  }
  return true;
}

}  // namespace

std::string task_dir(const std::string& dir, const Study& s, const Task& t) {
  return dir + "/tasks/" + s.variants[static_cast<std::size_t>(t.variant)].name;
}

std::string task_path(const std::string& dir, const Study& s, const Task& t) {
  return task_dir(dir, s, t) + "/" + t.stem() + ".json";
}

bool write_text_atomic(const std::string& path, const std::string& text, std::string& error) {
  std::string temp;
  const int fd = write_temp(path, text, temp, error);
  if (fd < 0) return false;
  return finish(fd, temp, path, error);
}

bool write_task_file(const std::string& path, nlohmann::json record, double& write_s, std::string& error) {
  const auto start = std::chrono::steady_clock::now();
  // The file holds its own write time: the field is written as a fixed-width placeholder and overwritten in
  // place once the bytes are on disk (the fsync is what costs); only that 14-byte write and the rename are
  // left out of it.
  record["timing"]["write_s"] = 0.0;
  std::string text = record.dump(2) + "\n";
  const std::string placeholder = "\"write_s\": 0.0";
  const std::size_t at = text.rfind(placeholder);  // "timing" is the record's last key
  if (at == std::string::npos) {
    error = "internal: no timing.write_s in the task record";
    return false;
  }
  constexpr std::size_t kWidth = 14;  // "%.12f" of a time under 10 s
  text.replace(at, placeholder.size(), "\"write_s\": 0." + std::string(kWidth - 2, '0'));
  const std::size_t value_at = at + placeholder.size() - 3;
  std::string temp;
  const int fd = write_temp(path, text, temp, error);
  if (fd < 0) return false;
  write_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  char value[kWidth + 1];
  std::snprintf(value, sizeof value, "%.12f", std::min(write_s, 9.999999999999));
  if (::pwrite(fd, value, kWidth, static_cast<off_t>(value_at)) != static_cast<ssize_t>(kWidth)) {
    error = "cannot write " + temp + ": " + std::strerror(errno);
    ::close(fd);
    ::unlink(temp.c_str());
    return false;
  }
  return finish(fd, temp, path, error);
}

StoredTask read_task_file(const std::string& path, const std::string& expected_hash) {
  StoredTask out;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return out;
  std::ifstream f(path, std::ios::binary);
  std::ostringstream text;
  text << f.rdbuf();
  nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
  out.state = Stored::kCorrupt;
  if (j.is_discarded() || !j.is_object()) {
    out.why = "not valid JSON (truncated or damaged)";
    return out;
  }
  if (j.value("format", "") != kTaskFormat) {
    out.why = std::string("not a task file of format ") + kTaskFormat;
    return out;
  }
  if (!j.contains("definition_hash") || !j["definition_hash"].is_string() || !j.contains("result_check") ||
      !j["result_check"].is_string()) {
    out.why = "no definition_hash or result_check";
    return out;
  }
  if (j["result_check"].get<std::string>() != result_check(j)) {
    out.why = "its result fields do not match their check (damaged)";
    return out;
  }
  const std::string outcome = j.value("outcome", "");
  if (outcome != kCompleted && outcome != kDiverged && outcome != kRefused) {
    out.why = "unknown outcome \"" + outcome + "\"";
    return out;
  }
  if (!j.contains("figures") || !j["figures"].is_object() || !j.contains("reasons") || !j["reasons"].is_array() ||
      !j.contains("timing") || !j["timing"].is_object()) {
    out.why = "figures, reasons or timing missing";
    return out;
  }
  for (std::string_view name : kTaskFigures) {
    const auto it = j["figures"].find(std::string(name));
    if (it == j["figures"].end() || !(it->is_null() || it->is_number())) {
      out.why = "figure " + std::string(name) + " missing or not a number";
      return out;
    }
  }
  if (j["definition_hash"].get<std::string>() != expected_hash) {
    out.state = Stored::kStale;
    out.why = "written for another definition of this task (the study or its base scene changed)";
    return out;
  }
  out.state = Stored::kValid;
  out.record = std::move(j);
  return out;
}

}  // namespace gyrostab::tools::sweep

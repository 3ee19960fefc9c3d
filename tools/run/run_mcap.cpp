#include "tools/run/run_mcap.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tools/signals/device_outputs.hpp"
#include "tools/signals/device_signals.hpp"

namespace gyrostab::tools {

namespace {

bool under(const std::filesystem::path& p, const char* root) {
  const std::string s = p.string();
  const std::string r(root);
  return s == r || s.rfind(r + "/", 0) == 0;
}

}  // namespace

std::int64_t RecorderRows::tick(std::size_t row) const {
  // Row times are tick × tick_s exactly as the loop computed them; the nearest tick recovers the integer.
  const double t = rec_.at(row, 0);
  return static_cast<std::int64_t>(std::llround(t * 1e9 / static_cast<double>(tick_ns_)));
}

RunMcapFile::~RunMcapFile() {
  if (open_) {
    w_.abandon();
    std::remove(tmp_.c_str());
  }
}

std::uint64_t RunMcapFile::stamp(std::int64_t tick) const {
  return tick < 0 ? 0 : static_cast<std::uint64_t>(tick) * static_cast<std::uint64_t>(tick_ns_);
}

bool RunMcapFile::open(const std::string& path, std::string& error) {
  path_ = path;
  tmp_ = path + ".tmp-" + std::to_string(::getpid());
  mcap::WriterOptions options;
  if (!w_.open(tmp_, options, error)) return false;
  open_ = true;
  return true;
}

std::uint16_t RunMcapFile::add(const ChannelInfo& info, const std::map<std::string, std::string>& metadata) {
  const std::uint16_t schema = w_.add_schema(info.title, "jsonschema", json_schema(info));
  return w_.add_channel(schema, info.topic, "json", metadata);
}

std::uint16_t RunMcapFile::add_json(const std::string& topic, const std::string& title, const std::string& description) {
  const nlohmann::json schema{{"$schema", "https://json-schema.org/draft/2020-12/schema"},
                              {"title", title},
                              {"type", "object"},
                              {"description", description}};
  return w_.add_channel(w_.add_schema(title, "jsonschema", schema.dump()), topic, "json");
}

bool RunMcapFile::row(std::uint16_t channel, const ChannelInfo& info, std::int64_t tick, const double* values) {
  msg_.clear();
  append_json_row(msg_, info, tick, values);
  return w_.write(channel, stamp(tick), stamp(tick), msg_);
}

bool RunMcapFile::rows(std::uint16_t channel, const ChannelInfo& info, const ChannelRows& rows) {
  scratch_.resize(info.signals.size());
  for (std::size_t r = 0; r < rows.rows(); ++r) {
    for (std::size_t c = 0; c < scratch_.size(); ++c) scratch_[c] = rows.value(r, c);
    if (!row(channel, info, rows.tick(r), scratch_.data())) return false;
  }
  return true;
}

bool RunMcapFile::json(std::uint16_t channel, std::int64_t tick, const nlohmann::json& value) {
  return w_.write(channel, stamp(tick), stamp(tick),
                  value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

bool RunMcapFile::commit(std::string& error) {
  std::string why;
  if (!open_) {
    error = "cannot write " + path_ + ": not open";
    return false;
  }
  open_ = false;
  if (!w_.close(why)) {
    w_.abandon();
    std::remove(tmp_.c_str());
    error = "cannot write " + path_ + (why.empty() ? "" : ": " + why);
    return false;
  }
  std::error_code ec;
  std::filesystem::rename(tmp_, path_, ec);
  if (ec) {
    std::remove(tmp_.c_str());
    error = "cannot move the MCAP file into place at " + path_ + ": " + ec.message();
    return false;
  }
  return true;
}

std::string mcap_path_problem(const std::string& path) {
  namespace fs = std::filesystem;
  if (path.empty()) return "--mcap needs a file name";
  std::error_code ec;
  const fs::path p = fs::absolute(path, ec);
  if (ec) return "--mcap " + path + ": " + ec.message();
  if (fs::is_directory(p, ec)) return "--mcap " + path + " is a directory; name a file";
  const fs::path dir = fs::weakly_canonical(p.parent_path(), ec);
  if (ec || !fs::is_directory(dir)) return "--mcap " + path + ": the directory " + p.parent_path().string() + " does not exist";
  if (under(dir, "/proc") || under(dir, "/sys") || under(dir, "/dev")) return "--mcap " + path + ": not a place for outputs";
  if (::access(dir.c_str(), W_OK | X_OK) != 0) return "--mcap " + path + ": the directory " + dir.string() + " is not writable";
  return "";
}

std::int64_t mcap_frames_every(const RunRequest& req, const LoopConfig& loop) {
  if (req.mcap_path.empty() && !req.mcap_frames_csv) return 0;
  if (req.mcap_frames_every >= 0) return req.mcap_frames_every;
  return loop.record_every;
}

std::unique_ptr<FrameTable> make_frame_table(const msg::DeviceSignals& device, const RunRequest& req,
                                             const LoopConfig& loop, std::int64_t ticks, std::string& error) {
  const std::int64_t every = mcap_frames_every(req, loop);
  if (every <= 0) return nullptr;
  if (error = FrameTable::size_problem(device, ticks, every); !error.empty()) return nullptr;
  return std::make_unique<FrameTable>(device, ticks, every);
}

namespace {

// A CSV of numbers with a header line, as signals.csv and the frame CSVs are written: the first column's
// ticks from `tick_of`.
class CsvRows final : public ChannelRows {
 public:
  std::vector<std::string> columns;
  std::vector<double> data;
  std::int64_t tick_ns{1};
  bool first_is_tick{false};  // the first column is the tick itself (frame CSVs), else t_s
  std::size_t rows() const override { return columns.empty() ? 0 : data.size() / columns.size(); }
  std::int64_t tick(std::size_t row) const override {
    const double first = data[row * columns.size()];
    if (first_is_tick) return static_cast<std::int64_t>(first);
    return static_cast<std::int64_t>(std::llround(first * 1e9 / static_cast<double>(tick_ns)));
  }
  double value(std::size_t row, std::size_t signal) const override {
    return data[row * columns.size() + signal + (first_is_tick ? 1 : 0)];
  }

  bool read(const std::string& file, std::string& error) {
    std::ifstream f(file);
    std::string line;
    if (!f || !std::getline(f, line)) {
      error = "cannot read " + file;
      return false;
    }
    std::stringstream header(line);
    for (std::string c; std::getline(header, c, ',');) columns.push_back(c);
    while (std::getline(f, line)) {
      if (line.empty()) continue;
      std::size_t n = 0;
      const char* p = line.c_str();
      while (*p != '\0') {
        char* end = nullptr;
        data.push_back(std::strtod(p, &end));
        if (end == p) {
          error = file + ": not a number in row " + std::to_string(rows());
          return false;
        }
        ++n;
        p = *end == ',' ? end + 1 : end;
      }
      if (n != columns.size()) {
        error = file + ": a row of " + std::to_string(n) + " values for " + std::to_string(columns.size()) + " columns";
        return false;
      }
    }
    return true;
  }
};

std::uint16_t add_report_channel(RunMcapFile& f) {
  return f.add_json(kReportTopic, "gyrostab.report",
                    "report.json of the run: scene, figures with their predictions, timing, limits");
}

std::int64_t report_ticks(const nlohmann::json& report) {
  if (report.contains("timing") && report["timing"].contains("ticks") && report["timing"]["ticks"].is_number_integer()) {
    return report["timing"]["ticks"].get<std::int64_t>();
  }
  return 0;
}

}  // namespace

bool write_run_mcap(const std::string& path, const LoopConfig& loop, const Recorder& rec, const nlohmann::json& report,
                    const FrameTable* frames, std::string& error) {
  RunMcapFile f(loop.tick_ns);
  if (!f.open(path, error)) return false;
  const ChannelInfo signals{kSignalsTopic, "gyrostab.signals." + loop.device,
                            signals_of_columns(rec.columns(), find_device_outputs(loop.device))};
  bool ok = f.rows(f.add(signals), signals, RecorderRows(rec, loop.tick_ns));
  if (frames != nullptr) {
    for (const FrameDirection d : {FrameDirection::kSensor, FrameDirection::kActuator}) {
      const ChannelInfo info = frame_channel(frames->device(), d);
      ok = ok && f.rows(f.add(info), info, frames->rows_of(d));
    }
  }
  ok = ok && f.json(add_report_channel(f), report_ticks(report), report);
  if (!ok) {
    error = "cannot write " + path + ": a write failed";
    return false;
  }
  return f.commit(error);
}

bool write_mcap_from_outputs(const std::string& path, const std::string& out_dir, const nlohmann::json& report,
                             std::string& error) {
  CsvRows rows;
  if (!rows.read(out_dir + "/signals.csv", error)) return false;
  const nlohmann::json& scene = report.contains("scene") ? report["scene"] : nlohmann::json::object();
  rows.tick_ns = scene.value("tick_ns", std::int64_t{1'000'000});
  const std::string device = scene.value("device", std::string("unknown"));
  const ChannelInfo signals{kSignalsTopic, "gyrostab.signals." + device,
                            signals_of_columns(rows.columns, find_device_outputs(device))};
  // The frames the plant process kept, if it was asked to (run --transport lcm|can --mcap).
  struct Frames {
    ChannelInfo info;
    CsvRows rows;
    std::string file;
  };
  std::vector<Frames> frames;
  const msg::DeviceSignals* dev = find_device_signals(device);
  for (const FrameDirection d : {FrameDirection::kSensor, FrameDirection::kActuator}) {
    const std::string file = out_dir + "/" + (d == FrameDirection::kSensor ? kSensorFramesCsv : kActuatorFramesCsv);
    if (!std::filesystem::exists(file)) continue;
    if (dev == nullptr) {
      error = "device " + device + " has no signal table: its frames (" + file + ") cannot be written";
      return false;
    }
    Frames fr{frame_channel(*dev, d), {}, file};
    fr.rows.first_is_tick = true;
    if (!fr.rows.read(file, error)) return false;
    std::vector<std::string> expected{"tick"};
    for (const SignalInfo& s : fr.info.signals) expected.push_back(label_of(s));
    if (fr.rows.columns != expected) {
      error = file + ": its columns are not the " + device + " frames' (" + std::to_string(expected.size()) + " expected)";
      return false;
    }
    frames.push_back(std::move(fr));
  }
  RunMcapFile f(rows.tick_ns);
  if (!f.open(path, error)) return false;
  bool ok = f.rows(f.add(signals), signals, rows);
  for (const Frames& fr : frames) ok = ok && f.rows(f.add(fr.info), fr.info, fr.rows);
  ok = ok && f.json(add_report_channel(f), report_ticks(report), report);
  if (!ok) {
    error = "cannot write " + path + ": a write failed";
    return false;
  }
  if (!f.commit(error)) return false;
  for (const Frames& fr : frames) std::remove(fr.file.c_str());
  return true;
}

bool write_frames_csv(const FrameTable& frames, FrameDirection direction, const std::string& path, std::string& error) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (out == nullptr) {
    error = "cannot create " + path;
    return false;
  }
  const ChannelInfo info = frame_channel(frames.device(), direction);
  std::fputs("tick", out);
  for (const SignalInfo& s : info.signals) std::fprintf(out, ",%s", label_of(s).c_str());
  std::fputc('\n', out);
  const ChannelRows& rows = frames.rows_of(direction);
  for (std::size_t r = 0; r < rows.rows(); ++r) {
    std::fprintf(out, "%lld", static_cast<long long>(rows.tick(r)));
    for (std::size_t c = 0; c < info.signals.size(); ++c) std::fprintf(out, ",%.17g", rows.value(r, c));
    std::fputc('\n', out);
  }
  const bool ok = std::ferror(out) == 0;
  if (std::fclose(out) != 0 || !ok) {
    error = "cannot write " + path;
    return false;
  }
  return true;
}

}  // namespace gyrostab::tools

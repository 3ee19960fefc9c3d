#include "tools/run/run_mcap.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tools/log/mcap_writer.hpp"

namespace gyrostab::tools {

namespace {

bool under(const std::filesystem::path& p, const char* root) {
  const std::string s = p.string();
  const std::string r(root);
  return s == r || s.rfind(r + "/", 0) == 0;
}

std::uint64_t stamp(std::int64_t tick, std::int64_t tick_ns) {
  return tick < 0 ? 0 : static_cast<std::uint64_t>(tick) * static_cast<std::uint64_t>(tick_ns);
}

bool write_channel(mcap::Writer& w, const ChannelInfo& info, const ChannelRows& rows, std::int64_t tick_ns) {
  const std::uint16_t schema = w.add_schema(info.title, "jsonschema", json_schema(info));
  std::map<std::string, std::string> meta;
  const std::uint16_t channel = w.add_channel(schema, info.topic, "json", meta);
  std::vector<double> values(info.signals.size());
  std::string msg;
  for (std::size_t r = 0; r < rows.rows(); ++r) {
    for (std::size_t c = 0; c < values.size(); ++c) values[c] = rows.value(r, c);
    msg.clear();
    const std::int64_t tick = rows.tick(r);
    append_json_row(msg, info, tick, values.data());
    if (!w.write(channel, stamp(tick, tick_ns), stamp(tick, tick_ns), msg)) return false;
  }
  return true;
}

}  // namespace

std::int64_t RecorderRows::tick(std::size_t row) const {
  // Row times are tick × tick_s exactly as the loop computed them; the nearest tick recovers the integer.
  const double t = rec_.at(row, 0);
  return static_cast<std::int64_t>(std::llround(t * 1e9 / static_cast<double>(tick_ns_)));
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

namespace {

// signals.csv read back: t_s first; ticks from the times as RecorderRows does.
class CsvRows final : public ChannelRows {
 public:
  std::vector<std::string> columns;
  std::vector<double> data;
  std::int64_t tick_ns{1};
  std::size_t rows() const override { return columns.empty() ? 0 : data.size() / columns.size(); }
  std::int64_t tick(std::size_t row) const override {
    return static_cast<std::int64_t>(std::llround(data[row * columns.size()] * 1e9 / static_cast<double>(tick_ns)));
  }
  double value(std::size_t row, std::size_t signal) const override { return data[row * columns.size() + signal]; }

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

bool write_file(const std::string& path, std::int64_t tick_ns, const ChannelInfo& signals,
                const ChannelRows& rows, const nlohmann::json& report, const std::vector<McapChannel>& extra,
                std::string& error);

}  // namespace

bool write_run_mcap(const std::string& path, const LoopConfig& loop, const Recorder& rec, const nlohmann::json& report,
                    const std::vector<McapChannel>& extra, std::string& error) {
  const ChannelInfo signals{kSignalsTopic, "gyrostab.signals." + loop.device, signals_of_columns(rec.columns())};
  return write_file(path, loop.tick_ns, signals, RecorderRows(rec, loop.tick_ns), report, extra, error);
}

bool write_mcap_from_outputs(const std::string& path, const std::string& out_dir, const nlohmann::json& report,
                             std::string& error) {
  CsvRows rows;
  if (!rows.read(out_dir + "/signals.csv", error)) return false;
  const nlohmann::json& scene = report.contains("scene") ? report["scene"] : nlohmann::json::object();
  rows.tick_ns = scene.value("tick_ns", std::int64_t{1'000'000});
  const std::string device = scene.value("device", std::string("unknown"));
  const ChannelInfo signals{kSignalsTopic, "gyrostab.signals." + device, signals_of_columns(rows.columns)};
  return write_file(path, rows.tick_ns, signals, rows, report, {}, error);
}

namespace {

bool write_file(const std::string& path, std::int64_t tick_ns, const ChannelInfo& signals,
                const ChannelRows& rows, const nlohmann::json& report, const std::vector<McapChannel>& extra,
                std::string& error) {
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  mcap::Writer w;
  mcap::WriterOptions options;
  if (!w.open(tmp, options, error)) return false;
  bool ok = write_channel(w, signals, rows, tick_ns);
  for (const McapChannel& c : extra) ok = ok && c.rows != nullptr && write_channel(w, c.info, *c.rows, tick_ns);
  if (ok) {
    const std::uint16_t schema = w.add_schema(
        "gyrostab.report", "jsonschema",
        R"({"$schema":"https://json-schema.org/draft/2020-12/schema","title":"gyrostab.report","type":"object",)"
        R"("description":"report.json of the run: scene, figures with their predictions, timing, limits"})");
    const std::uint16_t channel = w.add_channel(schema, kReportTopic, "json");
    std::int64_t ticks = 0;
    if (report.contains("timing") && report["timing"].contains("ticks") && report["timing"]["ticks"].is_number_integer()) {
      ticks = report["timing"]["ticks"].get<std::int64_t>();
    }
    ok = w.write(channel, stamp(ticks, tick_ns), stamp(ticks, tick_ns), report.dump());
  }
  std::string why;
  if (!ok || !w.close(why)) {
    w.abandon();
    std::remove(tmp.c_str());
    error = "cannot write " + path + (why.empty() ? "" : ": " + why);
    return false;
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    error = "cannot move the MCAP file into place at " + path + ": " + ec.message();
    return false;
  }
  return true;
}

}  // namespace

}  // namespace gyrostab::tools

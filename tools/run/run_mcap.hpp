// `gyrostab run SCENE --mcap FILE` (and `gyrostab plant ... --mcap FILE`): the run written as an MCAP file
// (tools/log/mcap_writer.hpp) at its end, from the recorder's table, off the loop:
//   /gyrostab/signals   one message per recorded row, the fields of signals.csv ("t_s" included) and "tick"
//   /gyrostab/report    one message, report.json's content, stamped with the run's last tick
//   (more channels)     `extra`: a channel per frame once the device's signal table declares the frames
// Messages are JSON with a JSON Schema each (Foxglove, Lichtblick and PlotJuggler decode both without a
// plug-in); log and publish times are simulated time in nanoseconds (tick × tick_ns). The file is an output
// like the others: its directory is checked before the run starts, and it is written under a temporary name
// beside it and renamed when complete, so a failed run leaves no partial file. Docs: docs/mcap.md.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/log/signal_channel.hpp"
#include "tools/run/recorder.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

inline constexpr const char* kSignalsTopic = "/gyrostab/signals";
inline constexpr const char* kReportTopic = "/gyrostab/report";

// A further channel of the file (a frame channel): what it holds and its rows.
struct McapChannel {
  ChannelInfo info;
  const ChannelRows* rows{nullptr};
};

// The recorder's table as a channel: row r's tick from its time column.
class RecorderRows final : public ChannelRows {
 public:
  RecorderRows(const Recorder& rec, std::int64_t tick_ns) : rec_(rec), tick_ns_(tick_ns) {}
  std::size_t rows() const override { return rec_.rows(); }
  std::int64_t tick(std::size_t row) const override;
  double value(std::size_t row, std::size_t signal) const override { return rec_.at(row, signal); }

 private:
  const Recorder& rec_;
  std::int64_t tick_ns_;
};

// "" if `path` can be written as the run's MCAP file (its directory exists and is writable, outside /proc,
// /sys and /dev; the path is not a directory), else why not.
std::string mcap_path_problem(const std::string& path);

// Writes the file (through `path`.tmp-<pid> and a rename); false with `error` set, and nothing left behind.
bool write_run_mcap(const std::string& path, const LoopConfig& loop, const Recorder& rec, const nlohmann::json& report,
                    const std::vector<McapChannel>& extra, std::string& error);
// The same from a run's output directory (its signals.csv, whose "%.17g" values read back to the same doubles)
// and the run's final report: the two-process run writes its file this way, once the parent has merged the
// plant's and the controller's reports.
bool write_mcap_from_outputs(const std::string& path, const std::string& out_dir, const nlohmann::json& report,
                             std::string& error);

}  // namespace gyrostab::tools

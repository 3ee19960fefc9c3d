// `gyrostab run SCENE --mcap FILE` (and `gyrostab plant ... --mcap FILE`, `gyrostab export LOG --mcap FILE`):
// a run written as an MCAP file (tools/log/mcap_writer.hpp), off the loop:
//   /gyrostab/signals   one message per recorded row, the fields of signals.csv ("t_s" included) and "tick"
//   /gyrostab/sensor    the sensor frames: header and every signal of the device's table, one message per
//   /gyrostab/actuator  the actuator frames      captured tick (tools/log/frame_channel.hpp, frame_table.hpp)
//   /gyrostab/report    one message, report.json's content, stamped with the run's last tick
// (export: /gyrostab/scene and /gyrostab/log instead of the report: tools/log/bus_log_export.hpp).
// Messages are JSON with a JSON Schema each (Foxglove, Lichtblick and PlotJuggler decode both without a
// plug-in); log and publish times are simulated time in nanoseconds (tick × tick_ns). The file is an output
// like the others: its directory is checked before the run starts, and it is written under a temporary name
// beside it and renamed when complete, so a failed run leaves no partial file. Docs: docs/mcap.md.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tools/log/mcap_writer.hpp"
#include "tools/log/signal_channel.hpp"
#include "tools/run/frame_table.hpp"
#include "tools/loop/recorder.hpp"
#include "tools/run/run_output.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

inline constexpr const char* kSignalsTopic = "/gyrostab/signals";
inline constexpr const char* kReportTopic = "/gyrostab/report";
// The frame CSVs a plant process writes beside signals.csv for its parent's MCAP file (run --transport lcm|can).
inline constexpr const char* kSensorFramesCsv = "frames_sensor.csv";
inline constexpr const char* kActuatorFramesCsv = "frames_actuator.csv";

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

// One MCAP file of a run, written through `path`.tmp-<pid> and renamed into place by commit(); dropped
// uncommitted, the temporary file is removed.
class RunMcapFile {
 public:
  explicit RunMcapFile(std::int64_t tick_ns) : tick_ns_(tick_ns) {}
  ~RunMcapFile();
  RunMcapFile(const RunMcapFile&) = delete;
  RunMcapFile& operator=(const RunMcapFile&) = delete;

  bool open(const std::string& path, std::string& error);
  // A channel with its JSON Schema (json_schema(info)); its id.
  std::uint16_t add(const ChannelInfo& info, const std::map<std::string, std::string>& metadata = {});
  // A channel whose messages are free-form JSON objects (the report, the scene): its id.
  std::uint16_t add_json(const std::string& topic, const std::string& title, const std::string& description);
  // One row of a channel added with add(); false once a write failed.
  bool row(std::uint16_t channel, const ChannelInfo& info, std::int64_t tick, const double* values);
  bool rows(std::uint16_t channel, const ChannelInfo& info, const ChannelRows& rows);
  bool json(std::uint16_t channel, std::int64_t tick, const nlohmann::json& value);
  // Closes the file and moves it into place; false with `error` set (nothing is left behind then).
  bool commit(std::string& error);

 private:
  std::uint64_t stamp(std::int64_t tick) const;
  mcap::Writer w_;
  std::string path_, tmp_;
  std::int64_t tick_ns_;
  std::string msg_;
  std::vector<double> scratch_;
  bool open_{false};
};

// "" if `path` can be written as the run's MCAP file (its directory exists and is writable, outside /proc,
// /sys and /dev; the path is not a directory), else why not.
std::string mcap_path_problem(const std::string& path);

// The frames the run's MCAP file holds: every this many ticks (RunRequest::mcap_frames_every, or the
// recorder's row interval when not given); 0 when none are kept (no --mcap, or --mcap-frames-every 0).
std::int64_t mcap_frames_every(const RunRequest& req, const LoopConfig& loop);

// The table of the frames a run keeps (mcap_frames_every); nullptr when it keeps none, or with `error` set when
// the table would pass the recorder's ceiling (the run is then refused before tick 0).
std::unique_ptr<FrameTable> make_frame_table(const msg::DeviceSignals& device, const RunRequest& req,
                                             const LoopConfig& loop, std::int64_t ticks, std::string& error);

// Writes the file: the recorded rows, the frames (if `frames`), the report. false with `error` set, and nothing
// left behind.
bool write_run_mcap(const std::string& path, const LoopConfig& loop, const Recorder& rec, const nlohmann::json& report,
                    const FrameTable* frames, std::string& error);
// The same from a run's output directory (its signals.csv and, if the plant process wrote them, its
// frames_sensor.csv and frames_actuator.csv, whose "%.17g" values read back to the same doubles) and the run's
// final report: the two-process run writes its file this way, once the parent has merged the plant's and the
// controller's reports. The frame CSVs are removed once the file is in place.
bool write_mcap_from_outputs(const std::string& path, const std::string& out_dir, const nlohmann::json& report,
                             std::string& error);
// The frames CSV of one direction (header "tick" and the channel's labels; %.17g values), into `path`.
bool write_frames_csv(const FrameTable& frames, FrameDirection direction, const std::string& path, std::string& error);

}  // namespace gyrostab::tools

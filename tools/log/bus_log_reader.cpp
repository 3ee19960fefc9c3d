#include "tools/log/bus_log_reader.hpp"

#include "tools/signals/device_signals.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <sys/stat.h>

#include <lcm/eventlog.h>

#include "hil/lcm/frame_codec.hpp"

namespace gyrostab::tools::buslog {

namespace {
// A log records every frame with the empty envelope (session 0: never live, so that a log played onto a bus
// is refused by every live end; scene 0: the log's scene event names the scene once); anything else in it is
// a corruption.
bool recorded_envelope(const hil::LinkEnvelope& e) {
  return e.sender == 0 && e.session == 0 && e.freshness == 0 && e.mac == 0 && e.scene == 0;
}
// A frame of another size or fingerprint is most likely from a build with another contract (the frames grew
// when the cluster fields were added): say so, with both sizes.
std::string other_contract(hil::DecodeError e, std::int64_t size, int expected) {
  if (e != hil::DecodeError::kWrongSize && e != hil::DecodeError::kWrongFingerprint) return {};
  return " (" + std::to_string(size) + " bytes, this build's " + std::to_string(expected) +
         ": a log of a build with another contract version, or a corrupt one)";
}
}  // namespace

namespace {

constexpr std::uint32_t kSyncWord = 0xEDA1DA01u;  // LCM log format: every event starts with it
constexpr int kHeaderBytes = 28;                  // sync, event number, timestamp, channel and data lengths

std::uint32_t be32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}
std::uint64_t be64(const std::uint8_t* p) {
  return (std::uint64_t{be32(p)} << 32) | be32(p + 4);
}

// A channel name from a possibly corrupt log, printable.
std::string printable(const char* s, int n) {
  std::string out;
  for (int i = 0; i < n && out.size() < 80; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  if (n > 80) out += "...";
  return out;
}

}  // namespace

const char* describe(ReadStatus s) {
  switch (s) {
    case ReadStatus::kOk: return "ok";
    case ReadStatus::kEnd: return "complete";
    case ReadStatus::kTruncated: return "truncated";
    case ReadStatus::kCorrupt: return "corrupt";
    case ReadStatus::kUnreadable: return "unreadable";
  }
  return "?";
}

struct BusLogReader::Event {
  struct Free {
    void operator()(lcm_eventlog_event_t* e) const { lcm_eventlog_free_event(e); }
  };
  std::int64_t offset{0};
  std::int64_t number{0};
  std::unique_ptr<lcm_eventlog_event_t, Free> ev;

  std::string channel() const { return std::string(ev->channel, static_cast<std::size_t>(ev->channellen)); }
};

BusLogReader::BusLogReader() = default;

BusLogReader::~BusLogReader() {
  if (log_ != nullptr) lcm_eventlog_destroy(log_);
}

ReadStatus BusLogReader::fail(ReadStatus s, std::int64_t offset, const std::string& what) {
  problem_ = path_ + ": byte " + std::to_string(offset) + ": " + what;
  problem_offset_ = offset;
  done_ = true;
  last_ = s;
  return s;
}

std::string BusLogReader::tick_name() const {
  return "tick " + std::to_string(ticks_);
}

// The event at `pos` (header `h` already checked, its channel and data within the file), read byte for byte
// into the structure LCM's reader returns (malloc'ed: lcm_eventlog_free_event frees it). nullptr on a read error.
lcm_eventlog_event_t* read_event_after_lcm_refused(std::FILE* f, std::int64_t pos, const std::uint8_t* h,
                                                   std::int32_t channellen, std::int32_t datalen) {
  if (fseeko(f, static_cast<off_t>(pos + kHeaderBytes), SEEK_SET) != 0) return nullptr;
  auto* ev = static_cast<lcm_eventlog_event_t*>(std::calloc(1, sizeof(lcm_eventlog_event_t)));
  if (ev == nullptr) return nullptr;
  ev->eventnum = static_cast<std::int64_t>(be64(h + 4));
  ev->timestamp = static_cast<std::int64_t>(be64(h + 12));
  ev->channellen = channellen;
  ev->datalen = datalen;
  ev->channel = static_cast<char*>(std::calloc(static_cast<std::size_t>(channellen) + 1, 1));
  ev->data = std::malloc(datalen > 0 ? static_cast<std::size_t>(datalen) : 1);
  if (ev->channel == nullptr || ev->data == nullptr ||
      std::fread(ev->channel, 1, static_cast<std::size_t>(channellen), f) != static_cast<std::size_t>(channellen) ||
      std::fread(ev->data, 1, static_cast<std::size_t>(datalen), f) != static_cast<std::size_t>(datalen)) {
    lcm_eventlog_free_event(ev);
    return nullptr;
  }
  return ev;
}

// One event, its envelope checked before LCM reads it; kEnd here means "at the end of the file, between
// events" (the caller decides whether that is allowed).
ReadStatus BusLogReader::read_event(Event& e) {
  std::FILE* f = log_->f;
  const std::int64_t pos = ftello(f);
  if (pos < 0) return fail(ReadStatus::kCorrupt, 0, std::string("cannot tell the read position: ") + std::strerror(errno));
  e.offset = pos;
  e.number = next_eventnum_;
  const std::int64_t left = file_size_ - pos;
  if (left == 0) return ReadStatus::kEnd;
  const std::string which = "event " + std::to_string(next_eventnum_);
  if (left < kHeaderBytes) {
    return fail(ReadStatus::kTruncated, pos,
                "the log ends " + std::to_string(left) + " bytes into the 28-byte header of " + which);
  }
  std::uint8_t h[kHeaderBytes];
  if (std::fread(h, 1, kHeaderBytes, f) != static_cast<std::size_t>(kHeaderBytes)) {
    return fail(ReadStatus::kTruncated, pos, "cannot read the header of " + which + " (file shrank?)");
  }
  const std::uint32_t sync = be32(h);
  const auto number = static_cast<std::int64_t>(be64(h + 4));
  const auto channellen = static_cast<std::int32_t>(be32(h + 20));
  const auto datalen = static_cast<std::int32_t>(be32(h + 24));
  if (sync != kSyncWord) {
    char found[16];
    std::snprintf(found, sizeof found, "0x%08X", sync);
    return fail(ReadStatus::kCorrupt, pos,
                which + " does not start with the LCM sync word 0xEDA1DA01 (found " + found + ")");
  }
  if (channellen <= 0 || channellen > kMaxChannelLength) {
    return fail(ReadStatus::kCorrupt, pos, which + " has an impossible channel length " + std::to_string(channellen));
  }
  if (datalen < 0 || datalen > kMaxSceneEventBytes) {
    return fail(ReadStatus::kCorrupt, pos, which + " has an impossible data length " + std::to_string(datalen));
  }
  const std::int64_t need = kHeaderBytes + std::int64_t{channellen} + datalen;
  if (need > left) {
    return fail(ReadStatus::kTruncated, pos,
                "the log ends inside " + which + ": it declares " + std::to_string(need) + " bytes, " +
                    std::to_string(left) + " remain");
  }
  if (number != next_eventnum_) {
    return fail(ReadStatus::kCorrupt, pos,
                "event number " + std::to_string(number) + " where " + std::to_string(next_eventnum_) +
                    " was due (an event is missing, repeated or corrupt)");
  }
  if (fseeko(f, static_cast<off_t>(pos), SEEK_SET) != 0) {
    return fail(ReadStatus::kCorrupt, pos, std::string("cannot seek: ") + std::strerror(errno));
  }
  e.ev.reset(lcm_eventlog_read_next_event(log_));
  if (!e.ev) {
    // LCM 1.3 also refuses an event whose successor does not start with the sync word ("Invalid header after
    // log data"): the event itself, whose header we have checked, is whole — read it as LCM would have, so that
    // everything before damaged bytes is still read and the damage is reported where it lies.
    e.ev.reset(read_event_after_lcm_refused(f, pos, h, channellen, datalen));
  }
  if (!e.ev || e.ev->channellen != channellen || e.ev->datalen != datalen) {
    return fail(ReadStatus::kCorrupt, pos, "LCM's log reader did not read " + which + " as its header declares");
  }
  // LCM 1.3 peeks at the next event's sync word and does not step back when fewer than 4 bytes follow: the
  // next event starts where this one's header says it ends, wherever LCM left the stream.
  if (fseeko(f, static_cast<off_t>(pos + need), SEEK_SET) != 0) {
    return fail(ReadStatus::kCorrupt, pos, std::string("cannot seek: ") + std::strerror(errno));
  }
  ++next_eventnum_;
  return ReadStatus::kOk;
}

ReadStatus BusLogReader::open(const std::string& path) {
  path_ = path;
  if (log_ != nullptr) return fail(ReadStatus::kUnreadable, 0, "reader already open");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return fail(ReadStatus::kUnreadable, 0, std::strerror(errno));
  if (!S_ISREG(st.st_mode)) return fail(ReadStatus::kUnreadable, 0, "not a regular file");
  errno = 0;
  log_ = lcm_eventlog_create(path.c_str(), "r");
  if (log_ == nullptr) return fail(ReadStatus::kUnreadable, 0, errno != 0 ? std::strerror(errno) : "cannot open");
  struct stat fst {};
  if (::fstat(fileno(log_->f), &fst) != 0) return fail(ReadStatus::kUnreadable, 0, std::strerror(errno));
  file_size_ = static_cast<std::int64_t>(fst.st_size);

  Event e;
  const ReadStatus s = read_event(e);
  if (s == ReadStatus::kEnd) return fail(ReadStatus::kTruncated, 0, "empty file: no scene event");
  if (s != ReadStatus::kOk) return s;
  const std::string ch = e.channel();
  const std::string base = kSceneChannel;
  if (ch.compare(0, base.size(), base) != 0) {
    return fail(ReadStatus::kCorrupt, e.offset,
                "the first event is on channel '" + printable(e.ev->channel, e.ev->channellen) + "', not " + base +
                    "<suffix>: not a gyrostab bus log");
  }
  if (e.ev->timestamp != 0) {
    return fail(ReadStatus::kCorrupt, e.offset,
                "the scene event has timestamp " + std::to_string(e.ev->timestamp) + " µs, not 0");
  }
  std::string why;
  if (!decode(e.ev->data, e.ev->datalen, scene_, why)) {
    return fail(ReadStatus::kCorrupt, e.offset, "the scene event does not decode: " + why);
  }
  suffix_ = ch.substr(base.size());
  signals_ = find_device_signals(scene_.device);
  if (signals_ == nullptr) {
    return fail(ReadStatus::kCorrupt, e.offset,
                "the log's device '" + scene_.device + "' has no signal table in this build: its frames cannot be "
                "decoded");
  }
  sensor_channel_ = channel(kSensorChannel, suffix_);
  actuator_channel_ = channel(kActuatorChannel, suffix_);
  end_channel_ = channel(kEndChannel, suffix_);
  return ReadStatus::kOk;
}

ReadStatus BusLogReader::read_frame_event(const char* what, const std::string& expected, Event& e) {
  const ReadStatus s = read_event(e);
  if (s != ReadStatus::kOk) return s;
  const std::string ch = e.channel();
  if (ch != expected) {
    const bool is_end = ch == end_channel_;
    return fail(ReadStatus::kCorrupt, e.offset,
                "event " + std::to_string(e.number) + " is on channel '" + printable(e.ev->channel, e.ev->channellen) +
                    "' where the " + what + " frame of " + tick_name() + " (" + expected + ") was due" +
                    (is_end ? " (an end event inside a tick)" : ""));
  }
  const std::int64_t due = sim_time_us(ticks_, scene_.tick_ns);
  if (e.ev->timestamp != due) {
    return fail(ReadStatus::kCorrupt, e.offset,
                std::string("the ") + what + " frame of " + tick_name() + " has timestamp " +
                    std::to_string(e.ev->timestamp) + " µs, not the tick's sim time " + std::to_string(due) + " µs");
  }
  return ReadStatus::kOk;
}

ReadStatus BusLogReader::next(TickRecord& out) {
  if (log_ == nullptr && !done_) return fail(ReadStatus::kUnreadable, 0, "not open");
  if (done_) return last_;
  const std::int64_t due = sim_time_us(ticks_, scene_.tick_ns);

  Event s;
  ReadStatus st = read_event(s);
  if (st == ReadStatus::kEnd) {
    return fail(ReadStatus::kTruncated, file_size_,
                "the log ends after " + std::to_string(ticks_) +
                    " whole ticks without its end event (GYROSTAB_END): the run was killed or the file cut");
  }
  if (st != ReadStatus::kOk) return st;
  if (s.channel() == end_channel_) {
    std::string why;
    if (!decode(s.ev->data, s.ev->datalen, end_, why)) {
      return fail(ReadStatus::kCorrupt, s.offset, "the end event does not decode: " + why);
    }
    if (end_.ticks != ticks_) {
      return fail(ReadStatus::kCorrupt, s.offset,
                  "the end event counts " + std::to_string(end_.ticks) + " ticks, the log holds " +
                      std::to_string(ticks_));
    }
    if (s.ev->timestamp != due) {
      return fail(ReadStatus::kCorrupt, s.offset,
                  "the end event has timestamp " + std::to_string(s.ev->timestamp) + " µs, not " +
                      std::to_string(due) + " µs");
    }
    const std::int64_t after = ftello(log_->f);
    if (after != file_size_) {
      return fail(ReadStatus::kCorrupt, after,
                  std::to_string(file_size_ - after) + " bytes follow the end event");
    }
    done_ = true;
    last_ = ReadStatus::kEnd;
    return ReadStatus::kEnd;
  }
  // Re-check as a frame event (channel, timestamp) now that it is not the end event.
  const std::string ch = s.channel();
  if (ch != sensor_channel_) {
    return fail(ReadStatus::kCorrupt, s.offset,
                "event " + std::to_string(s.number) + " is on channel '" + printable(s.ev->channel, s.ev->channellen) +
                    "' where the sensor frame of " + tick_name() + " (" + sensor_channel_ + ") was due");
  }
  if (s.ev->timestamp != due) {
    return fail(ReadStatus::kCorrupt, s.offset,
                "the sensor frame of " + tick_name() + " has timestamp " + std::to_string(s.ev->timestamp) +
                    " µs, not the tick's sim time " + std::to_string(due) + " µs");
  }
  TickRecord r;
  r.tick = ticks_;
  r.sensor_offset = s.offset;
  std::int64_t t_us = 0;
  hil::LinkEnvelope env;
  hil::DecodeError de = hil::decode(s.ev->data, s.ev->datalen, *signals_, r.sensor, &t_us, &env);
  if (de != hil::DecodeError::kOk) {
    return fail(ReadStatus::kCorrupt, s.offset,
                "the sensor frame of " + tick_name() + " does not decode as " +
                    std::string(signals_->lcm_sensor_type) + ": " + hil::describe(de) +
                    other_contract(de, s.ev->datalen, hil::sensor_encoded_size(*signals_)));
  }
  if (!recorded_envelope(env)) {
    return fail(ReadStatus::kCorrupt, s.offset,
                "the sensor frame of " + tick_name() + " carries a live link envelope (a log records it empty)");
  }
  if (t_us != due) {
    return fail(ReadStatus::kCorrupt, s.offset,
                "the sensor frame of " + tick_name() + " carries sim_time_us " + std::to_string(t_us) +
                    ", its event timestamp is " + std::to_string(due));
  }

  Event a;
  st = read_frame_event("actuator", actuator_channel_, a);
  if (st == ReadStatus::kEnd) {
    return fail(ReadStatus::kTruncated, file_size_,
                "the log ends after the sensor frame of " + tick_name() + ": its actuator frame is missing");
  }
  if (st != ReadStatus::kOk) return st;
  r.actuator_offset = a.offset;
  de = hil::decode(a.ev->data, a.ev->datalen, *signals_, r.actuator, &t_us, &env);
  if (de != hil::DecodeError::kOk) {
    return fail(ReadStatus::kCorrupt, a.offset,
                "the actuator frame of " + tick_name() + " does not decode as " +
                    std::string(signals_->lcm_actuator_type) + ": " + hil::describe(de) +
                    other_contract(de, a.ev->datalen, hil::actuator_encoded_size(*signals_)));
  }
  if (!recorded_envelope(env)) {
    return fail(ReadStatus::kCorrupt, a.offset,
                "the actuator frame of " + tick_name() + " carries a live link envelope (a log records it empty)");
  }
  if (t_us != due) {
    return fail(ReadStatus::kCorrupt, a.offset,
                "the actuator frame of " + tick_name() + " carries sim_time_us " + std::to_string(t_us) +
                    ", its event timestamp is " + std::to_string(due));
  }
  out = r;
  ++ticks_;
  return ReadStatus::kOk;
}

}  // namespace gyrostab::tools::buslog

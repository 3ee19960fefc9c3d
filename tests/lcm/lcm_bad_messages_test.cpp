// Bad messages on the bus are counted and rejected, never applied. A third process (this test) joins the bus
// of a lockstep `run --transport lcm` and, following the genuine frames, publishes on both channels: wrong
// sizes, wrong fingerprints, stale and repeated sequences, ticks far ahead. Each kind must show up in the
// receiving side's counters, and the run must still be bit-identical to the in-process run (nothing forged was
// applied). A copier that sends other contents for a tick the peer also answers is a second source: without a
// key that run is a hijack, never a success (exit 7, both ends name it). NaN and out-of-range commands of the
// bound controller itself: tests/lcm/lcm_faults_test.cpp (--corrupt-actuator), tests/unit/lcm_link_test.cpp.
#include <gtest/gtest.h>
#include <lcm/lcm.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

#include "gyrostab_signals/monorail_frames.hpp"
#include "hil/lcm/frame_codec.hpp"
#include "tools/signals/device_signals.hpp"
#include "tests/lcm/lcm_test_support.hpp"

namespace gyrostab::testing {
namespace {

constexpr const char* kSuffix = "_forged";
const std::string kSensorChannel = std::string("GYROSTAB_SENSOR") + kSuffix;
const std::string kActuatorChannel = std::string("GYROSTAB_ACTUATOR") + kSuffix;

struct Forger {
  lcm_t* lcm{nullptr};
  std::int64_t last_sensor_tick{-1};  // the latest genuine sensor frame
  std::int64_t last_copied_actuator{-1};
  std::uint64_t forged{0};
  // The envelope of the genuine frame being answered: a process that reads the bus copies the session and
  // the sender ids (without a link key nothing more is needed), so its frames reach the order and value
  // checks, which are what this test is about.
  hil::LinkEnvelope envelope{};
  bool hijack{false};  // also send other contents for the tick the plant has just taken, and every tick
  std::int64_t last_actuator_sequence{-1};
  const msg::DeviceSignals& device = *tools::find_device_signals("monorail");

  template <class Frame>
  void publish(const std::string& channel, const Frame& f, int size_delta = 0, bool bad_fingerprint = false) {
    std::uint8_t buf[512] = {};
    const int n = hil::encode(msg::any_of(f), device, 0, buf, static_cast<int>(sizeof buf), envelope);
    if (bad_fingerprint) buf[3] ^= 0x40;
    lcm_publish(lcm, channel.c_str(), buf, static_cast<unsigned>(n + size_delta));
    ++forged;
  }

  void on_sensor(const msg::monorail::SensorFrame& s) {
    const auto k = static_cast<std::int64_t>(s.tick);
    // Genuine ticks only go up (our own stale, repeated and far-ahead forgeries come back to us too).
    if (last_sensor_tick >= 0 && (k <= last_sensor_tick || k > last_sensor_tick + 1000)) return;
    last_sensor_tick = k;
    if (k < 20) return;
    if (hijack && last_actuator_sequence >= 0) {
      // A command of our own for the tick the plant now waits for, racing the genuine one.
      msg::monorail::ActuatorFrame own{};
      own.tick = s.tick;
      own.sequence = static_cast<std::uint32_t>(last_actuator_sequence + 1);
      own.motor_torque_Nm = 1.0;
      publish(kActuatorChannel, own);
    }
    if (k % 10 == 0) {
      publish(kSensorChannel, s, +1);
      publish(kSensorChannel, s, 0, true);
      // Stale: five ticks old, well formed. Far ahead: beyond what the controller may skip.
      msg::monorail::SensorFrame old = s;
      old.tick -= 5;
      old.sequence -= 5;
      publish(kSensorChannel, old);
      msg::monorail::SensorFrame ahead = s;
      ahead.tick += 5000;
      ahead.sequence += 5000;
      publish(kSensorChannel, ahead);
    }
    if (k % 10 == 3) publish(kSensorChannel, s);  // an exact repeat of the frame just sent
  }

  // Forged commands follow the genuine one of the same tick: the plant's socket holds the genuine frame first
  // (both left the controller's one sendmsg), so the forgeries reach a plant that has already taken tick k —
  // they are rejected whatever the machine's load, and the run stays bit-identical. (A bad command that comes
  // BEFORE the genuine one is the lockstep grace rule's case: tests/unit/lcm_link_test.cpp.)
  void on_actuator(const msg::monorail::ActuatorFrame& a) {
    const auto k = static_cast<std::int64_t>(a.tick);
    if (a.motor_torque_Nm != 1.0 && static_cast<std::int64_t>(a.sequence) > last_actuator_sequence &&
        k <= last_sensor_tick) {
      last_actuator_sequence = static_cast<std::int64_t>(a.sequence);
    }
    if (k > last_sensor_tick || k <= last_copied_actuator ||
        !std::isfinite(a.motor_torque_Nm) || a.precession_brake > 1.0 ||
        std::fabs(a.motor_torque_Nm) > 2000.0) {
      return;  // one of ours
    }
    if (k % 10 == 7) {
      last_copied_actuator = k;
      if (hijack) {
        msg::monorail::ActuatorFrame bad = a;  // NaN torque, then a brake out of [0, 1], for the tick just taken
        bad.motor_torque_Nm = std::numeric_limits<double>::quiet_NaN();
        publish(kActuatorChannel, bad);
        bad = a;
        bad.precession_brake = 2.0;
        publish(kActuatorChannel, bad);
      }
      publish(kActuatorChannel, a, +1);  // wrong sizes, wrong fingerprint
      publish(kActuatorChannel, a, -1);
      publish(kActuatorChannel, a, 0, true);
      return;
    }
    if (k % 10 != 3) return;
    last_copied_actuator = k;
    publish(kActuatorChannel, a);  // exact repeat of the command the plant just accepted
    msg::monorail::ActuatorFrame old = a;    // stale: an older tick with a well-formed command
    old.tick -= 2;
    old.sequence -= 2;
    publish(kActuatorChannel, old);
    // Ahead: a later tick than the plant waits for — beyond the run, so that however late this copy arrives
    // (a loaded machine) the plant is never waiting for exactly that tick when it does.
    msg::monorail::ActuatorFrame ahead = a;
    ahead.tick += 5000;
    ahead.sequence += 5000;
    publish(kActuatorChannel, ahead);
  }
};

void on_message(const lcm_recv_buf_t* rbuf, const char* channel, void* user) {
  auto* f = static_cast<Forger*>(user);
  if (kSensorChannel == channel) {
    msg::AnySensorFrame any{};
    msg::monorail::SensorFrame s{};
    if (hil::decode(rbuf->data, static_cast<int>(rbuf->data_size), f->device, any, nullptr, &f->envelope) ==
        hil::DecodeError::kOk) {
      msg::from_any(any, s);
      f->on_sensor(s);
    }
  } else {
    msg::AnyActuatorFrame any{};
    msg::monorail::ActuatorFrame a{};
    if (hil::decode(rbuf->data, static_cast<int>(rbuf->data_size), f->device, any, nullptr, &f->envelope) ==
        hil::DecodeError::kOk) {
      msg::from_any(any, a);
      f->on_actuator(a);
    }
  }
}

struct ForgedRun {
  Exit exit;
  std::uint64_t forged{0};
};

ForgedRun run_with_forger(const std::string& path, const std::string& out, bool hijack) {
  Forger forger;
  forger.hijack = hijack;
  forger.lcm = lcm_create("udpm://239.255.76.67:7667?ttl=0");
  if (forger.lcm == nullptr) return {};
  for (const std::string& ch : {kSensorChannel, kActuatorChannel}) {
    lcm_subscription_set_queue_capacity(lcm_subscribe(forger.lcm, ch.c_str(), on_message, &forger), 100'000);
  }
  std::atomic<bool> stop{false};
  std::thread t([&] {
    while (!stop) lcm_handle_timeout(forger.lcm, 50);
  });
  ForgedRun r;
  r.exit = run({gyrostab_bin(), "run", path, "--transport", "lcm", "--ticks", "3000", "--channel-suffix", kSuffix,
                "--out", out});
  stop = true;
  t.join();
  lcm_destroy(forger.lcm);
  r.forged = forger.forged;
  return r;
}

TEST(LcmBadMessages, AreCountedByKindAndNeverApplied) {
  TempDir d;
  const std::string path = scene("monorail.toml");
  ASSERT_EQ(
      run({gyrostab_bin(), "run", path, "--ticks", "3000", "--no-progress", "--out", d / "inproc"}).code, 0);
  const ForgedRun f = run_with_forger(path, d / "lcm", false);
  ASSERT_EQ(f.exit.code, 0);
  EXPECT_GT(f.forged, 1000u);

  // Nothing forged was applied: the run is the in-process run, bit for bit.
  EXPECT_EQ(read_json(d / "lcm/report.json")["figures"].dump(),
            read_json(d / "inproc/report.json")["figures"].dump());
  EXPECT_TRUE(read_file(d / "lcm/signals.csv") == read_file(d / "inproc/signals.csv"));

  const nlohmann::json r = read_json(d / "lcm/report.json");
  const nlohmann::json& plant = r["link"]["counters"]["rejected"];
  for (const char* kind : {"size", "fingerprint", "stale", "repeated", "ahead"}) {
    EXPECT_GT(plant[kind].get<int>(), 0) << "plant: " << kind << " " << plant.dump();
  }
  EXPECT_EQ(r["link"]["counters"]["accepted"], 3000);
  EXPECT_EQ(r["link"]["drive_watchdog"]["zero_torque_ticks"], 0);
  const nlohmann::json& ctl = r["controller_process"]["link"]["counters"]["rejected"];
  for (const char* kind : {"size", "fingerprint", "stale", "repeated", "ahead"}) {
    EXPECT_GT(ctl[kind].get<int>(), 0) << "controller: " << kind << " " << ctl.dump();
  }
  EXPECT_EQ(r["controller_process"]["link"]["counters"]["accepted"], 3000);
  EXPECT_EQ(r["timing"]["controller"]["fault_monitor"]["good_frames"], 3000);
}

// The forger: it copies the session and the sender and sends a command of its own every tick (and
// NaN, out-of-range and other commands for the tick just taken). Without a key it may win commands, but the
// run never ends "completed": the plant sees two contents for one tick (or the genuine frames refused as stale
// tick after tick) and ends with exit 7 naming the hijack.
TEST(LcmBadMessages, ACopierOfSessionAndSenderIsAHijackNeverASuccess) {
  TempDir d;
  const ForgedRun f = run_with_forger(scene("monorail.toml"), d / "lcm", true);
  EXPECT_EQ(f.exit.code, 7);
  const nlohmann::json r = read_json(d / "lcm/report.json");
  ASSERT_TRUE(r["link"].contains("hijacked")) << r["link"].dump();
  EXPECT_LT(r["link"]["hijacked"]["tick"].get<int>(), 3000);
  // The genuine controller learns it from the plant's end-of-run frame and ends with the same verdict.
  const nlohmann::json& c = r["controller_process"]["link"];
  ASSERT_TRUE(c.contains("hijacked")) << c.dump();
  EXPECT_NE(r["link"]["what_happened"].get<std::string>().find("hijacked: a second source sends as controller"),
            std::string::npos)
      << r["link"].dump();
  // The plant stopped while waiting for a command: its end-of-run frame is for that tick, whose sensor frame
  // was already sent, and the controller took it as the end (not as a second frame for that tick).
  EXPECT_EQ(c["hijacked"]["evidence"], "the plant's end-of-run frame") << c.dump();
  EXPECT_EQ(c["end_of_run"]["tick"], r["link"]["end_of_run"]["tick"]);
  EXPECT_EQ(r["processes"]["what_happened"].get<std::string>().rfind("stopped on a second source", 0), 0u)
      << r["processes"]["what_happened"];
}

}  // namespace
}  // namespace gyrostab::testing

GYROSTAB_LCM_TEST_MAIN()

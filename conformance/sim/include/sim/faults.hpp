// Seeded fault injection for topsim: what a faulty device or link does to
// the frames the device model produces. Pure; no I/O.
//
//   drop=P  delay=MS  duplicate=P  bad-checksum=P  header-case=P  no-swap
//   lying-length=P  tmp-quirk  split  garbage=P  hang-on=IDENT|CLASS
//   ignore=CLASS[+CLASS...] (repeatable)
//
// Firmware faults (sim/firmware_faults.cpp; what `topconf fuzz` hunts):
//   crash-on=CLASS  hang-on=CLASS hang-s=S  slow-on=CLASS slow-ms=MS
//   answer-corrupt
// where CLASS is ident:GAY (or a bare GAY), len:N (data length) or byte:HH (a
// byte value anywhere in the frame).
//
// Device faults (sim/device.hpp DeviceFaults; each shows one field diagnosis
// of docs/DIAGNOSES.md, conformance/README.md "Faults for the diagnoses"):
//   stall=IDENT@T+S  no-stream=IDENT  ignore-motion=IDENT[+IDENT...]
//   invert=AXIS[:angle|:rate]  placeholder-identity  refuse-tracking
//   clock=month-early  stop=IDENT@T  ere=IDENT  range-form=short
// For topconf drive (docs/DRIVE.md): late=IDENT@MS  checksum-case=P  reboot=S
#pragma once

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "sim/device.hpp"
#include "top/frame.hpp"

namespace topsim {

// A class of request a firmware fault fires on.
struct InputClass {
  enum class Kind : std::uint8_t { none, ident, length, byte };
  Kind kind = Kind::none;
  std::string ident;         // ident: the three characters
  std::uint32_t length = 0;  // length: the frame's data length
  std::uint8_t byte = 0;     // byte: a byte value anywhere in the frame
  bool matches(const top::Frame& f) const noexcept;
  explicit operator bool() const noexcept { return kind != Kind::none; }
  std::string to_string() const;  // "ident:GAY", "len:20", "byte:FF"
};
// Parses "ident:GAY", "len:20" (decimal), "byte:FF" (hex) or a bare
// three-character identifier; nullopt for anything else.
std::optional<InputClass> parse_input_class(std::string_view s);

struct FaultConfig {
  double drop = 0;             // probability a frame is not sent
  std::uint32_t delay_ms = 0;  // every frame is sent this much later
  double duplicate = 0;        // probability a frame is sent twice
  double bad_checksum = 0;     // probability the checksum is corrupted
  double header_case = 0;      // probability the header case flips after the
                               // checksum was computed (the SkyDroid errata)
  bool no_swap = false;        // replies keep the client's address first
  double lying_length = 0;     // probability the length char lies (checksum
                               // valid over the bytes sent, as a C12 did)
  bool tmp_quirk = false;      // TMP answered in the malformed Topotek form
  bool split = false;          // frames cut in two writes (streams only)
  double garbage = 0;          // probability junk bytes precede a frame
  std::string hang_on;         // after this identifier, the device goes silent
  // ignore=: requests of these classes get no answer and change nothing, as
  // from firmware that does not implement them (ArduPilot's simulators
  // answer neither VER nor AWB); the device goes on answering the rest.
  std::vector<InputClass> ignore;
  // Firmware faults (docs/TOPCONF-FUZZ.md).
  InputClass crash_on;           // silent until restarted (SIGHUP, restart())
  InputClass hang_class;         // hang-on=CLASS: silent for hang_s seconds
  std::uint32_t hang_s = 0;      // 0: the hang lasts until a restart
  InputClass slow_on;            // answers (and all after) wait slow_ms
  std::uint32_t slow_ms = 1000;  //
  bool answer_corrupt = false;   // a frame failing its checksum is answered
  // late=IDENT@MS (repeatable): frames of IDENT (its replies) leave MS later.
  struct Late {
    std::string ident;
    std::uint32_t ms = 0;
  };
  std::vector<Late> late;
  double checksum_case = 0;  // probability the checksum's hex letters go lowercase
  // reboot=S: the device power-cycles S seconds after the server started
  // (topsim_server: Server::restart, streams off); 0: never.
  std::uint64_t reboot_us = 0;
  // What the device itself does wrong (handed to it as DeviceOptions::faults).
  DeviceFaults device;

  bool any() const noexcept;
};

// Parses "drop=0.1,delay=20,no-swap". Names and values are checked: an
// unknown name, a probability outside [0,1] or a missing value is an error
// naming the item.
std::optional<FaultConfig> parse_faults(std::string_view spec, std::string& error);
// The list of fault names, for --help and tests.
const std::vector<std::string_view>& fault_names();
// Every fault with its value, for --help (topsim --fault).
std::string_view fault_usage() noexcept;

// One write: bytes to send `delay_us` after the frame was produced.
struct Emission {
  std::string bytes;
  std::uint64_t delay_us = 0;
};

class FaultInjector {
 public:
  FaultInjector(FaultConfig cfg, std::uint64_t seed);

  const FaultConfig& config() const noexcept { return cfg_; }
  // Sees every request frame; returns false when the request must get no
  // answer: the device ignores its class, or has hung (streams stop).
  bool on_request(const top::Frame& request);
  // The firmware faults as well (sim/firmware_faults.cpp), at `now_us` on
  // the device's clock: false when the request gets no answer (hung,
  // crashed); answer-corrupt repairs `request` so the device answers it.
  bool admit(top::Frame& request, std::uint64_t now_us);
  // What a restart does: the device answers again (crash and hang cleared).
  void restart() noexcept;
  bool hung() const noexcept { return hung_ || crashed_ || now_us_ < hang_until_; }
  bool crashed() const noexcept { return crashed_; }
  // Turns one frame of the device into the writes that go on the link.
  // `stream_link`: a TCP connection or serial line (split applies).
  void apply(const std::string& frame, bool stream_link, std::vector<Emission>& out);

 private:
  bool chance(double p);
  FaultConfig cfg_;
  std::mt19937_64 rng_;
  bool hung_ = false;
  bool crashed_ = false;
  std::uint64_t now_us_ = 0;
  std::uint64_t hang_until_ = 0;
  std::uint64_t slow_until_ = 0;
};

}  // namespace topsim

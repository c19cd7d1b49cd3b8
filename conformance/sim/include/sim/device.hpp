// topsim's device model: a stateful gimbal camera for one model, built on
// the catalog. Pure: bytes and a time in, frames out. No I/O, no clock of
// its own (the caller passes `now_us`), so tests and fuzzers drive it
// deterministically.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sim/fanout.hpp"
#include "top/top.hpp"

namespace topsim {

// The link a request arrived on (top/device.hpp: Topotek answers only the
// link its source byte names).
using Link = top::Link;

// What a faulty device does that topdump names as a field diagnosis
// (docs/DIAGNOSES.md; topsim --fault, parsed by sim/faults.hpp). Applied by
// the device itself: it stops a push, moves an axis the wrong way, reports
// a placeholder identity.
struct DeviceFaults {
  static constexpr std::uint64_t kForever = std::numeric_limits<std::uint64_t>::max();
  // A push stream that stops: no push of `ident` from `from_us` to
  // `until_us` after the stream was switched on (stall=: it resumes;
  // no-stream=: from 0, forever, while its switch is still answered).
  struct Mute {
    std::string ident;
    std::uint64_t from_us = 0, until_us = kForever;
  };
  std::vector<Mute> mutes;
  // Motion commands echoed but not applied (ignore-motion=): the field's
  // firmware that ignores GAM/GSM/GAY (DESIGN.md field notes).
  std::vector<std::string> ignore_motion;
  // Per axis (yaw, pitch, roll): the commands that move it the other way
  // from the healthy device (invert=): kInvertAngle, kInvertRate.
  static constexpr std::uint8_t kInvertAngle = 1, kInvertRate = 2;
  std::uint8_t invert[3] = {0, 0, 0};
  // Identity replies are factory placeholders (placeholder-identity).
  bool placeholder_identity = false;
  // The TRC start answered with state 4 (refuse-tracking; --no-tracking).
  bool refuse_tracking = false;
  // TIM/UTC writes answered with the camera's clock one month early, as a
  // clock set with a 0-based month (clock=month-early).
  bool clock_month_early = false;
  // A push stream switched off by the device `from_us` after it was turned
  // on (stop=IDENT@T): it stays off until the client switches it on again,
  // and stops once only (topconf drive 1.3).
  std::vector<Mute> stops;
  // Requests of these identifiers answered with ERE where the dialect has
  // one (SkyDroid), silence on Topotek (ere=IDENT; topconf drive 5.1).
  std::vector<std::string> ere;
  // The LRF range answered without the document's zero padding, `12.5`
  // where Topotek 5.9 gives `00012.5` (range-form=short; topconf drive 8.3).
  bool range_short = false;

  bool any() const noexcept {
    return !mutes.empty() || !ignore_motion.empty() || invert[0] || invert[1] || invert[2] ||
           placeholder_identity || refuse_tracking || clock_month_early || !stops.empty() ||
           !ere.empty() || range_short;
  }
  // Whether pushes of `ident` never come (no-stream=).
  bool never_pushes(std::string_view ident) const noexcept {
    for (const Mute& m : mutes)
      if (m.ident == ident && m.from_us == 0 && m.until_us == kForever) return true;
    return false;
  }
  // Whether a push of `ident` is withheld `since_on_us` after its stream
  // was switched on.
  bool muted(std::string_view ident, std::uint64_t since_on_us) const noexcept {
    for (const Mute& m : mutes)
      if (m.ident == ident && since_on_us >= m.from_us && since_on_us < m.until_us) return true;
    return false;
  }
};

struct DeviceOptions {
  // Where the device's behaviour comes from (top/device.hpp): field
  // evidence, then the document's examples, then its rules; or the
  // document alone. Each trait below overrides the profile when set.
  top::Profile profile = top::Profile::field;
  std::optional<top::Order> push_order;    // GAC/GIC pushes
  std::optional<top::Header> push_header;  // fixed (#TP) or variable (#tp)
  std::optional<top::Order> reply_order;   // replies to reads
  std::optional<top::Header> reply_header;
  // The attitude reports the opposite sign of every yaw (pitch) command
  // (true), of none (false); unset: the model's sign traits, each for the
  // identifiers its evidence names (top::Trait::idents).
  std::optional<bool> yaw_inverted;
  std::optional<bool> pitch_inverted;
  std::optional<bool> field_ptz;  // C13: PTZ codes the field says work
  bool swap_addresses = true;     // false: the no-swap fault (client first)
  bool tmp_quirk = false;         // answer TMP in the malformed #tpDU16wTMP form
  // A speed command holds for this long unless refreshed; 0: the model's
  // (top::speed_hold_ms, from the speed_refresh trait).
  std::uint32_t speed_hold_ms = 0;
  // Push rate of Topotek GIC/GAC streams, which GIA/GAA only switch on.
  std::uint32_t topotek_stream_hz = 10;
  // Identity: SkyDroid's VER and MOD replies, Topotek's VSN and PA2 (empty:
  // the model's defaults: SkyDroid V1.0.78, the form ArduPilot's SkyDroid
  // driver parses, and the model's name, C12; Topotek the version a real
  // Topotek camera answered, 1.6.26.R.D (PixEagle session
  // 20260917T185212Z-identity 18:52:16.574300 #tpDPArVSN1.6.26.R.D62), and
  // the model name SIP, which no capture shows: PA2 was never asked there).
  std::string version;
  std::string model_name;
  // Topotek tracking: false for a lens that cannot track (TRC state 4,
  // ArduPilot PR #31768).
  bool tracking = true;
  // What the Topotek rangefinder measures, in metres: the result a
  // measuring LRF write is answered with (X1X2X3X4X5.X6, Topotek 5.9).
  double range_m = 1234.5;
  // The UDP traits of a real unit (top/device.hpp: ephemeral_reply_port,
  // fan_out, duplicate_to_client_port; sim/fanout.hpp): unset, the
  // profile's (field: the model's traits; document: none).
  std::optional<bool> ephemeral_reply_port;
  std::optional<bool> fan_out;
  std::optional<bool> duplicate;
  // true: echo every valid write top::write_reply gives no answer (the
  // document gives it no reply form; a real Topotek camera echoes none:
  // silent_writes); unset or false: answer each write as write_reply says.
  std::optional<bool> write_echo;
  // true: answer a request whatever link its source address names (a
  // Topotek U request over the network too); topconf drive sets it in
  // every case but 6.4, which alone judges the driver's source address.
  bool any_source = false;
  DeviceFaults faults;
};

// One gimbal axis: an angle moving toward a target at a speed, or turning
// at a commanded rate until the rate expires.
struct Axis {
  double angle = 0;  // deg
  double min = -90, max = 90;
  bool has_target = false;
  double target = 0;        // deg
  double target_speed = 0;  // deg/s
  double rate = 0;          // deg/s
  std::uint64_t rate_until = 0;
};

// An attitude stream switched on by GAA (SkyDroid, rate in Hz) or GIA/GAA
// (Topotek, on/off).
struct Stream {
  std::string ident;            // GAC or GIC
  std::uint32_t period_us = 0;  // 0: off
  std::uint64_t next_us = 0;
  char dst = 'U';           // client address the pushes go to
  std::uint64_t on_us = 0;  // when it was switched on
};

// The Topotek tracker (field: ArduPilot AP_Mount_Topotek PR #27568 and
// #31768, PixEagle sessions on a real Topotek camera; sim/src/device_topotek.cpp).
struct Tracking {
  char state = '0';             // TRC data char 1: 0 stopped, 1 waiting, 2 tracking, 4 no lens
  std::uint64_t starts_us = 0;  // a LOC while waiting: tracking from then (0: none)
  std::uint64_t next_box_us = 0;
  std::uint64_t on_us = 0;    // when tracking (and the OFT push) started
  std::int16_t x = 0, y = 0;  // LOC centre on the +/-1000 grid
  std::uint16_t w = 0, h = 0;
  char dst = 0, device = 0;  // the LOC's source and destination: where OFT goes, from whom
  std::string_view push;     // the frames of the LOC's stream (top::stream_enabled_by: OFT)
};

class Device {
 public:
  explicit Device(top::Model model, DeviceOptions opts = {});

  top::Model model() const noexcept { return model_; }
  // One trait as the device applies it, with its source.
  struct TraitLine {
    std::string name;    // the switch: "push-order"
    std::string value;   // "request-order"
    std::string source;  // "field", "document example", "document rule", "option"
    std::string evidence;
  };
  // Every trait of this device (for `topsim --describe`).
  std::vector<TraitLine> describe() const;
  top::Dialect dialect() const noexcept { return dialect_; }
  const DeviceOptions& options() const noexcept { return opts_; }

  // Handles one parsed request received on `link` at `now_us` and appends
  // the frames the device sends back (none for silence).
  void handle(const top::Frame& request, Link link, std::uint64_t now_us,
              std::vector<std::string>& out);

  // When the next stream frame is due (max() when no stream runs).
  std::uint64_t next_timer() const noexcept;
  // Appends the stream frames due at `now_us`.
  void poll(std::uint64_t now_us, std::vector<std::string>& out);

  // State, for tests and the console.
  const Axis& yaw() const noexcept { return axes_[0]; }
  const Axis& pitch() const noexcept { return axes_[1]; }
  const Axis& roll() const noexcept { return axes_[2]; }
  void advance(std::uint64_t now_us) noexcept;
  // Takes new options (faults, identity, forms) and keeps the state: the
  // axes, the streams (their switch-on time now, so that a fault's times
  // count from here), recording, settings (topconf drive --persistent: the
  // device changes case in place).
  void reconfigure(DeviceOptions opts, std::uint64_t now_us);
  bool recording() const noexcept { return recording_; }
  std::uint32_t file_index() const noexcept { return file_index_; }
  // The stored data of a setting (written value or default), "" if none.
  std::string setting(std::string_view ident) const;
  const std::vector<Stream>& streams() const noexcept { return streams_; }
  // The UDP traits the device applies (its profile's, then the options'),
  // for the transports that send its datagrams.
  UdpTraits udp_traits() const noexcept;
  // Whether a valid write of `cmd` gets no answer: top::write_reply says
  // nothing and write_echo is not on.
  bool silent_write(const top::CommandSpec& cmd) const noexcept;
  const Tracking& tracking() const noexcept { return tracking_; }
  std::uint64_t requests() const noexcept { return requests_; }

 private:
  bool accepts(const top::Frame& f, Link link) const noexcept;
  // A reply to `req` under header `h`, its addresses swapped unless no-swap:
  // the spec, for a reply with a malformation of its own, or the frame.
  top::BuildSpec reply_spec(top::Header h, const top::Frame& req, char control,
                            std::string_view ident, std::string_view data) const;
  std::string make(top::Header h, const top::Frame& req, char control, std::string_view ident,
                   std::string_view data) const;
  void reply_error(const top::Frame& req, std::vector<std::string>& out) const;
  // The commands with state behind them (sim/src/device_handlers.cpp): true
  // when a handler answered `req`.
  bool dispatch(const top::Frame& req, const top::Decoded& dec, std::uint64_t now_us,
                std::vector<std::string>& out);
  friend struct Handlers;
  // The Topotek commands of sim/src/device_topotek.cpp, asked first: true
  // when one answered `req`.
  bool dispatch_topotek(const top::Frame& req, const top::Decoded& dec, std::uint64_t now_us,
                        std::vector<std::string>& out);
  // Tracking's state changes and OFT pushes due at `now_us`.
  void poll_topotek(std::uint64_t now_us, std::vector<std::string>& out);
  // One OFT tracking box of `t` with `status` ('2' tracking, '1' stopped).
  void push_box(const Tracking& t, char status, std::vector<std::string>& out) const;
  void describe_topotek(std::vector<TraitLine>& out) const;
  void describe_udp(std::vector<TraitLine>& out) const;
  friend struct TopotekHandlers;
  // The form of a reply to `req`: form_of, and the request's header kept
  // where the keeps_request_header trait applies and the length fits it.
  top::DeviceForm reply_form(const top::Frame& req, std::string_view ident,
                             std::size_t length) const;
  bool field() const noexcept { return opts_.profile == top::Profile::field; }
  void start_stream(std::string_view ident, std::uint32_t hz, char dst, std::uint64_t now_us);
  // The attitude as the report `ident` carries it (GAC, GIC, GIA: the
  // signs of top::motion_of under the profile).
  std::string attitude_data(std::string_view ident) const;
  std::string read_data(const top::CommandSpec& cmd, const top::FormSpec& form) const;
  // The form of a reply or push of `ident` with `length` data chars: the
  // profile's, then the options' overrides, then the no-swap fault.
  top::DeviceForm form_of(std::string_view ident, top::Sent sent, std::size_t length) const;
  std::string build(const top::DeviceForm& form, char client, char device, char control,
                    std::string_view ident, std::string_view data) const;

  top::Model model_;
  top::Dialect dialect_;
  DeviceOptions opts_;
  // Whether a command of `ident` moves `axis` (0 yaw, 1 pitch) the other
  // way from what the attitude reports.
  bool inverted(std::size_t axis, std::string_view ident) const noexcept;
  // The faults' motion (DeviceFaults): commands of `ident` move nothing;
  // commands of `kind` move `axis` the other way.
  bool ignores_motion(std::string_view ident) const noexcept;
  bool fault_inverts(std::size_t axis, top::MotionKind kind) const noexcept;
  const top::Trait* sign_trait_[2] = {nullptr, nullptr};
  bool field_ptz_ = false;
  Axis axes_[3];
  std::uint64_t now_us_ = 0;
  bool recording_ = false;
  std::uint32_t file_index_ = 0;
  double zoom_ = 1.0;
  std::map<std::string, std::string, std::less<>> settings_;
  std::vector<Stream> streams_;
  std::uint64_t requests_ = 0;
  Tracking tracking_;
  bool keeps_header_ = false;
  std::uint32_t stops_fired_ = 0;  // DeviceFaults::stops that fired, a bit each
};

// The request handler as a function (the fuzz entry point): one datagram's
// bytes in, the frames the device answers out. Never throws on any input.
// Through sim/intake.hpp's Intake, as every transport.
std::vector<std::string> handle_datagram(Device& device, std::string_view bytes, Link link,
                                         std::uint64_t now_us);

}  // namespace topsim

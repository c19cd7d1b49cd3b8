// Driver profiles: what each public client of these cameras sends and what
// it needs from the device, every fact with the public source it was read
// from (docs/COMPAT.md). Facts carried over, never code. Pure data; no I/O.
//
// A profile's needs become a topconf matrix (drivers/compat.hpp), graded:
// must (without it the driver breaks), should (a feature is lost), info.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "top/top.hpp"

namespace drivers {

enum class Grade : std::uint8_t { must, should, info };
std::string_view to_string(Grade g) noexcept;

// Where a fact was read: repository, file, commit or pull request.
struct Source {
  std::string_view repo, path, ref;
};
// "repo path @ ref", as every listing of a profile names its sources.
std::string to_string(const Source& s);

enum class LinkKind : std::uint8_t { serial, udp, tcp };
std::string_view to_string(LinkKind k) noexcept;

// The link the driver flies the camera over.
struct LinkSpec {
  LinkKind kind = LinkKind::udp;
  std::uint32_t baud = 0;         // serial
  std::uint16_t device_port = 0;  // UDP/TCP: where it sends
  std::uint16_t listen_port = 0;  // UDP: where it reads answers (0: the asking port)
  std::string_view note;
  int source = 0;  // index into Profile::sources
};

// A frame the driver sends, and how often.
struct Sent {
  std::string_view ident;
  char control = 'w';
  std::string_view data;  // an example of its data
  char dst = 0;
  bool fixed = true;  // #TP (else #tp)
  double hz = 0;      // 0: on command only
  int slot = -1;      // its step in a 1 Hz round robin of ten ticks, -1: none
  bool until_answered = false;
  std::string_view note;
  int source = 0;
};

// What a case checks of the device's answer.
enum class Check : std::uint8_t {
  reply,   // a frame `ident` whose data match `pattern`
  stream,  // pushes of `ident` whose data match `pattern`, at min_hz or more, no gap over
           // max_gap_ms (and, with move_axis, the attitude turning)
  taken,   // no ERE: an echo, a reply of the request's identifier, or silence
};

// The data of an attitude both drivers parse: twelve hex characters first,
// yaw, pitch and roll as signed 16-bit 0.01 deg (the whole data must match).
inline constexpr std::string_view kAngles12 = "[0-9A-Fa-f]{12}[\\s\\S]*";

// One thing the driver needs, and what it loses without it.
struct Need {
  std::string_view id;       // stable: the case is driver/<profile>/<id>
  std::string_view feature;  // what is lost ("attitude", "firmware version")
  Grade grade = Grade::must;
  std::string_view reasoning;  // the driver's line of reasoning this case protects
  std::string_view lost;       // what the driver does without it
  int source = 0;
  // What the case sends: a request (ident, control, data, dst; #TP when
  // `fixed`), or a `raw` frame text (checksum added when absent), or exact
  // bytes as `raw_hex`.
  std::string_view send_ident;
  char send_control = 'r';
  std::string_view send_data = "00";
  char send_dst = 0;  // 0: the identifier's address class
  bool send_fixed = true;
  std::string_view raw;
  std::string_view raw_hex;
  Check check = Check::reply;
  std::string_view ident;          // the frame the driver reads (reply, stream)
  std::string_view pattern;        // ECMAScript regex its data must match (empty: any)
  bool any_addresses = true;       // false: the driver needs the addresses swapped
  double min_hz = 0, max_hz = 0;   // stream
  std::uint32_t max_gap_ms = 0;    // stream
  std::uint32_t window_ms = 0;     // stream: how long it is watched; reply: the wait (0: matrix)
  std::string_view cleanup_ident;  // a write sent after the case (REC 00 after REC 01)
  std::string_view cleanup_data;
  // A write sent before the case (the stream it watches switched on).
  std::string_view on_ident;
  std::string_view on_data;
  // stream: the attitude must turn on this axis (top::Axis; -1: not
  // watched) by move_min_deg or more, the move_sign way (+1 right or up, -1
  // left or down), while the case's request holds: a rate command the
  // driver steers with, taken and moving the way it expects.
  int move_axis = -1;
  int move_sign = 0;
  double move_min_deg = 0;
};

struct Profile {
  std::string_view name;           // ardupilot-topotek
  std::string_view title;          // "ArduPilot AP_Mount_Topotek (upstream)"
  std::vector<top::Model> models;  // the first is the default of --driver
  LinkSpec link;
  std::uint32_t tick_ms = 100;  // the driver's main cadence
  std::vector<Source> sources;
  std::vector<Sent> sends;
  std::vector<Need> needs;
  // How strictly it parses what it reads, each with its source index; and
  // what topconf cannot check of it.
  std::vector<std::pair<std::string_view, int>> parsing;
  std::vector<std::string_view> unchecked;
  bool serves(top::Model m) const noexcept;
};

// Every profile, in the order `topconf drivers` lists them.
const std::vector<Profile>& profiles();
const Profile* find_profile(std::string_view name) noexcept;

// The profiles of each family, defined in profiles_<family>.cpp.
Profile ardupilot_topotek();
Profile pixeagle();
Profile ardupilot_skydroid();
Profile skydroid_gcs();
Profile c10pro_tool();

}  // namespace drivers

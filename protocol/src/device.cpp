// Device behaviour tables: streams, write replies, recorded frame forms and
// firmware traits, each with its source. See top/device.hpp.
#include "top/device.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <string>

#include "catalog_data.hpp"
#include "device_form.hpp"
#include "top/enum_names.hpp"
#include "top/text.hpp"

#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace top {
namespace {

using detail::c10;
using detail::c10pro;
using detail::c12;
using detail::c13;
using detail::c20;
using detail::sip;

constexpr std::string_view kSource[] = {"document example", "document rule", "field"};
static_assert(std::size(kSource) == static_cast<std::size_t>(Source::field) + 1);
constexpr std::string_view kProfile[] = {"field", "document"};
static_assert(std::size(kProfile) == static_cast<std::size_t>(Profile::document) + 1);
constexpr std::string_view kWriteReply[] = {"echo", "data", "file index", "nothing"};
static_assert(std::size(kWriteReply) == static_cast<std::size_t>(WriteReply::nothing) + 1);
constexpr std::string_view kOrder[] = {"swapped", "request order"};
static_assert(std::size(kOrder) == static_cast<std::size_t>(Order::request_order) + 1);
constexpr std::string_view kTraitKind[] = {
    "yaw-inverted",  "pitch-inverted",       "answers-to-source", "link-by-source",
    "speed-refresh", "keeps-request-header", "double-checksum"};
static_assert(std::size(kTraitKind) == static_cast<std::size_t>(TraitKind::double_checksum) + 1);
constexpr std::string_view kLink[] = {"network", "uart"};
static_assert(std::size(kLink) == static_cast<std::size_t>(Link::uart) + 1);
constexpr std::string_view kRejection[] = {"none", "unsupported", "invalid"};
static_assert(std::size(kRejection) == static_cast<std::size_t>(Rejection::invalid) + 1);

constexpr StreamSpec kStreams[] = {
    {.dialect = Dialect::skydroid,
     .request = "GAA",
     .push = "GAC",
     .rate_in_data = true,
     .section = "SkyDroid 3.3.2",
     .note = "GAA 01-64 (hex) pushes GAC at 1-100 Hz; 00 stops it"},
    {.dialect = Dialect::skydroid,
     .request = "FAE",
     .push = "FAI",
     .sender = Sender::client,
     .section = "SkyDroid 3.3.6",
     .note = "FAE 01 lets the flight controller send its attitude as FAI writes; "
             "the document gives FAI no reply"},
    {.dialect = Dialect::topotek,
     .request = "GAA",
     .push = "GAC",
     .section = "Topotek 3.4",
     .note = "GAA 01 switches the gimbal attitude push on, 00 off; the rate is "
             "the device's"},
    {.dialect = Dialect::topotek,
     .request = "GIA",
     .push = "GIC",
     .section = "Topotek 3.6",
     .note = "GIA 01 switches the gyroscope attitude push on, 00 off; the rate "
             "is the device's"},
    // The field: pushes the documents do not give. After the document's
    // entry of the same request, so that stream_enabled_by() without a
    // profile keeps the document's.
    {.dialect = Dialect::topotek,
     .request = "GIA",
     .push = "GIA",
     .section = "field: ArduPilot AP_Mount_Topotek (PR #28455); a real SIP (issue 28)",
     .note = "GIA 01 pushes 12-char GIA attitude frames (yaw, pitch down positive, roll in "
             "0.01 deg); ArduPilot's driver re-sends the enable once a second and is healthy "
             "only while GIA frames arrive",
     .evidence =
         "AP_Mount_Topotek.cpp sends #TPUG2wGIA013E once a second and parses only GIA "
         "for attitude (it parsed GAC before: PR #28455 per issue 28); ArduPilot's SIM_Topotek "
         "pushes #TPUGCrGIA at 10 Hz; a real SIP answers the GIC query with a 12-char "
         "GIA (issue 28 log, PixEagle bench notes)"},
    {.dialect = Dialect::topotek,
     .request = "LOC",
     .push = "OFT",
     .section = "field: PixEagle bench notes on a real SIP",
     .note = "a tracking start (LOC) pushes OFT tracking boxes at about video rate while the "
             "unit tracks; after a cancel one OFT with an all-zero box and status 1",
     .evidence = "PixEagle bench notes (a real SIP: 99 OFT in one session; the vendor's "
                 "tracking PDF section 7); issue 28: OFT at about 30 Hz while it tracks"},
};

constexpr DeviceForm kForms[] = {
    // SkyDroid 3.3.2.2, receive example: "#TPUGCrGACY0Y1Y2Y3P0P1P2P3R0R1R2R3CC".
    {.dialect = Dialect::skydroid,
     .models = c10 | c10pro | c12 | c20,
     .ident = "GAC",
     .control = 'r',
     .sent = Sent::push,
     .header = Header::fixed,
     .order = Order::request_order,
     .source = Source::document_example,
     .evidence = "SkyDroid 3.3.2.2 example #TPUGCrGACY0Y1Y2Y3P0P1P2P3R0R1R2R3CC: "
                 "uppercase #TP, U first"},
    {.dialect = Dialect::skydroid,
     .models = c12,
     .ident = "GAC",
     .control = 'r',
     .sent = Sent::push,
     .header = Header::variable,
     .order = Order::request_order,
     .source = Source::field,
     .evidence = "real C12s push #tpUGCrGAC<12 hex><cs>: an Android app and two Python "
                 "C12 drivers (one checks the checksum) accept only that prefix"},
    // SkyDroid 4.22, reply example: "#TPUD4rSLR0005BC".
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "SLR",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::fixed,
     .order = Order::request_order,
     .source = Source::document_example,
     .evidence = "SkyDroid 4.22 reply example #TPUD4rSLR0005BC: #TP with length 4, U first"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "SLR",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::fixed,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a public C13 SDK takes a range only from a datagram holding #TPDU and "
                 "SLR: #TP with length 4, addresses swapped"},
    {.dialect = Dialect::skydroid,
     .models = c12,
     .ident = "IMG",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::fixed,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a Python C12 console reads the thermal palette only from a reply that "
                 "starts #TPDU and holds IMG"},
    {.dialect = Dialect::skydroid,
     .models = c12,
     .ident = "VER",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::variable,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a real C12 answered VER with #tpDU3rVER0105025A (its length char lies)"},
    // Topotek 3.5: "receive: #tpGU C r GIC Y0Y1Y2Y3P0P1P2P3R0R1R2R3 CC".
    {.dialect = Dialect::topotek,
     .models = sip,
     .ident = "GIC",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::variable,
     .order = Order::swapped,
     .source = Source::document_example,
     .evidence = "Topotek 3.5 example #tpGU C r GIC Y0Y1Y2Y3P0P1P2P3R0R1R2R3 CC"},
    {.dialect = Dialect::topotek,
     .models = sip,
     .ident = "GAC",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::variable,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a Topotek device answered #tpGPCrGACFF36ED5A0048DE to a network client"},
    {.dialect = Dialect::topotek,
     .models = sip,
     .ident = "GIA",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::variable,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a real SIP (firmware 1.6.26.R.D) answered the GIC query #TPPG2rGIC0035 with "
                 "#tpGPCrGIA + 12 hex (issue 28 log; PixEagle: GIC queries consistently got "
                 "GIA replies)"},
    {.dialect = Dialect::topotek,
     .models = sip,
     .ident = "GMS",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::variable,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a real Topotek unit answered #tpPG2rGMS0089 with #tpGP2rGMS018A: #tp kept on "
                 "a 2-data-char reply (issue 28 log)"},
    // Lengths that count bytes. The SLR reply is of a C14 Pro, a model the
    // catalog does not list: no model bit, so only a capture of unknown
    // model matches it.
    {.dialect = Dialect::skydroid,
     .models = c12,
     .ident = "IMG",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::fixed,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a C12 Android app (log114/PTZControl C12Service.kt) waits for #TPDU1rIMG and "
                 "takes the 2 chars after IMG as the palette: length 1 for 2 data chars",
     .length_in_bytes = true},
    {.dialect = Dialect::skydroid,
     .ident = "SLR",
     .control = 'r',
     .sent = Sent::reply,
     .header = Header::fixed,
     .order = Order::swapped,
     .source = Source::field,
     .evidence = "a real device answered the range read with #TPDU2rSLR0018BE, data 0018 = 24 dm "
                 "under length 2 (a Qt ground station's lgs::SkydroidSdkClient note; a C14 Pro "
                 "per issue 28)",
     .length_in_bytes = true},
};

constexpr Trait kTraits[] = {
    {.kind = TraitKind::yaw_inverted,
     .dialect = Dialect::skydroid,
     .models = c12,
     .source = Source::field,
     .evidence = "for: two public C12 clients negate yaw before GAY/GAM; one notes the attitude "
                 "reports the opposite sign of the GAM input. Against: a C12 Android app "
                 "(log114/PTZControl) turns left with GSY E2, the document's sign",
     .idents = "GAY GAM"},
    {.kind = TraitKind::pitch_inverted,
     .dialect = Dialect::skydroid,
     .models = c12,
     .source = Source::field,
     .evidence = "for: one public C12 client negates pitch before GAM (\"attitude telemetry "
                 "reports yaw/pitch with opposite signs from GAM input\"; that client was not "
                 "found again in docs/sources/ardupilot.md's search), and a C12 visual-servoing "
                 "README's tuning example sets inv_y (image to pitch: weak). Against: a C12 "
                 "Android app (log114/PTZControl) sends GAP DCD8 (-90.00) for down and GSP +30 "
                 "for up, the document's signs; AP_Mount_SkyDroid (C11, PR #34155) and a C13 "
                 "station (custom-GCS) keep pitch up positive, and SkyDroid told the driver's "
                 "author the C11/C13 commands are the same; with it ArduPilot's driver drives "
                 "pitch to +90 after a -30 target (issue 28). Unconfirmed",
     .idents = "GAM"},
    {.kind = TraitKind::yaw_inverted,
     .dialect = Dialect::skydroid,
     .models = c13,
     .source = Source::field,
     .evidence = "on the wire +GSY makes GAC yaw decrease, the reverse of SkyDroid 3.2.1: "
                 "AP_Mount_SkyDroid negates GSY (\"a positive GSY value moves yaw LEFT\", real "
                 "C11, PR #34155; SkyDroid says C11/C13 commands are the same) and a station "
                 "used on a real C13 (custom-GCS, _LRF_C13_INVERT_GSY) agrees; which of GSY or "
                 "GAC yaw differs from the document physically is not established",
     .idents = "GSY"},
    {.kind = TraitKind::answers_to_source,
     .dialect = Dialect::skydroid,
     .models = c10 | c10pro | c12 | c13 | c20,
     .source = Source::field,
     .evidence = "C12 clients send from UDP 5000 to 5000 (the vendor's app does) and read "
                 "the replies on that socket: the device answers the datagram's source"},
    {.kind = TraitKind::link_by_source,
     .dialect = Dialect::topotek,
     .models = sip,
     .source = Source::document_rule,
     .evidence = "Topotek 2: the source byte names the interface (P network, U UART); a "
                 "UDP request with source U gets no answer (public Topotek clients agree)"},
    {.kind = TraitKind::speed_refresh,
     .dialect = Dialect::skydroid,
     .models = c10 | c10pro | c12 | c20,
     .value = 1000,
     .source = Source::field,
     .evidence = "autopilot drivers refresh speed commands at 10-50 Hz: without a refresh "
                 "the motors stop"},
    {.kind = TraitKind::keeps_request_header,
     .dialect = Dialect::topotek,
     .models = sip,
     .source = Source::field,
     .evidence = "a real unit answers #tpPG2rGMS0089 with #tpGP2rGMS018A (#tp kept on 2 data "
                 "chars) and #TPPD2rTRC0048 with #TPDP2rTRC0048 (issue 28 log)"},
    {.kind = TraitKind::double_checksum,
     .dialect = Dialect::skydroid,
     .models = c10pro,
     .source = Source::field,
     .evidence = "a C10 Pro tool (DifferentialRobotics/C10Pro_Control README) sends "
                 "#TPUG2wPTZ056FEB, #TPUG2wPTZ016BE3, #TPUG2wPTZ026CE5: a valid frame, then a "
                 "checksum over it and its checksum; that the camera takes them is the tool "
                 "author's claim",
     .idents = "PTZ"},
};

// SkyDroid 3.1 lists PTZ for C10, C10Pro, C12 and C20, and 0E-13 as trim.
constexpr std::int64_t kC13Ptz[] = {0x02, 0x05, 0x0E, 0x0F, 0x10, 0x11, 0x12, 0x13};
// ArduPilot's SkyDroid driver sends these PTZ codes to C11 and C13 alike.
constexpr std::int64_t kC13PtzDriver[] = {0x05, 0x06, 0x07};
constexpr FieldSupport kFieldSupport[] = {
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "PTZ",
     .values = kC13Ptz,
     .evidence = "a public C13 SDK (skydroid_c13_miniSDK) reports PTZ 02 (down), 05 "
                 "(center) and 0E/0F pitch +/-, 10/11 yaw +/-, 12/13 roll +/- working on a "
                 "real C13"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "PTZ",
     .values = kC13PtzDriver,
     .evidence = "AP_Mount_SkyDroid (PR #34155, https://github.com/ArduPilot/ardupilot/pull/"
                 "34155) sends PTZ 06 follow, 07 lock and 05 centre to C11 and C13 alike; its "
                 "author: SkyDroid confirmed the C11/C13 commands are the same"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "GAA",
     .evidence = "AP_Mount_SkyDroid (PR #34155) turns the C13's attitude on with "
                 "#TPUG2wGAA323A (SkyDroid confirmed the C11/C13 commands are the same); a "
                 "station used on a real C13 (custom-GCS) sends GAA 1-100 Hz"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "GAC",
     .evidence = "a station used on a real C13 (custom-GCS) reads GAC attitude "
                 "(#TPUG2rGAC00); AP_Mount_SkyDroid (PR #34155) reads the C13's GAC pushes"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "GSY",
     .evidence = "AP_Mount_SkyDroid (PR #34155) drives C11 and C13 yaw with GSY (SkyDroid "
                 "confirmed the C11/C13 commands are the same); a station used on a real C13 "
                 "(custom-GCS) sends GSY"},
    {.dialect = Dialect::skydroid,
     .models = c13,
     .ident = "GSP",
     .evidence = "AP_Mount_SkyDroid (PR #34155) drives C11 and C13 pitch with GSP (SkyDroid "
                 "confirmed the C11/C13 commands are the same); a station used on a real C13 "
                 "(custom-GCS) sends GSP, sign as documented"},
};

bool same(std::string_view a, std::string_view b) noexcept { return a == b; }

bool model_in(ModelSet set, Model m) noexcept {
  return m == Model::unknown || (set & model_bit(m)) != 0;
}

}  // namespace

std::string_view to_string(Source s) noexcept { return enum_name(kSource, s); }
std::string_view to_string(Profile p) noexcept { return enum_name(kProfile, p); }

std::optional<Profile> profile_from_string(std::string_view s) noexcept {
  return enum_from_name<Profile>(kProfile, s);
}

std::span<const StreamSpec> streams() noexcept { return kStreams; }

std::optional<unsigned> switch_value(std::string_view data) noexcept {
  if (data.empty() || data.size() > 8) return std::nullopt;
  unsigned v = 0;
  for (char ch : data) {
    const int x = hex_value(ch);
    if (x < 0) return std::nullopt;
    v = v * 16 + static_cast<unsigned>(x);
  }
  return v;
}

const StreamSpec* stream_enabled_by(Dialect d, std::string_view request) noexcept {
  return stream_enabled_by(d, request, Profile::document);
}

const StreamSpec* stream_enabled_by(Dialect d, std::string_view request, Profile profile) noexcept {
  const StreamSpec* document = nullptr;
  for (const StreamSpec& s : kStreams) {
    if (s.dialect != d || !same(s.request, request)) continue;
    if (s.from_field() && profile == Profile::field) return &s;
    if (!s.from_field() && !document) document = &s;
  }
  return document;
}

const StreamSpec* stream_of(Dialect d, std::string_view push) noexcept {
  return stream_of(d, push, Profile::field);
}

const StreamSpec* stream_of(Dialect d, std::string_view push, Profile profile) noexcept {
  for (const StreamSpec& s : kStreams)
    if (s.dialect == d && same(s.push, push) && (!s.from_field() || profile == Profile::field))
      return &s;
  return nullptr;
}

std::string_view to_string(WriteReply r) noexcept { return enum_name(kWriteReply, r); }

WriteReply write_reply(const CommandSpec& cmd) noexcept {
  const StreamSpec* s = stream_of(cmd.dialect, cmd.ident);
  if (s && s->sender == Sender::client) return WriteReply::nothing;
  for (const FormSpec& f : cmd.forms) {
    if (f.control != 'w' || f.role != Role::response) continue;
    // Topotek 5.1/5.2: REC and CAP answer with the state and a file index.
    if (cmd.dialect == Dialect::topotek && (cmd.ident == "REC" || cmd.ident == "CAP"))
      return WriteReply::file_index;
    return cmd.ident == "ERE" ? WriteReply::echo : WriteReply::data;
  }
  return WriteReply::echo;
}

std::string_view to_string(Order o) noexcept { return enum_name(kOrder, o); }

std::span<const DeviceForm> device_forms() noexcept { return kForms; }

DeviceForm device_form(Model model, std::string_view ident, char control, Sent sent,
                       std::size_t data_length, Profile profile) noexcept {
  const Dialect d = dialect_of(model);
  const DeviceForm* example = nullptr;
  const DeviceForm* field = nullptr;
  for (const DeviceForm& f : kForms) {
    if (f.dialect != d || !model_in(f.models, model) || f.ident != ident || f.control != control ||
        f.sent != sent)
      continue;
    if (f.source == Source::field && !field) field = &f;
    if (f.source == Source::document_example && !example) example = &f;
  }
  if (profile == Profile::field && field) return *field;
  if (example) return *example;
  const CommandSpec* cmd = find_command(d, ident);
  DeviceForm rule;
  rule.dialect = d;
  rule.models = model == Model::unknown ? 0 : model_bit(model);
  rule.ident = ident;
  rule.control = control;
  rule.sent = sent;
  rule.header = choose_header(d, cmd ? cmd->address : 'G', data_length);
  rule.order = Order::swapped;
  rule.source = Source::document_rule;
  rule.evidence = d == Dialect::topotek
                      ? "Topotek 2: the reply swaps the addresses; #TP for 2 data chars, #tp "
                        "otherwise and for M class"
                      : "SkyDroid 2.3.1: the reply swaps the addresses; 2.2.2: #TP for G class "
                        "and 2 data chars, #tp otherwise";
  return rule;
}

const DeviceForm* recorded_form(Dialect d, Model model, const Frame& f, Sent sent) noexcept {
  const Order order = is_client_address(f.src) ? Order::request_order : Order::swapped;
  const std::string_view ident = f.ident_view();
  const DeviceForm* best = nullptr;
  for (const DeviceForm& x : kForms) {
    if (x.dialect != d || !model_in(x.models, model) || x.ident != ident ||
        x.control != f.control || x.sent != sent || x.header != f.header || x.order != order)
      continue;
    // Field evidence names the firmware; prefer it to an example of the same form.
    if (!best || x.source == Source::field) best = &x;
  }
  return best;
}

void detail::note_device_form(const Frame& f, Model model, bool detail, Decoded& dec) {
  const bool unswapped = role_from_addresses(f) == Role::request;
  Finding* tp = nullptr;
  Finding* un = nullptr;
  for (Finding& x : dec.findings) {
    if (x.code == FindingCode::tp_length && x.severity != Severity::info) tp = &x;
    if (x.code == FindingCode::unswapped_addresses) un = &x;
  }
  if (!unswapped && !tp) return;
  const StreamSpec* st = stream_of(dec.dialect, f.ident_view());
  const bool push = st && st->sender == Sender::device;
  const DeviceForm* rf = recorded_form(dec.dialect, model, f, push ? Sent::push : Sent::reply);
  // The evidence itself goes in the finding's quirk; the message says
  // which kind of source records the form.
  auto source = [&] { return "; as recorded (" + std::string(to_string(rf->source)) + ")"; };
  if (unswapped && !un) {
    std::string msg;
    if (detail)
      msg = rf ? std::string(f.ident_view()) + (push ? " push" : " reply") + " addressed " + f.src +
                     " to " + f.dst + " (the request's order)" + source()
               : std::string("a response addressed ") + f.src + " to " + f.dst +
                     " (the request's order; some simulators)";
    dec.findings.push_back(make_finding(FindingCode::unswapped_addresses, 3, std::move(msg)));
    un = &dec.findings.back();
    tp = nullptr;
    for (Finding& x : dec.findings)
      if (x.code == FindingCode::tp_length && x.severity != Severity::info) tp = &x;
  } else if (un && rf && detail) {
    un->message += source();
  }
  if (!rf) return;
  if (un) un->quirk = rf->evidence;
  if (tp) {
    tp->severity = Severity::info;
    tp->quirk = rf->evidence;
    if (detail) tp->message += source();
  }
}

std::string_view to_string(TraitKind k) noexcept { return enum_name(kTraitKind, k); }

std::span<const Trait> traits() noexcept { return kTraits; }

const Trait* find_trait(TraitKind kind, Model model, Profile profile) noexcept {
  for (const Trait& t : kTraits) {
    if (t.kind != kind || t.dialect != dialect_of(model) || !model_in(t.models, model)) continue;
    if (t.source == Source::field && profile != Profile::field) continue;
    return &t;
  }
  return nullptr;
}

std::span<const FieldSupport> field_support() noexcept { return kFieldSupport; }

const FieldSupport* field_supported(Dialect d, Model model, std::string_view ident,
                                    std::optional<std::int64_t> value) noexcept {
  for (const FieldSupport& s : kFieldSupport) {
    if (s.dialect != d || model == Model::unknown || !model_in(s.models, model) || s.ident != ident)
      continue;
    if (!value || s.values.empty()) return &s;
    for (std::int64_t v : s.values)
      if (v == *value) return &s;
  }
  return nullptr;
}

// ---- rules ----

std::string_view to_string(Link l) noexcept { return enum_name(kLink, l); }
std::string_view to_string(Rejection r) noexcept { return enum_name(kRejection, r); }

char client_address(Dialect d, Link link) noexcept {
  return d == Dialect::topotek && link == Link::network ? 'P' : 'U';
}

bool answers_source(Model model, Profile profile, Link link, char src) noexcept {
  if (find_trait(TraitKind::link_by_source, model, profile) == nullptr) return true;
  return src == client_address(dialect_of(model), link);
}

bool answers_source(Dialect d, Profile profile, Link link, char src) noexcept {
  for (const Trait& t : kTraits)
    if (t.kind == TraitKind::link_by_source && t.dialect == d &&
        (t.source != Source::field || profile == Profile::field))
      return src == client_address(d, link);
  return true;
}

bool rejects(FindingCode c) noexcept {
  switch (c) {
    case FindingCode::unknown_ident:
    case FindingCode::unsupported_on_model:
    case FindingCode::unsupported_control:
    case FindingCode::data_length:
    case FindingCode::bad_field:
    case FindingCode::value_out_of_range:
      return true;
    default:
      return false;
  }
}

Rejection rejection(const Decoded& dec, Model model, bool field_evidence) noexcept {
  Rejection r = Rejection::none;
  // Without field evidence the device is the document's: it knows neither
  // the field's commands nor the field's forms of its own.
  if (!field_evidence && dec.command != nullptr && dec.command->from_field())
    return Rejection::unsupported;
  if (!field_evidence && dec.form != nullptr && dec.form->from_field()) r = Rejection::invalid;
  for (const Finding& f : dec.findings) {
    if (f.code == FindingCode::unsupported_on_model) {
      const bool lifted = field_evidence && f.severity != Severity::error &&
                          dec.command != nullptr &&
                          field_supported(dec.dialect, model, dec.command->ident,
                                          !dec.fields.empty() && dec.fields[0].valid
                                              ? std::optional<std::int64_t>(dec.fields[0].integer)
                                              : std::nullopt) != nullptr;
      if (!lifted) return Rejection::unsupported;
    } else if (f.code == FindingCode::unknown_ident) {
      return Rejection::unsupported;
    } else if (rejects(f.code)) {
      r = Rejection::invalid;
    }
  }
  return r;
}

bool answers_error_reply(Dialect d) noexcept { return d == Dialect::skydroid; }

BuildSpec error_reply(const Frame& request) noexcept {
  BuildSpec b;
  b.header = Header::fixed;
  b.src = request.dst;
  b.dst = request.src;
  b.control = 'w';
  b.ident = error_reply_ident;
  b.data = error_reply_data;
  return b;
}

std::uint32_t speed_hold_ms(Model model, Profile profile) noexcept {
  const Trait* t = find_trait(TraitKind::speed_refresh, model, profile);
  return t != nullptr && t->value != 0 ? t->value : default_speed_hold_ms;
}

}  // namespace top

// Device behaviour: what a camera sends, as the documents write it and as
// real devices (and the clients written against them) show it.
//
// The catalog (catalog.hpp) says what a frame means; this says how a device
// behaves: which request turns on which stream, what a device answers to a
// write, the header and address order of each reply and push, and traits
// seen on real firmware. Every fact carries its source: a document example,
// a document rule, or field evidence with a one-line note. topsim's
// profiles, topdump's roles and topconf's matrices read it from here;
// docs/FIELD.md is generated from it.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "top/catalog.hpp"
#include "top/decode.hpp"
#include "top/frame.hpp"

namespace top {

// Where a fact about a device comes from.
enum class Source : std::uint8_t {
  document_example,  // an example frame of the document
  document_rule,     // a rule of the document (2.3.1: a reply swaps the addresses)
  field              // what real devices or clients written against them show
};
std::string_view to_string(Source s) noexcept;  // "document example", ...

// What topsim follows. field: field evidence, then the document's examples,
// then its rules. document: the document's examples, then its rules.
enum class Profile : std::uint8_t { field, document };
std::string_view to_string(Profile p) noexcept;  // "field", "document"
std::optional<Profile> profile_from_string(std::string_view s) noexcept;

// Who sends the frames of a stream.
enum class Sender : std::uint8_t { device, client };

// A stream: a write of `request` turns on frames of `push`.
struct StreamSpec {
  Dialect dialect = Dialect::unknown;
  std::string_view request;  // "GAA"
  std::string_view push;     // "GAC"
  Sender sender = Sender::device;
  // The write's data is the rate in Hz (SkyDroid GAA 01-64); otherwise it is
  // on (01) or off (00) and the rate is the device's own.
  bool rate_in_data = false;
  std::string_view section;  // where the document (or the field) says so
  std::string_view note;
  // The frames come at a rate while the stream is on (an attitude push):
  // topdump judges its stalls, its rate and a start that never came. False
  // for an event push (the field's Topotek OFT, ODR, ODZ), which comes and
  // goes with its cause (a target tracked, an object detected, the lens
  // zooming) and which none of those judges. A source must show the rate.
  bool periodic = false;
  // The write's value that switches the stream off: 00 for every switch
  // of the documents; the field's Topotek FED takes 20 (10 is on).
  unsigned off = 0;
  // Empty for a stream a document gives. A stream only the field shows
  // (Topotek GIA 01 pushing GIA frames) names its source here; the field
  // profile takes it, the document profile does not.
  std::string_view evidence;

  bool from_field() const noexcept { return !evidence.empty(); }
};

// Every stream of both dialects: the documents' and the field's.
std::span<const StreamSpec> streams() noexcept;
// The document's stream a write of `request` switches, or nullptr (Topotek
// GIA: GIC, as Topotek 4.3.6 says).
const StreamSpec* stream_enabled_by(Dialect d, std::string_view request) noexcept;
// The same under `profile`: field takes the field's stream first (Topotek
// GIA: GIA frames, LOC: OFT frames), then the document's; document only the
// document's.
const StreamSpec* stream_enabled_by(Dialect d, std::string_view request, Profile profile) noexcept;
// What a stream switch's write carries (the hex data: the rate in Hz with
// rate_in_data, else 00 off / 01 on), read from the frame without a
// detailed decode; nullopt when the data is empty or not hex.
std::optional<unsigned> switch_value(std::string_view data) noexcept;
// Whether a switch value (switch_value) turns `s` off (StreamSpec::off).
inline bool switches_off(const StreamSpec& s, unsigned value) noexcept { return value == s.off; }
// The stream whose frames carry `push`, the document's or the field's (a
// reader of traffic takes both: Topotek GIA frames are pushes), or nullptr.
const StreamSpec* stream_of(Dialect d, std::string_view push) noexcept;
// The same under `profile` (document: the documents' streams only).
const StreamSpec* stream_of(Dialect d, std::string_view push, Profile profile) noexcept;

// What a device answers to a valid write.
enum class WriteReply : std::uint8_t {
  echo,        // the write itself, addresses swapped (SkyDroid 2.3.1)
  data,        // a reply layout of its own (Topotek LON/LAT target, LRF)
  file_index,  // state and file index (Topotek 5.1 REC, 5.2 CAP)
  nothing      // no answer (a stream of the client: FAI; a Topotek write
               // the document gives no reply form: its `w` is set/control)
};
std::string_view to_string(WriteReply r) noexcept;
// What a device answers to a write of `cmd` (ERE for an invalid one is the
// dialect's rule, not the command's). SkyDroid 2.3.1 echoes every write;
// Topotek V1.1.3 defines `w` as set/control and promises a reply only where
// it gives the write's reply a form (REC and CAP's file index, LRF's
// range): any other Topotek write is taken without a word, as a real
// Topotek camera does (the silent_writes trait).
WriteReply write_reply(const CommandSpec& cmd) noexcept;

// The address order of a frame the device sends.
enum class Order : std::uint8_t {
  swapped,       // device first: the reply of 2.3.1 (#TPGU...)
  request_order  // client first, as in the request (#tpUGCrGAC...)
};
std::string_view to_string(Order o) noexcept;  // "swapped", "request order"

// Whether a device frame answers a request or is pushed by a stream.
enum class Sent : std::uint8_t { reply, push };

// One recorded form of a device frame: for these models, a `sent` frame of
// `ident` with `control` comes with `header` in `order`.
struct DeviceForm {
  Dialect dialect = Dialect::unknown;
  ModelSet models = 0;
  std::string_view ident;
  char control = 'r';
  Sent sent = Sent::reply;
  Header header = Header::fixed;
  Order order = Order::swapped;
  Source source = Source::document_rule;
  std::string_view evidence;  // the example, or one line of field evidence
  // The length char counts the bytes of a hex-coded value, half its chars
  // (#TPDU1rIMG01, #TPDU2rSLR0018): the frame layer finds the data by the
  // checksum and reports a length mismatch.
  bool length_in_bytes = false;
  // A reply of `ident` that answers a read of another identifier (a real
  // SIP answers the GIC query with GIA); empty: a read of `ident` itself.
  std::string_view answers;
};

// Every recorded form (document examples and field evidence; the rule is
// not listed: see device_form()).
std::span<const DeviceForm> device_forms() noexcept;

// The form a device of `model` uses for a frame of `ident`/`control` with
// `data_length` bytes under `profile`: the first recorded form the profile
// takes (field: field, then example; document: example), else the rule
// (choose_header and swapped addresses), returned with source
// document_rule and evidence naming the rule.
DeviceForm device_form(Model model, std::string_view ident, char control, Sent sent,
                       std::size_t data_length, Profile profile) noexcept;

// The recorded form a device frame matches (its header and address order),
// or nullptr: for topdump and topconf to name the source of a frame that
// deviates from the rule. `model` unknown matches every model.
const DeviceForm* recorded_form(Dialect d, Model model, const Frame& f, Sent sent) noexcept;

// The identifier a device of `model` answers a read of `request` with under
// `profile`: a recorded reply form that answers it (field: GIC -> GIA), else
// `request` itself.
std::string_view reply_ident(Model model, std::string_view request, Profile profile) noexcept;
// Whether a device frame of `reply` answers a read of `request` (the same
// identifier, or a recorded form of any model and profile: a reader of
// traffic takes both the document's and the field's answer).
bool answers_query(Dialect d, std::string_view request, std::string_view reply) noexcept;
// Whether a device frame of `reply` answers a read of another identifier in
// some recorded form (answers_query true for a `request` other than
// `reply`): false for nearly every identifier, so a reader asks it once
// before it looks for such a read among the pending requests.
bool answers_other_query(Dialect d, std::string_view reply) noexcept;
// The recorded form whose length char counts bytes (length_in_bytes) that
// `f` has: its identifier, control, header and address order, any model.
// Asked by the frame parser when a frame's data is twice its length.
const DeviceForm* length_in_bytes_form(const Frame& f) noexcept;

// A trait of real firmware that is not a frame form.
enum class TraitKind : std::uint8_t {
  yaw_inverted,          // the attitude reports the opposite sign of the yaw commanded
  pitch_inverted,        // the same for pitch
  answers_to_source,     // the reply goes to the datagram's source address and port
  link_by_source,        // Topotek: answers only the link the source byte names
  speed_refresh,         // a speed command must be refreshed or the motors stop
  keeps_request_header,  // a reply keeps the request's #TP or #tp, whatever its length
  double_checksum,       // takes a frame followed by a second checksum over it
  // UDP: the device sends its replies from an ephemeral port of its own,
  // not from the port it serves
  ephemeral_reply_port,
  // UDP: each reply goes to the asking port, to the client port of the
  // port table (Topotek 9004) and to the client ports that asked before it
  fan_out,
  // UDP: each reply reaches the client port of the port table twice
  duplicate_to_client_port,
  // a valid write takes effect without any reply (no echo)
  silent_writes
};
std::string_view to_string(TraitKind k) noexcept;

struct Trait {
  TraitKind kind{};
  Dialect dialect = Dialect::unknown;
  ModelSet models = 0;
  std::uint32_t value = 0;  // speed_refresh: ms (ports: top/dialect.hpp known_ports())
  Source source = Source::field;
  std::string_view evidence;  // every source for, and every source against
  // The identifiers the evidence concerns, space separated ("GSY"); empty:
  // every identifier (or a trait that is not about commands). A sign trait
  // applies to the commands it names only.
  std::string_view idents;
  // The sources conflict, and the reading that serves the autopilot is the
  // document's: recorded and shown with every source, applied only when
  // asked for (topsim --pitch-sign inverted), never by a profile.
  bool contested = false;

  // Whether the trait concerns commands of `ident` (every one when idents is empty).
  bool names(std::string_view ident) const noexcept;
};
std::span<const Trait> traits() noexcept;
// The trait of `kind` for `model` under `profile` (a field trait only under
// the field profile), or nullptr. A contested trait is found only with
// `contested_too` (to show it), never applied.
const Trait* find_trait(TraitKind kind, Model model, Profile profile,
                        bool contested_too = false) noexcept;

// How a positive command of `ident` on `axis` (0 yaw, 1 pitch) turns a
// device of `model` relative to the motion table's sign (top/motion.hpp):
// +1 as the table says; -1 where a field sign trait (yaw_inverted,
// pitch_inverted) inverts it for this model and identifier; 0 when `model`
// is unknown and such a trait inverts it on some model of `d`: which way
// the gimbal should turn cannot be told. A contested trait is never
// applied. For judging a capture's directions (topdump's direction-inverted).
int sign_trait_factor(Dialect d, Model model, int axis, std::string_view ident) noexcept;

// A command value the document does not list for a model but field
// evidence says the firmware takes (C13 PTZ codes).
struct FieldSupport {
  Dialect dialect = Dialect::unknown;
  ModelSet models = 0;
  std::string_view ident;
  std::span<const std::int64_t> values;  // the first field's values; empty: any
  std::string_view evidence;
};
std::span<const FieldSupport> field_support() noexcept;
// The field evidence that `model` takes `ident` with the first field's value
// `value` (nullopt: any value), or nullptr.
const FieldSupport* field_supported(Dialect d, Model model, std::string_view ident,
                                    std::optional<std::int64_t> value) noexcept;

// What a field source says of a model that nothing here acts on: recorded
// with its source so that an engineer reading a capture knows of it, but
// neither decoded, simulated nor checked (a station's note, unconfirmed,
// or at odds with a rule: C13 ports that are Topotek's device port).
struct FieldNote {
  Dialect dialect = Dialect::unknown;
  ModelSet models = 0;
  std::string_view ident;     // the identifier it concerns; empty: none
  std::string_view note;      // what the source says
  std::string_view evidence;  // the source, and why it is not modelled
};
std::span<const FieldNote> field_notes() noexcept;

// ---- Rules of the device: asked for by topsim, topconf, the fuzzers and
// topdump alike, so that each is written once. ----

// The link a request reaches the device on.
enum class Link : std::uint8_t {
  network,  // UDP or TCP
  uart      // a serial line
};
std::string_view to_string(Link l) noexcept;  // "network", "uart"

// The source address a client of `d` writes on `link`: Topotek names the
// interface by the source byte (P network, U UART; Topotek 2), SkyDroid's
// clients are U on every link (SkyDroid 2.1).
char client_address(Dialect d, Link link) noexcept;
// Whether a device of `model` under `profile` answers a request with source
// `src` that arrived on `link` (the trait link_by_source: a Topotek UDP
// request with source U gets no answer). Devices without the trait answer
// every source.
bool answers_source(Model model, Profile profile, Link link, char src) noexcept;
// The same for a device of dialect `d` whose model is not known (a capture):
// the trait of any model of the dialect.
bool answers_source(Dialect d, Profile profile, Link link, char src) noexcept;

// Whether a device of `d` may send what it sends over UDP to any port of
// the client's host, from any port of its own: Topotek V1.1.3 answers to
// the client port 9004 whatever the request's source port, and a real
// Topotek camera answers from an ephemeral port to several client ports
// (the traits ephemeral_reply_port and fan_out). A reader of traffic pairs
// such a device's frames with the requests of the client's host, whatever
// the ports; SkyDroid devices answer the datagram's source (answers_to_source).
bool replies_reach_host(Dialect d) noexcept;

// Why a device refuses a request, judged from the request's catalog findings.
enum class Rejection : std::uint8_t {
  none,         // the device takes it
  unsupported,  // unknown-ident, or unsupported-on-model without field evidence
  invalid       // unsupported-control, data-length, bad-field, value-out-of-range
};
std::string_view to_string(Rejection r) noexcept;  // "none", "unsupported", "invalid"
// The rejection a device of `model` gives a request decoded as `dec` (its
// catalog findings). With `field_evidence` (the field profile), an
// unsupported-on-model is lifted where field evidence says the model takes
// the command with that first-field value (field_supported: C13 PTZ 0E);
// without it (the document profile) it always rejects, and so do the
// field's own commands (unsupported: TRC, LOC) and forms (invalid: a
// 12-char GIA, as the document's lengths make it). unsupported wins over
// invalid. A finding of information refuses nothing (a data-length that
// names the field's form: ArduPilot's 14-char FAI).
Rejection rejection(const Decoded& dec, Model model, bool field_evidence = true) noexcept;
// True for the finding codes that can make a device reject a request.
bool rejects(FindingCode c) noexcept;

// The invalid-command reply (SkyDroid 2.3.2): #TP<dst><src>2wERE!!<cs>.
inline constexpr std::string_view error_reply_ident = "ERE";
inline constexpr std::string_view error_reply_data = "!!";
// True when `f` is an invalid-command reply.
inline bool is_error_reply(const Frame& f) noexcept { return f.ident_view() == error_reply_ident; }
// True when `ident` names the invalid-command reply.
inline bool is_error_reply(std::string_view ident) noexcept { return ident == error_reply_ident; }
// Whether devices of `d` answer an invalid request with ERE (SkyDroid 2.3.2;
// Topotek documents no such reply and stays silent).
bool answers_error_reply(Dialect d) noexcept;
// The ERE a device sends for `request`, addresses swapped; the spec views
// static text and the request's nothing.
BuildSpec error_reply(const Frame& request) noexcept;

// Timing rules (each with the reason it has the value it has).
// A push stream runs at its asked rate when its measured rate is within this
// fraction of it: GAA asks a rate in whole Hz and devices pace by their own
// tick, so a few percent are jitter and 25% is a different rate.
inline constexpr double stream_rate_tolerance = 0.25;
// Copies of one datagram a device sends to several ports of the client
// (fan_out, duplicate_to_client_port) arrive less than this after the
// first: a real Topotek camera's copies came within 1 ms, a few of them
// 6-7 ms late (PixEagle bench: 2852 and 6 of 2858; 20260917T051804Z-queries
// 05:18:06.703191 and .710040), while two frames of the same bytes it sent
// on their own came 30 ms apart or more (ODZ during zoom), and the fastest
// periodic push of either document (SkyDroid GAA at 100 Hz) is 10 ms
// apart. The same bytes again within less than 10 ms are a copy.
inline constexpr std::int64_t fan_out_copy_window_us = 10000;
// A device holding bytes that may start a frame (one failing its checksum
// waits for the bytes after it: a length that lies) decides on them once its
// line has been quiet this long. The documents give no inter-frame timeout; this is
// topsim's choice (a 20-byte frame at 115200 baud takes 1.7 ms), and topconf
// waits it out before it expects the device's verdict on a cut frame.
inline constexpr std::uint32_t quiet_line_ms = 20;
// How long a speed command keeps the motors turning without a refresh: the
// speed_refresh trait's value for `model` (field: autopilots refresh at
// 10-50 Hz), else default_speed_hold_ms.
inline constexpr std::uint32_t default_speed_hold_ms = 1000;
std::uint32_t speed_hold_ms(Model model, Profile profile) noexcept;
// The speed-refresh trait a capture is judged by: `model`'s (field
// profile), or with the model unknown the first of dialect `d`; nullptr when
// none applies (Topotek records none: a rate holds until changed).
const Trait* speed_refresh_trait(Model model, Dialect d) noexcept;

// The model a device names in its model-name reply, or unknown: SkyDroid
// MOD, whose data is the model name ("C13"; ArduPilot's AP_Mount_SkyDroid
// reads it until answered, docs/sources/ardupilot.md), read as one of the
// dialect's models, case and trailing blanks aside.
Model model_named_by(Dialect d, std::string_view ident, std::string_view data) noexcept;

}  // namespace top

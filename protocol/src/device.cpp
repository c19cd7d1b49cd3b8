// Device behaviour: the rules read from the tables of device_tables.cpp and
// device_traits.cpp
// (streams, write replies, recorded forms, traits, field support). See
// top/device.hpp.
#include "top/device.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <string>
#include <vector>

#include "catalog_data.hpp"
#include "device_form.hpp"
#include "top/detail/prefilter.hpp"
#include "top/dialect.hpp"
#include "top/enum_names.hpp"
#include "top/text.hpp"

#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace top {
namespace {

// Identifiers are three chars: compared as such, without a call to memcmp
// (the session asks the stream rules of every write and every reply).
bool same(std::string_view a, std::string_view b) noexcept {
  if (a.size() != b.size()) return false;
  if (a.size() == 3) return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
  return a == b;
}

constexpr std::string_view kSource[] = {"document example", "document rule", "field"};
static_assert(std::size(kSource) == static_cast<std::size_t>(Source::field) + 1);
constexpr std::string_view kProfile[] = {"field", "document"};
static_assert(std::size(kProfile) == static_cast<std::size_t>(Profile::document) + 1);
constexpr std::string_view kWriteReply[] = {"echo", "data", "file index", "nothing"};
static_assert(std::size(kWriteReply) == static_cast<std::size_t>(WriteReply::nothing) + 1);
constexpr std::string_view kOrder[] = {"swapped", "request order"};
static_assert(std::size(kOrder) == static_cast<std::size_t>(Order::request_order) + 1);
constexpr std::string_view kTraitKind[] = {
    "yaw-inverted",  "pitch-inverted",           "answers-to-source", "link-by-source",
    "speed-refresh", "keeps-request-header",     "double-checksum",   "ephemeral-reply-port",
    "fan-out",       "duplicate-to-client-port", "silent-writes"};
static_assert(std::size(kTraitKind) == static_cast<std::size_t>(TraitKind::silent_writes) + 1);
constexpr std::string_view kLink[] = {"network", "uart"};
static_assert(std::size(kLink) == static_cast<std::size_t>(Link::uart) + 1);
constexpr std::string_view kRejection[] = {"none", "unsupported", "invalid"};
static_assert(std::size(kRejection) == static_cast<std::size_t>(Rejection::invalid) + 1);

bool model_in(ModelSet set, Model m) noexcept {
  return m == Model::unknown || (set & model_bit(m)) != 0;
}

}  // namespace

std::string_view to_string(Source s) noexcept { return enum_name(kSource, s); }
std::string_view to_string(Profile p) noexcept { return enum_name(kProfile, p); }

std::optional<Profile> profile_from_string(std::string_view s) noexcept {
  return enum_from_name<Profile>(kProfile, s);
}

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

namespace {

// An identifier's three chars as one integer (detail::ident_key; 0: not
// three chars).
std::uint32_t key_of(std::string_view id) noexcept {
  return id.size() == 3 ? detail::ident_key(id.data()) : 0;
}

// Every stream request's key, built at start-up: most writes switch no
// stream, and the session asks of every one.
const std::vector<std::uint32_t> kSwitchKeys = [] {
  std::vector<std::uint32_t> v;
  for (const StreamSpec& s : streams()) v.push_back(key_of(s.request));
  return v;
}();

// Whether a link_by_source trait applies, per dialect and profile: built at
// start-up from traits() (answers_source is asked of every request).
const std::array<std::array<bool, 2>, 3> kLinkBySource = [] {
  std::array<std::array<bool, 2>, 3> v{};
  for (const Trait& t : traits())
    if (t.kind == TraitKind::link_by_source)
      for (const Profile p : {Profile::field, Profile::document})
        if (t.source != Source::field || p == Profile::field)
          v[static_cast<std::size_t>(t.dialect)][static_cast<std::size_t>(p)] = true;
  return v;
}();

}  // namespace

const StreamSpec* stream_enabled_by(Dialect d, std::string_view request, Profile profile) noexcept {
  const std::uint32_t key = key_of(request);
  if (std::find(kSwitchKeys.begin(), kSwitchKeys.end(), key) == kSwitchKeys.end()) return nullptr;
  const StreamSpec* document = nullptr;
  for (const StreamSpec& s : streams()) {
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
  for (const StreamSpec& s : streams())
    if (s.dialect == d && same(s.push, push) && (!s.from_field() || profile == Profile::field))
      return &s;
  return nullptr;
}

std::string_view to_string(WriteReply r) noexcept { return enum_name(kWriteReply, r); }

namespace {

WriteReply write_reply_of(const CommandSpec& cmd) noexcept {
  const StreamSpec* s = stream_of(cmd.dialect, cmd.ident);
  if (s && s->sender == Sender::client) return WriteReply::nothing;
  for (const FormSpec& f : cmd.forms) {
    if (f.control != 'w' || f.role != Role::response) continue;
    // Topotek 5.1/5.2: REC and CAP answer with the state and a file index.
    if (cmd.dialect == Dialect::topotek && (cmd.ident == "REC" || cmd.ident == "CAP"))
      return WriteReply::file_index;
    return cmd.ident == "ERE" ? WriteReply::echo : WriteReply::data;
  }
  // Topotek 2: `w` is set/control; the document gives no reply to a write
  // it shows no reply form for (SkyDroid 2.3.1's echo is SkyDroid's rule).
  if (cmd.dialect == Dialect::topotek) return WriteReply::nothing;
  return WriteReply::echo;
}

// built at start-up (the tables are constants): no guard on each call
const detail::PerCommand<WriteReply, decltype(&write_reply_of)> kReplyOf(&write_reply_of);

}  // namespace

WriteReply write_reply(const CommandSpec& cmd) noexcept { return kReplyOf(cmd); }

std::string_view to_string(Order o) noexcept { return enum_name(kOrder, o); }

std::string_view reply_ident(Model model, std::string_view request, Profile profile) noexcept {
  const Dialect d = dialect_of(model);
  const DeviceForm* example = nullptr;
  for (const DeviceForm& f : device_forms()) {
    if (f.dialect != d || !model_in(f.models, model) || f.sent != Sent::reply ||
        f.answers != request)
      continue;
    if (f.source == Source::field && profile == Profile::field) return f.ident;
    if (f.source == Source::document_example && !example) example = &f;
  }
  return example ? example->ident : request;
}

bool answers_query(Dialect d, std::string_view request, std::string_view reply) noexcept {
  if (request == reply) return true;
  for (const DeviceForm& f : device_forms())
    if (f.dialect == d && f.sent == Sent::reply && f.ident == reply && f.answers == request)
      return true;
  return false;
}

bool answers_other_query(Dialect d, std::string_view reply) noexcept {
  // the recorded forms that answer another identifier's read, found once
  // (one today: a SIP's GIA answering GIC); the device forms are ~40 rows
  // of 80 bytes, and every push a client's read waits beside would scan them
  static const std::vector<const DeviceForm*> kOthers = [] {
    std::vector<const DeviceForm*> v;
    for (const DeviceForm& f : device_forms())
      if (f.sent == Sent::reply && !f.answers.empty() && f.answers != f.ident) v.push_back(&f);
    return v;
  }();
  for (const DeviceForm* f : kOthers)
    if (f->dialect == d && f->ident == reply) return true;
  return false;
}

DeviceForm device_form(Model model, std::string_view ident, char control, Sent sent,
                       std::size_t data_length, Profile profile) noexcept {
  const Dialect d = dialect_of(model);
  const DeviceForm* example = nullptr;
  const DeviceForm* field = nullptr;
  for (const DeviceForm& f : device_forms()) {
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
  for (const DeviceForm& x : device_forms()) {
    if (x.dialect != d || !model_in(x.models, model) || x.ident != ident ||
        x.control != f.control || x.sent != sent || x.header != f.header || x.order != order)
      continue;
    // Field evidence names the firmware; prefer it to an example of the same form.
    if (!best || x.source == Source::field) best = &x;
  }
  return best;
}

const DeviceForm* length_in_bytes_form(const Frame& f) noexcept {
  const Order order = is_client_address(f.src) ? Order::request_order : Order::swapped;
  for (const DeviceForm& x : device_forms())
    if (x.length_in_bytes && x.ident == f.ident_view() && x.control == f.control &&
        x.header == f.header && x.order == order)
      return &x;
  return nullptr;
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
  // A push in the order the document's example and the field record for it
  // (the C12's #tpUGCrGAC at 10 Hz and more) is that device's own form, not
  // a reply that failed to swap: no note on every frame of the stream.
  if (unswapped && push && rf) {
    if (un) dec.findings.erase(dec.findings.begin() + (un - dec.findings.data()));
    un = nullptr;
    tp = nullptr;
    for (Finding& x : dec.findings)
      if (x.code == FindingCode::tp_length && x.severity != Severity::info) tp = &x;
  } else if (unswapped && !un) {
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

bool Trait::names(std::string_view ident) const noexcept {
  if (idents.empty()) return true;
  for (std::size_t at = 0; at < idents.size();) {
    const std::size_t end = std::min(idents.find(' ', at), idents.size());
    if (idents.substr(at, end - at) == ident) return true;
    at = end + 1;
  }
  return false;
}

const Trait* find_trait(TraitKind kind, Model model, Profile profile, bool contested_too) noexcept {
  for (const Trait& t : traits()) {
    if (t.kind != kind || t.dialect != dialect_of(model) || !model_in(t.models, model)) continue;
    if (t.source == Source::field && profile != Profile::field) continue;
    if (t.contested && !contested_too) continue;
    return &t;
  }
  return nullptr;
}

int sign_trait_factor(Dialect d, Model model, int axis, std::string_view ident) noexcept {
  const TraitKind kind = axis == 0 ? TraitKind::yaw_inverted : TraitKind::pitch_inverted;
  if (axis > 1) return 1;
  // the sign traits, found once: every judged motion command asks, and the
  // whole table is a few kilobytes of mostly other traits
  static const std::vector<const Trait*> kSigns = [] {
    std::vector<const Trait*> v;
    for (const Trait& t : traits())
      if (t.kind == TraitKind::yaw_inverted || t.kind == TraitKind::pitch_inverted) v.push_back(&t);
    return v;
  }();
  for (const Trait* p : kSigns) {
    const Trait& t = *p;
    if (t.kind != kind || t.dialect != d || t.contested || !t.names(ident)) continue;
    if (model == Model::unknown) return 0;
    if (model_in(t.models, model)) return -1;
  }
  return 1;
}

const FieldSupport* field_supported(Dialect d, Model model, std::string_view ident,
                                    std::optional<std::int64_t> value) noexcept {
  for (const FieldSupport& s : field_support()) {
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
  if (!kLinkBySource[static_cast<std::size_t>(d)][static_cast<std::size_t>(profile)]) return true;
  return src == client_address(d, link);
}

bool replies_reach_host(Dialect d) noexcept {
  for (const PortSpec& p : known_ports())
    if (p.client && p.dialect == d) return true;
  for (const Trait& t : traits())
    if (t.dialect == d &&
        (t.kind == TraitKind::fan_out || t.kind == TraitKind::ephemeral_reply_port))
      return true;
  return false;
}

bool rejects(FindingCode c) noexcept {
  using enum FindingCode;
  static constexpr FindingCode kRejected[] = {unknown_ident,       unsupported_on_model,
                                              unsupported_control, data_length,
                                              bad_field,           value_out_of_range};
  return std::find(std::begin(kRejected), std::end(kRejected), c) != std::end(kRejected);
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
    } else if (rejects(f.code) && f.severity != Severity::info) {
      // information is no refusal: a form of the field (ArduPilot's
      // 14-char FAI) under the field profile
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

const Trait* speed_refresh_trait(Model model, Dialect d) noexcept {
  if (model != Model::unknown) return find_trait(TraitKind::speed_refresh, model, Profile::field);
  for (const Trait& t : traits())
    if (t.kind == TraitKind::speed_refresh && t.dialect == d) return &t;
  return nullptr;
}

Model model_named_by(Dialect d, std::string_view ident, std::string_view data) noexcept {
  if (d != Dialect::skydroid || ident != "MOD") return Model::unknown;
  while (!data.empty() && (data.back() == ' ' || data.back() == '\0')) data.remove_suffix(1);
  char low[8];
  if (data.empty() || data.size() > sizeof low) return Model::unknown;
  for (std::size_t i = 0; i < data.size(); ++i)
    low[i] = data[i] >= 'A' && data[i] <= 'Z' ? static_cast<char>(data[i] - 'A' + 'a') : data[i];
  const std::optional<Model> m = model_from_string({low, data.size()});
  return m && *m != Model::unknown && dialect_of(*m) == d ? *m : Model::unknown;
}

std::uint32_t speed_hold_ms(Model model, Profile profile) noexcept {
  const Trait* t = find_trait(TraitKind::speed_refresh, model, profile);
  return t != nullptr && t->value != 0 ? t->value : default_speed_hold_ms;
}

}  // namespace top

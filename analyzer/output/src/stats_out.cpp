// The statistics of a run, as text (stats) or JSON (stats --json, and the
// last line of live and serial --json), each key written here once.
#include <cmath>
#include <cstdio>

#include "capture/sources.hpp"
#include "output/json_writer.hpp"
#include "output/output.hpp"

namespace topdump {

using namespace jsonw;

namespace {

void put_ms(std::string& o, std::int64_t us) { put_double(o, static_cast<double>(us) / 1000.0); }

// The keys of an input: file, format, link (null for serial logs).
void input_members(Doc& j, const InputInfo& i) {
  std::string& o = j.out();
  j.key("file");
  put_text(o, i.file);
  j.key("format");
  put_str(o, to_string(i.format));
  j.key("link");
  put_or_null(o, !i.link.empty(), [&] { put_str(o, i.link); });
}
}  // namespace

void jsonw::latency_members(Doc& j, const Latency& l) {
  std::string& o = j.out();
  j.u("count", l.count());
  auto ms = [&](std::string_view k, std::int64_t us) {
    j.key(k);
    put_ms(o, us);
  };
  ms("min_ms", l.min());
  for (auto [k, q] :
       {std::pair{"p50_ms", 0.5}, {"p90_ms", 0.9}, {"p95_ms", 0.95}, {"p99_ms", 0.99}})
    ms(k, l.quantile(q));
  ms("max_ms", l.max());
}

void jsonw::conversation_members(Doc& j, const ConvStats& c) {
  j.u("id", c.id);
  j.str("transport", to_string(c.transport));
  j.str("a", c.a);
  j.str("b", c.b);
}

void jsonw::counts_member(Doc& j, std::string_view k,
                          const std::map<std::string, std::uint64_t>& m) {
  j.key_object(k);
  for (const auto& [name, v] : m) j.u(name, v);
  j.close_object();
}

void jsonw::stream_members(Doc& j, const StreamStat& t, StreamKeys k) {
  std::string& o = j.out();
  j.str("ident", t.ident);
  if (k.asked_by) j.str("asked_by", t.asked_by);
  j.key("asked_hz");
  put_or_null(o, t.asked_hz > 0, [&] { put_double(o, t.asked_hz); });
  j.key("measured_hz");
  put_double(o, std::round(t.measured_hz() * k.measured_per_hz) / k.measured_per_hz);
  j.key("periodic");
  put_bool(o, t.periodic);
  j.u("frames", t.frames);
}

void write_input_json(std::string& out, const InputInfo& i) {
  Doc j(out, -1);
  j.open_object();
  j.str("type", "input");
  input_members(j, i);
  j.close_object();
  out += '\n';
}

std::string input_text(const InputInfo& i) {
  std::string s = i.file + ": " + std::string(to_string(i.format));
  if (!i.link.empty()) s += ", link type " + i.link;
  return s;
}

void write_stats_json(std::string& out, const Stats& s, top::Severity worst, int indent,
                      std::string_view type, const std::vector<InputInfo>* inputs) {
  Doc j(out, indent);
  j.open_object();
  if (!type.empty()) j.str("type", type);
  if (inputs) {
    j.key_objects("inputs", *inputs, [&](const InputInfo& i) { input_members(j, i); });
  }
  j.u("frames", s.frames);
  j.u("bad_checksum", s.bad_checksum);
  j.u("error_frames", s.error_frames);
  j.u("garbage", s.garbage);
  j.u("records", s.records);
  j.u("records_skipped", s.records_skipped);
  j.time("first_time", s.first);
  j.time("last_time", s.last);
  j.str("worst", top::to_string(worst));
  counts_member(j, "per_ident", s.per_ident);
  counts_member(j, "per_finding", s.per_code);
  j.key_object("pairing");
  for (const StatsCount& c : kPairingCounts) j.u(c.name, s.*c.count);
  j.u("copies", s.copies);
  j.close_object();
  j.key_object("latency");
  for (const auto& [k, l] : s.latency) {
    j.key_object(k);
    latency_members(j, l);
    j.close_object();
  }
  j.close_object();
  j.key_objects("conversations", s.conversations, [&](const ConvStats& c) {
    conversation_members(j, c);
    j.str("dialect", top::to_string(c.dialect));
    j.u("frames", c.frames);
    j.u("requests", c.requests);
    j.u("responses", c.responses);
    j.u("paired", c.paired);
    j.key_objects("streams", c.streams,
                  [&](const StreamStat& t) { stream_members(j, t, StreamKeys{}); });
  });
  j.u("conversations_dropped", s.conversations_dropped);
  j.close_object();
}

std::string stats_text(const Stats& s, top::Severity worst) {
  std::string o;
  char b[256];
  std::snprintf(
      b, sizeof b,
      "frames %llu (bad checksum %llu, with an error %llu), garbage runs %llu, records %llu "
      "(not TOP %llu), worst finding: %s\n",
      static_cast<unsigned long long>(s.frames), static_cast<unsigned long long>(s.bad_checksum),
      static_cast<unsigned long long>(s.error_frames), static_cast<unsigned long long>(s.garbage),
      static_cast<unsigned long long>(s.records),
      static_cast<unsigned long long>(s.records_skipped),
      std::string(top::to_string(worst)).c_str());
  o += b;
  if (s.first != kNoTime) o += "time " + format_time(s.first) + " .. " + format_time(s.last) + "\n";
  o += "per identifier:\n";
  for (const auto& [k, v] : s.per_ident) o += "  " + k + " " + std::to_string(v) + "\n";
  o += "per finding:\n";
  for (const auto& [k, v] : s.per_code) o += "  " + k + " " + std::to_string(v) + "\n";
  o += "pairing:";
  for (const StatsCount& c : kPairingCounts)
    o += std::string(&c == kPairingCounts ? " " : ", ") + std::string(c.name) + " " +
         std::to_string(s.*c.count);
  if (s.copies)
    o += ", copies " + std::to_string(s.copies) + " (the device's fan-out: counted once)";
  o += '\n';
  if (!s.latency.empty()) {
    o += "latency (ms): ident count min median p95 max\n";
    for (const auto& [k, l] : s.latency) {
      std::snprintf(
          b, sizeof b, "  %s %llu %.3f %.3f %.3f %.3f\n", k.c_str(),
          static_cast<unsigned long long>(l.count()), static_cast<double>(l.min()) / 1000.0,
          static_cast<double>(l.quantile(0.5)) / 1000.0,
          static_cast<double>(l.quantile(0.95)) / 1000.0, static_cast<double>(l.max()) / 1000.0);
      o += b;
    }
  }
  o += "conversations:\n";
  for (const ConvStats& c : s.conversations) {
    std::snprintf(
        b, sizeof b,
        "  %llu %s %s <> %s %s: frames %llu, requests %llu, responses %llu, paired %llu\n",
        static_cast<unsigned long long>(c.id), std::string(to_string(c.transport)).c_str(),
        c.a.c_str(), c.b.c_str(), std::string(top::to_string(c.dialect)).c_str(),
        static_cast<unsigned long long>(c.frames), static_cast<unsigned long long>(c.requests),
        static_cast<unsigned long long>(c.responses), static_cast<unsigned long long>(c.paired));
    o += b;
    for (const StreamStat& t : c.streams) {
      // an event push (top::StreamSpec::periodic) runs at no rate of its own
      const std::string asked =
          !t.periodic      ? std::string("event push")
          : t.asked_hz > 0 ? "asked " + std::to_string(static_cast<int>(t.asked_hz)) + " Hz"
                           : std::string("asked enable");
      std::snprintf(b, sizeof b, "    stream %s: %llu frames at %.2f Hz (%s)\n", t.ident.c_str(),
                    static_cast<unsigned long long>(t.frames), t.measured_hz(), asked.c_str());
      o += b;
    }
  }
  if (s.conversations_dropped)
    o += "  (" + std::to_string(s.conversations_dropped) + " more conversations not listed)\n";
  return o;
}

}  // namespace topdump

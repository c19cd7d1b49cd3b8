#include "driver_harness.hpp"

#include <sys/wait.h>

#include <nlohmann/json.hpp>

namespace {

int rank(const std::string& severity) {
  return severity == "error" ? 2 : severity == "warning" ? 1 : 0;
}

std::string text(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

}  // namespace

JsonLines topdump_read_json(const std::string& pcap) {
  JsonLines r;
  const std::string cmd =
      "'" + std::string(TOPKIT_BINARY_DIR) + "/analyzer/topdump' read --json '" + pcap + "'";
  FILE* f = ::popen(cmd.c_str(), "r");
  if (!f) return r;
  std::string out;
  char buf[65536];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) out.append(buf, n);
  const int st = ::pclose(f);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  for (std::size_t start = 0; start < out.size();) {
    const std::size_t end = std::min(out.find('\n', start), out.size());
    std::string line = out.substr(start, end - start);
    auto j = nlohmann::json::parse(line, nullptr, false);
    r.lines.emplace_back(std::move(line), std::move(j));
    start = end + 1;
  }
  return r;
}

Dump topdump_findings(const std::string& pcap, const std::string& min_severity) {
  Dump d;
  const JsonLines run = topdump_read_json(pcap);
  d.status = run.status;
  const int floor = rank(min_severity);
  for (const auto& [line, j] : run.lines) {
    ++d.lines;
    if (j.is_discarded()) {
      d.findings.push_back({"unparsable-json-line", "error", line.substr(0, 80), "", -1});
      continue;
    }
    const auto add = [&](const nlohmann::json& x, const std::string& ident, long long frame) {
      if (rank(text(x, "severity")) >= floor)
        d.findings.push_back(
            {text(x, "code"), text(x, "severity"), text(x, "message"), ident, frame});
    };
    if (text(j, "type") == "finding") {
      add(j, "", j.value("frame", nlohmann::json()).is_number() ? j["frame"].get<long long>() : -1);
    } else {
      // A frame's own findings and the session's notes on it (unsolicited...).
      const long long at =
          j.value("n", nlohmann::json()).is_number() ? j["n"].get<long long>() : -1;
      for (const char* key : {"findings", "session"})
        if (j.contains(key) && j[key].is_array())
          for (const auto& x : j[key])
            if (x.is_object()) add(x, text(j, "ident"), at);
    }
  }
  return d;
}

std::string describe(const Dump& d) {
  std::string s = "topdump exit " + std::to_string(d.status) + ", " +
                  std::to_string(d.findings.size()) + " finding(s):\n";
  std::size_t shown = 0;
  for (const DumpFinding& f : d.findings) {
    if (++shown > 40) {
      s += "  ...\n";
      break;
    }
    s += "  " + f.code + " (" + f.ident + ", frame " + std::to_string(f.frame) + "): " + f.message +
         "\n";
  }
  return s;
}

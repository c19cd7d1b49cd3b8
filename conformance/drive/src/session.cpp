#include "session.hpp"

#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "top/diagnoses.hpp"

namespace topconf::drive::detail {

namespace fs = std::filesystem;

void BeliefLog::take(Steady::time_point t0, Steady::time_point at, const std::string& line) {
  Line l;
  l.t = std::chrono::duration<double>(at - t0).count();
  l.j = nlohmann::json::parse(line, nullptr, false);
  l.json = !l.j.is_discarded() && l.j.is_object();
  if (!l.json) l.j = nullptr;
  std::lock_guard lock(mu_);
  lines_.push_back(std::move(l));
}

void BeliefLog::slice(double from, double to, Record& r) const {
  std::lock_guard lock(mu_);
  for (const Line& l : lines_) {
    if (l.t < from || l.t >= to) continue;
    if (!l.json) {
      ++r.non_json_lines;
      continue;
    }
    if (auto e = l.j.find("error"); e != l.j.end() && e->is_string())
      r.errors.push_back(e->get<std::string>());
    r.beliefs.push_back(Belief{l.t - from, l.j});
  }
}

std::string capture_name(topsim::TransportKind k) {
  return k == topsim::TransportKind::pty ? "wire.log" : "wire.pcap";
}

DeviceRun::DeviceRun(const DriveOptions& o, const CaseSetup& s, const std::string& capture)
    : model_(o.model),
      tap_(o.model, o.link == topsim::TransportKind::udp, s.options.profile == top::Profile::field),
      kind_(o.link) {
  topsim::ServerConfig cfg;
  cfg.model = o.model;
  cfg.kind = o.link;
  cfg.host = "127.0.0.1";
  cfg.port = 0;
  // The asking port gets the replies (no fixed client port such as 9004):
  // cases run side by side.
  cfg.reply_port = 0;
  cfg.faults = s.faults;
  cfg.device_options = s.options;
  cfg.seed = o.seed;
  cfg.record = capture;
  cfg.on_traffic = [this](const topsim::Traffic& t) {
    const Steady::rep t0 = t0_ns_.load();
    if (t0 == 0) return;
    const double at =
        std::chrono::duration<double>(Steady::now().time_since_epoch() - Steady::duration(t0))
            .count();
    tap_.take(at, t.dir == '<', t.bytes);
  };
  server_ = std::make_unique<topsim::Server>(std::move(cfg));
  thread_ = std::thread([this] { server_->run(); });
}

DeviceRun::~DeviceRun() { stop(); }

void DeviceRun::stop() {
  if (!thread_.joinable()) return;
  server_->stop();
  thread_.join();
  server_.reset();  // closes the capture
}

std::vector<std::pair<std::string, std::string>> DeviceRun::link_values() const {
  const std::string port =
      kind_ == topsim::TransportKind::pty ? "" : std::to_string(server_->port());
  return {{"pty", server_->pty_path()}, {"host", "127.0.0.1"}, {"port", port}};
}

bool DeviceRun::sample(std::vector<Truth>& out, double t) {
  Truth x;
  x.t = t;
  const bool ok = server_->visit([&x](const topsim::Device& d, std::uint64_t now) {
    const topsim::Axis* axes[3] = {&d.yaw(), &d.pitch(), &d.roll()};
    for (std::size_t i = 0; i < 3; ++i) {
      x.angle[i] = axes[i]->angle;
      x.rate[i] = axes[i]->rate_until > now ? axes[i]->rate : 0;
      x.limit_min[i] = axes[i]->min;
      x.limit_max[i] = axes[i]->max;
    }
    for (const topsim::Stream& s : d.streams()) x.streams_on += s.period_us != 0;
  });
  if (ok) out.push_back(x);
  return ok;
}

void DeviceRun::identity(Record& r) {
  const Idents ids = idents_of(model_);
  server_->visit([&](const topsim::Device& d, std::uint64_t) {
    r.version = d.setting(ids.version);
    r.model = d.setting(ids.model);
    r.range_m = d.options().range_m;
  });
}

void write_intents(const std::string& path, const std::vector<Intent>& intents, double offset,
                   bool append, const nlohmann::json* header) {
  std::ofstream f(path, append ? std::ios::app : std::ios::trunc);
  if (header) f << header->dump() << "\n";
  for (const Intent& i : intents) {
    nlohmann::json j = i.line;
    j["t"] = i.t + offset;
    f << j.dump() << "\n";
  }
  f.flush();
  if (!f) throw std::runtime_error(path + ": cannot write the intents file");
}

std::string find_topdump(const std::string& given) {
  if (!given.empty()) return given;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec)
    for (const fs::path& p : {self.parent_path() / "topdump",
                              self.parent_path().parent_path() / "analyzer" / "topdump"})
      if (::access(p.c_str(), X_OK) == 0) return p.string();
  return "topdump";
}

std::vector<Diagnosis> diagnose(const std::string& topdump, top::Model model,
                                const std::string& capture, std::string& note) {
  std::vector<Diagnosis> out;
  std::error_code ec;
  if (!fs::exists(capture, ec) || fs::file_size(capture, ec) == 0) {
    note = "no capture (nothing on the wire)";
    return out;
  }
  // The capture's path and topdump's come from topconf, never the driver:
  // quoted for the shell all the same.
  auto quote = [](const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  const std::string cmd = quote(topdump) + " read --json --dialect " +
                          std::string(top::to_string(top::dialect_of(model))) + " " +
                          quote(capture) + " 2>/dev/null";
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) {
    note = "topdump could not run";
    return out;
  }
  std::string line;
  std::array<char, 8192> buf{};
  std::size_t lines = 0;
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), p)) {
    line += buf.data();
    if (line.empty() || line.back() != '\n') continue;
    ++lines;
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
    line.clear();
    if (!j.is_object()) continue;
    auto add = [&](const nlohmann::json& x) {
      const std::string code = x.value("code", "");
      if (!top::diagnosis_from_string(code)) return;
      for (const Diagnosis& d : out)
        if (d.code == code) return;
      out.push_back(Diagnosis{code, x.value("severity", ""), x.value("message", "")});
    };
    if (j.value("type", "") == "finding") add(j);
    for (const char* key : {"findings", "session"})
      if (j.contains(key) && j[key].is_array())
        for (const auto& x : j[key])
          if (x.is_object()) add(x);
  }
  const int st = ::pclose(p);
  if (lines == 0)
    note = "topdump gave nothing (status " + std::to_string(st) + ", " + topdump + ")";
  return out;
}

}  // namespace topconf::drive::detail

// The cases of topconf drive (docs/DRIVE.md "The cases"): stable IDs, the
// field problem each puts the driver in front of, its source, and what the
// device does in it for a model and link (topsim faults and options) with
// the intents the driver is asked to perform.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "drive/record.hpp"
#include "sim/faults.hpp"
#include "sim/server.hpp"
#include "top/catalog.hpp"

namespace topconf::drive {

struct CaseSpec {
  std::string_view id;       // "2.1"
  std::string_view section;  // "Motion"
  std::string_view title;    // "rate sign"
  std::string_view good;     // what a good driver does
  std::string_view needs;    // "wire", "beliefs", ...
  std::string_view source;   // the field problem's evidence
};

// Every case, in ID order.
std::span<const CaseSpec> cases() noexcept;
const CaseSpec* find_case(std::string_view id) noexcept;
// The cases `sel` names ("2.1", or a section "2"), in ID order; an empty
// `sel`: all. `error` names an ID that matches none.
std::vector<const CaseSpec*> select_cases(const std::vector<std::string>& sel, std::string& error);

// What a case is on one model and link.
struct CaseSetup {
  std::string not_applicable;  // non-empty: informational, with this reason
  topsim::FaultConfig faults;
  topsim::DeviceOptions options;
  std::vector<Intent> intents;
  double duration_s = 3;
  double fault_at = 0, fault_len = 0;  // the fault's time and length (stall, stop, reboot)
};
CaseSetup setup_case(const CaseSpec& c, top::Model model, topsim::TransportKind link, bool full);

// The identifiers of a dialect that the cases and checks name.
struct Idents {
  std::string_view push, stream_switch, version, model, clock, range;
};
Idents idents_of(top::Model m) noexcept;

}  // namespace topconf::drive

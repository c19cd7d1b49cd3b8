// Running a case's steps (private to conf/run/): one attempt of a case,
// step by step, each step sent and its alternatives watched for.
#pragma once

#include <cstdint>
#include <string>

#include "conf/runner.hpp"
#include "expect.hpp"
#include "wire.hpp"

namespace topconf::detail {

enum class Outcome : std::uint8_t { strict, tolerated, fail, error };

struct StepResult {
  Outcome outcome = Outcome::fail;
  std::string reason;
  bool field_form = false;  // tolerated only for a form the field records
};

class CaseRunner {
 public:
  CaseRunner(const Matrix& m, Transport& t, const RunOptions& o, Wire& w)
      : m_(m), t_(t), o_(o), w_(w), matcher_(m) {}

  // Runs the case once: preconditions then steps.
  void attempt(const Case& c, Verdict& v, std::string& reason, bool& field_form);
  StepResult run_step(const Case& c, const Step& s);

 private:
  struct Watch;  // what a step saw (steps.cpp)
  std::uint32_t timeout_for(const Case& c, const Step& s) const;
  void watch(const Step& s, const std::vector<Alternative>& alts, const top::Frame* rq,
             Watch& seen);
  StepResult verdict(const Step& s, const Watch& seen) const;
  StepResult run_readback(const Case& c, const Step& s, const std::string& sent,
                          const top::Frame* rq, std::uint32_t timeout);

  const Matrix& m_;
  Transport& t_;
  const RunOptions& o_;
  Wire& w_;
  Matcher matcher_;
};

}  // namespace topconf::detail

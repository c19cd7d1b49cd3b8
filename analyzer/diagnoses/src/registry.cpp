#include "diagnoses/registry.hpp"

namespace topdump::diag {

// One detector per row of the table.
#define TOPDUMP_DIAGNOSIS_HAS_ITS_DETECTOR(e, code, severity, title, evidence, remedy) \
  static_assert(deciders_of(top::Diagnosis::e) == 1,                                   \
                "diagnosis " code " needs exactly one detector in diag::Detectors");
TOP_DIAGNOSES(TOPDUMP_DIAGNOSIS_HAS_ITS_DETECTOR)
#undef TOPDUMP_DIAGNOSIS_HAS_ITS_DETECTOR

}  // namespace topdump::diag

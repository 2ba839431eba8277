// StepPolicy's defaults that need the full JSON type (step_policy.hpp declares it only).
#include "pipeline/train/step_policy.hpp"

#include "core/config.hpp"

namespace sgnlf::pipeline {

Json StepPolicy::log_fields() { return Json::object(); }

}  // namespace sgnlf::pipeline

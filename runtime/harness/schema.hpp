// The results JSON schema version (results/schema.md). Bump kSchemaVersion on any change that
// renames, removes or changes the meaning of a field; `sgnlf compare` refuses other versions.
#pragma once

namespace sgnlf::harness {

constexpr const char* kSchemaName = "sgnlf.results";
constexpr int kSchemaVersion = 1;

}  // namespace sgnlf::harness

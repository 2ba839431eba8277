// The "Provenance" section of a combined table's markdown (results/schema.md "Combined
// tables"): every source file with its commit, time and command, then per row which
// sequences came from which source and whether their config is today's.
#include <sstream>

#include "core/config.hpp"
#include "harness/markdown.hpp"

namespace sgnlf::harness {
namespace {

std::string short_sha(const Json& sha) {
  return sha.is_string() ? sha.get<std::string>().substr(0, 7) : std::string("?");
}

// "commit X" with "(dirty)" when the checkout had uncommitted files; when the source records
// the binary's own build stamp (build_git_sha, build_git_dirty) and it says more, that too: a
// binary copied aside from a clean commit is still clean while its checkout moves on.
std::string commit_label(const Json& f) {
  const Json git = f.value("git", Json::object());
  const Json sha = git.is_object() ? git.value("sha", Json()) : Json();
  const bool dirty = git.is_object() && git.value("dirty", Json()) == Json(true);
  std::string s = "commit " + short_sha(sha) + (dirty ? " (dirty)" : "");
  const Json bsha = f.value("build_git_sha", Json()), bdirty = f.value("build_git_dirty", Json());
  if (bsha.is_string() && bdirty.is_boolean() && (dirty || bsha != sha))
    s += ", binary of " + std::string(bdirty.get<bool>() ? "dirty " : "clean ") + short_sha(bsha);
  return s;
}

}  // namespace

std::string render_provenance(const Json& r) {
  if (!r.contains("combined_from") || !r["combined_from"].is_object()) return "";
  const Json& cf = r["combined_from"];
  const Json files = cf.value("files", Json::array());
  std::ostringstream o;
  o << "\n## Provenance\n\nThe rows were run apart and combined by `sgnlf merge`"
    << (cf.value("later_wins", false) ? " (--later-wins: a later input replaces an earlier one)" : "")
    << ". Sources:\n\n";
  for (size_t i = 0; i < files.size(); ++i) {
    const Json& f = files[i];
    o << "- [" << i << "] `" << f.value("file", "") << "`: " << commit_label(f)
      << ", " << f.value("created_utc", "") << ", harness config " << f.value("config_hash", "")
      << "; `" << f.value("command", "") << "`\n";
  }
  o << "\n| method | status | sequences (source) | not run | config hash now | stale |\n"
    << "|---|---|---|---|---|---|\n";
  for (const auto& row : r.value("rows", Json::array())) {
    std::string seqs, not_run;
    for (const auto& s : row.value("sequences", Json::array())) {
      std::string src = s.value("source", Json()).dump();
      if (s.contains("runs") && s["runs"].is_array()) {  // several seeds: each seed's source
        src.clear();
        for (const auto& x : s["runs"])
          src += (src.empty() ? "" : ", ") + std::string("seed ") + x.value("seed", Json()).dump() +
                 ": " + x.value("source", s.value("source", Json())).dump();
      }
      seqs += (seqs.empty() ? "" : ", ") + s.value("sequence", "") + " [" + src + "]";
      if (s.value("stale", Json()) == Json(true))
        seqs += " (" + s.value("config_hash", Json()).get<std::string>() + ")";
    }
    for (const auto& n : row.value("sequences_not_run", Json::array()))
      not_run += (not_run.empty() ? "" : ", ") + n.get<std::string>();
    const Json cur = row.value("current_config_hash", Json());
    const Json stale = row.value("stale", Json());
    o << "| " << row.value("label", "") << " | " << row.value("status", "") << " | "
      << (seqs.empty() ? "—" : seqs) << " | " << (not_run.empty() ? "—" : not_run) << " | "
      << (cur.is_string() ? cur.get<std::string>() : "—") << " | "
      << (stale.is_boolean() ? (stale.get<bool>() ? "**stale**" : "no") : "—") << " |\n";
  }
  // A record made before cells were matched per seed has none.
  const auto cell = [](const Json& s) {
    return s.value("method", "") + " / " + s.value("sequence", "") +
           (s.contains("seed") ? " / seed " + s["seed"].dump() : std::string());
  };
  for (const auto& s : cf.value("superseded", Json::array()))
    o << "\n- " << cell(s) << ": source [" << s.value("source", Json()).dump() << "] replaced by ["
      << s.value("by", Json()).dump() << "]";
  for (const auto& s : cf.value("reproduced", Json::array()))
    o << "\n- " << cell(s) << ": source [" << s.value("source", Json()).dump()
      << "] reproduced bit for bit by [" << s.value("by", Json()).dump() << "]";
  if (!cf.value("superseded", Json::array()).empty() || !cf.value("reproduced", Json::array()).empty())
    o << "\n";
  o << "\nStale: a run whose config hash is not the one the method's preset resolves to in the "
       "commit that combined the table (tests/pipeline/config_hashes.json); its numbers are "
       "from an older config.\n";
  return o.str();
}

}  // namespace sgnlf::harness

// The sampler registry (sampler.hpp): name → SamplerKind, the built-in strategies first.
#include <algorithm>
#include <map>

#include "core/error.hpp"
#include "pipeline/model/sampler.hpp"

namespace sgnlf::pipeline {

// The built-in strategies, one per file of samplers/, each described by its function. Listed
// here rather than registered by a static object in its file: the pipeline is a static library,
// whose linker drops a file nothing refers to.
namespace samplers {
SamplerKind uniform(), importance(), terminated(), surface();
}

namespace {

std::map<std::string, SamplerKind>& registry() {
  static std::map<std::string, SamplerKind> kinds = [] {
    std::map<std::string, SamplerKind> k;
    for (const SamplerKind& s : {samplers::uniform(), samplers::importance(),
                                 samplers::terminated(), samplers::surface()})
      k.emplace(s.name, s);
    return k;
  }();
  return kinds;
}

}  // namespace

void register_sampler(const SamplerKind& kind) {
  if (kind.name.empty() || !kind.per_ray || !kind.make)
    throw Error("register_sampler: a strategy needs a name, per_ray and make");
  if (!registry().emplace(kind.name, kind).second)
    throw Error("register_sampler: a sampler named '" + kind.name + "' is registered already");
}

std::vector<std::string> sampler_names() {
  std::vector<std::string> names;
  for (const auto& [name, kind] : registry()) names.push_back(name);
  return names;  // the map's order: sorted
}

const SamplerKind& find_sampler(const std::string& name, const std::string& key,
                                const render::RenderConfig& rc) {
  const auto it = registry().find(name);
  if (it == registry().end()) {
    std::string known;
    for (const auto& n : sampler_names()) known += (known.empty() ? "" : ", ") + n;
    throw ConfigError(key + ": unknown sampler '" + name + "' (registered: " + known + ")");
  }
  if (it->second.check) it->second.check(rc, key);
  return it->second;
}

std::unique_ptr<Sampler> make_sampler(const std::string& name, const std::string& key,
                                      const SamplerContext& context) {
  std::unique_ptr<Sampler> s = find_sampler(name, key, context.render).make(context);
  s->name_ = name;
  return s;
}

}  // namespace sgnlf::pipeline

// ParamLayout: named, aligned slices of one flat parameter buffer.
#include "field/param_layout.hpp"

#include "core/error.hpp"

namespace sgnlf::field {

ParamSlice ParamLayout::add(const std::string& name, size_t count, size_t align) {
  if (align == 0) throw Error("ParamLayout::add('" + name + "'): align must be > 0");
  for (const auto& s : slices_)
    if (s.name == name) throw Error("ParamLayout::add: duplicate slice '" + name + "'");
  const size_t offset = (total_ + align - 1) / align * align;
  slices_.push_back({name, offset, count});
  total_ = offset + count;
  return slices_.back();
}

const ParamSlice& ParamLayout::slice(const std::string& name) const {
  for (const auto& s : slices_)
    if (s.name == name) return s;
  throw Error("ParamLayout: no slice named '" + name + "'");
}

}  // namespace sgnlf::field

#include "model/element_types.hpp"

namespace machdyn::detail {

const ElementType* find_element_type(std::string_view name) {
  for (const ElementType* t : element_types())
    if (name == t->name) return t;
  return nullptr;
}

}  // namespace machdyn::detail
